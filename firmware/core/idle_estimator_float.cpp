// The float build of the idle-time estimator (num::Float32Policy). This file is also
// what the Cortex-M4 cross-compile check builds.
#include "firmware/core/idle_estimator_impl.hpp"

namespace mrd::fw {
template class BasicIdleModel<num::Float32Policy>;
template class BasicIdleEstimator<num::Float32Policy>;
}  // namespace mrd::fw
