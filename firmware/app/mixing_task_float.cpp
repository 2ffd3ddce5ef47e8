// The float build of the mixing task (num::Float32Policy). This file is also what the
// Cortex-M4 cross-compile check builds.
#include "firmware/app/mixing_task_impl.hpp"

namespace mrd::app {
template class BasicMixingTask<num::Float32Policy>;
}  // namespace mrd::app
