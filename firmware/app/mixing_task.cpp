// The double (reference) build of the mixing task.
#include "firmware/app/mixing_task_impl.hpp"

namespace mrd::app {
template class BasicMixingTask<fw::Float64Policy>;
}  // namespace mrd::app
