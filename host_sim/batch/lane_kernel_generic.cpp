// The lane kernel for any CPU: 2 lanes a register (SSE2 on x86-64, NEON on
// AArch64), glibc's exp() per lane; the thesis-shape lanes step four register
// sets around two cores of 4 float lanes, the register's width.
#define MRD_BATCH_LANES 2
#define MRD_BATCH_INTERLEAVE 4
#define MRD_BATCH_CORE_LANES 4
#define MRD_BATCH_NS generic
#define MRD_BATCH_FMA_EXP 0
#include "host_sim/batch/lane_kernel.hpp"
#include "host_sim/batch/lane_kernel_any.hpp"
#include "host_sim/batch/core_lanes_kernel.hpp"

namespace mrd::batch {

LaneKernel generic_lane_kernel() noexcept {
  return LaneKernel{"generic", generic::kW * generic::kInterleave, generic::kW, &generic::sense, &generic::advance, &generic::run,
                    &generic::run_without_drift, &generic::exp_n,
                    &generic::any_sense, &generic::any_advance, &generic::any_run,
                    &generic::core_make, &generic::core_destroy, &generic::core_reset, &generic::core_step,
                    &generic::core_run, &generic::core_run_without_drift};
}

}  // namespace mrd::batch
