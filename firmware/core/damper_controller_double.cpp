// The double-precision build of the control core (fw::Float64Policy): the
// host's reference for the float and fixed-point builds, never on a board.
#include "firmware/core/damper_controller.hpp"

namespace mrd::fw {
template class DamperController<Float64Policy>;
}  // namespace mrd::fw
