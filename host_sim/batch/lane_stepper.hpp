#pragma once
/// What the lane steppers (the thesis-shape lanes in batch_run.cpp, any
/// building's in any_lanes.hpp) share: a lane's sensed values as the
/// scheduler reads them, the damper's constants as the kernels take them,
/// and the coil figures of a finished run.

#include <cstddef>

#include "host_sim/batch/lane_block.hpp"
#include "host_sim/plant/plant.hpp"

namespace mrd::batch {

/// What an idle lane reads as its ground acceleration, m/s².
inline constexpr double kNoGround = 0.0;

/// One lane at t_n, after sense(): the plant's state as plant::PlantState holds it.
struct LaneSensed {
  double ground_accel_m_s2 = 0.0;  ///< a_g held over the step, m/s²
  double stroke_m = 0.0;           ///< the first damper's element deformation, m
  double rate_m_s = 0.0;           ///< its deformation rate, m/s
  double damper_force_n = 0.0;     ///< one first damper's force, N
  double base_accel_m_s2 = 0.0;    ///< absolute base acceleration, m/s²
  double current_a = 0.0;          ///< coil current, A
  double pr = 0.0;                 ///< the first damper's participant ratio
};

/// The damper, coil and thermal constants of `spec` as the kernels use them
/// (SharedModel's non-building fields), computed as physics::CurrentDynamics
/// and plant::CoilThermal compute theirs.
SharedModel damper_constants(const plant::PlantSpec& spec);

/// What the thesis-shape lanes share on `spec` (a thesis-shape plant:
/// batch_run.cpp's thesis_shape): the building's stepping form, the damper's
/// constants and the peaks' bounds (peak_bounds.hpp).
SharedModel thesis_shared_model(const plant::PlantSpec& spec);

/// plant::CoilFigureCounter::figures from a lane's running sums.
plant::CoilFigures coil_figures(double peak_a, double peak_rise_k, double sum_sq_a2, double ticks_above_rated,
                                double command_changes, std::size_t ticks, double step_s) noexcept;

}  // namespace mrd::batch
