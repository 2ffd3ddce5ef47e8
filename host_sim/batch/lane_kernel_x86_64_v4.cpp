// The lane kernel for x86-64-v4 (AVX-512): 8 lanes.
#define MRD_BATCH_LANES 8
#define MRD_BATCH_NS x86_64_v4
#define MRD_BATCH_FMA_EXP 1
#include "host_sim/batch/lane_kernel.hpp"
#include "host_sim/batch/lane_kernel_any.hpp"
#include "host_sim/batch/core_lanes_kernel.hpp"

namespace mrd::batch {

LaneKernel x86_64_v4_lane_kernel() noexcept {
  return LaneKernel{"x86-64-v4", x86_64_v4::kW * x86_64_v4::kInterleave, x86_64_v4::kW, &x86_64_v4::sense, &x86_64_v4::advance, &x86_64_v4::run,
                    &x86_64_v4::run_without_drift, &x86_64_v4::exp_n,
                    &x86_64_v4::any_sense, &x86_64_v4::any_advance, &x86_64_v4::any_run,
                    &x86_64_v4::core_make, &x86_64_v4::core_destroy, &x86_64_v4::core_reset, &x86_64_v4::core_step,
                    &x86_64_v4::core_run, &x86_64_v4::core_run_without_drift};
}

}  // namespace mrd::batch
