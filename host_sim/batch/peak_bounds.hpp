#pragma once
/// The thesis-shape lanes' bounds on the floors' absolute accelerations and
/// the story drifts (SharedModel::floor_bound, drift_bound), which let the
/// kernel skip the ticks that cannot raise either peak (add_floor_peaks in
/// lane_kernel.hpp).

#include "host_sim/batch/lane_block.hpp"

namespace mrd::batch {

/// ‖[a b; c d]‖₂, the largest singular value, as
/// (√((a + d)² + (b − c)²) + √((a − d)² + (b + c)²)) / 2: a sum of two
/// non-negative terms, each within a few roundings, also where the two
/// singular values are (nearly) equal, as for a damped mode's block.
double block_norm(double a, double b, double c, double d) noexcept;

/// Sets m.peak_bounds, m.floor_bound and m.drift_bound from the stepping
/// form in `m` (blocks, gamma, accel_rows, disp_rows).
void set_peak_bounds(SharedModel& m) noexcept;

}  // namespace mrd::batch
