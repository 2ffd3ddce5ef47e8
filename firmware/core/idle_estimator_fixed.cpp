// The fixed build of the idle-time estimator (num::Fixed32Policy). This file is also
// what the Cortex-M4 cross-compile check builds.
#include "firmware/core/idle_estimator_impl.hpp"

namespace mrd::fw {
template class BasicIdleModel<num::Fixed32Policy>;
template class BasicIdleEstimator<num::Fixed32Policy>;
}  // namespace mrd::fw
