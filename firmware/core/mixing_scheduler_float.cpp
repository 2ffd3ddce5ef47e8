// The float build of the mixing scheduler (num::Float32Policy). This file is also what
// the Cortex-M4 cross-compile check builds.
#include "firmware/core/mixing_scheduler_impl.hpp"

namespace mrd::fw {
template class BasicMixingScheduler<num::Float32Policy>;
}  // namespace mrd::fw
