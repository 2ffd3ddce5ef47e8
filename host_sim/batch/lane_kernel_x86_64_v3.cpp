// The lane kernel for x86-64-v3 (AVX2, FMA): 4 lanes a register; the thesis-shape
// lanes step two register sets, so that the core's 8 float lanes all serve a run.
#define MRD_BATCH_LANES 4
#define MRD_BATCH_INTERLEAVE 2
#define MRD_BATCH_NS x86_64_v3
#define MRD_BATCH_FMA_EXP 1
#include "host_sim/batch/lane_kernel.hpp"
#include "host_sim/batch/lane_kernel_any.hpp"
#include "host_sim/batch/core_lanes_kernel.hpp"

namespace mrd::batch {

LaneKernel x86_64_v3_lane_kernel() noexcept {
  return LaneKernel{"x86-64-v3", x86_64_v3::kW * x86_64_v3::kInterleave, x86_64_v3::kW, &x86_64_v3::sense, &x86_64_v3::advance, &x86_64_v3::run,
                    &x86_64_v3::run_without_drift, &x86_64_v3::exp_n,
                    &x86_64_v3::any_sense, &x86_64_v3::any_advance, &x86_64_v3::any_run,
                    &x86_64_v3::core_make, &x86_64_v3::core_destroy, &x86_64_v3::core_reset, &x86_64_v3::core_step,
                    &x86_64_v3::core_run, &x86_64_v3::core_run_without_drift};
}

}  // namespace mrd::batch
