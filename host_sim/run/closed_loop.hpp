#pragma once
/// Closed-loop earthquake run: the plant (host_sim/plant/plant.hpp: the
/// 6-DOF base-isolated building of Table 6.1 and the MR damper with idle-time
/// effects and coil dynamics) and a controller, all at one fixed step.
///
/// Per tick n: sensors = plant.sense(a_g[n]); u[n] = controller.step(sensors);
/// plant.advance(u[n]).

#include <vector>

#include "host_sim/plant/plant.hpp"
#include "mrd/control/io.hpp"

namespace mrd::run {

class Controller;

/// Time series at every step (optional; the sweep runs without it). Entry n
/// holds the plant's state at t_n, the controller's output of tick n, and the
/// accelerations the step reached (t_{n+1}); command_a is u[n], the current
/// command the coil follows (0 A while the drive is disabled).
struct ClosedLoopRecord {
  std::vector<double> time_s, ground_accel_m_s2, base_disp_m, base_vel_m_s, damper_force_n, desired_force_n,
      command_a, current_a, pr, roof_accel_m_s2, peak_floor_accel_m_s2;
  /// Isolators' whole force at t_{n+1}, N (empty without isolators).
  std::vector<double> isolator_force_n;
  /// Story elements (1..N−1, fixed base 0..N−1) and their deformations at
  /// t_{n+1}, m: story_drift_m[s][n] is element story_elements[s]'s.
  std::vector<int> story_elements;
  std::vector<std::vector<double>> story_drift_m;
};

/// The drive a controller output asks for: u[n] as the coil stage sees it.
[[nodiscard]] inline plant::CoilDrive coil_drive(const control::ControllerOutput& out) noexcept {
  return plant::CoilDrive{static_cast<double>(out.current_command_a), out.drive_enable};
}

/// Tick n of the loop: sensors = plant.sense(a_g[n]); u[n] = controller.step(sensors); plant.advance(u[n]).
/// Returns u[n]. For loops that observe the plant their own way (run_closed_loop, the fragility runs).
control::ControllerOutput closed_loop_tick(plant::Plant& plant, Controller& controller, double ground_accel_m_s2,
                                           std::size_t tick);

/// Runs the loop over `ground_accel_m_s2` sampled at `spec.step_s`, after
/// resetting `controller`. Throws std::invalid_argument for a bad step.
plant::PlantSummary run_closed_loop(const plant::PlantSpec& spec, const std::vector<double>& ground_accel_m_s2,
                                    Controller& controller, ClosedLoopRecord* record = nullptr);

}  // namespace mrd::run
