// The fixed build of the mixing task (num::Fixed32Policy). This file is also what the
// Cortex-M4 cross-compile check builds.
#include "firmware/app/mixing_task_impl.hpp"

namespace mrd::app {
template class BasicMixingTask<num::Fixed32Policy>;
}  // namespace mrd::app
