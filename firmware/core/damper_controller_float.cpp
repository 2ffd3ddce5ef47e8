// The float build of the control core (num::Float32Policy). This file is
// also what the Cortex-M4 cross-compile check builds.
#include "firmware/core/damper_controller.hpp"

namespace mrd::fw {
template class DamperController<num::Float32Policy>;
}  // namespace mrd::fw
