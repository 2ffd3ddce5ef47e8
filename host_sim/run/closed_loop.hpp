#pragma once
/// Closed-loop earthquake run: the 6-DOF base-isolated building (Table 6.1),
/// the MR damper with idle-time effects and coil dynamics between ground and
/// base, and a controller, all at one fixed step.
///
/// Per tick n (step T, inputs held over the step, ZOH-exact structure):
///  1. sensors: damper stroke x_b[n], damper force F[n] = damper(v_b[n], i[n], PR[n]),
///     ground and absolute base acceleration, coil current i[n];
///  2. controller: u[n] = step(input);
///  3. damper: i[n+1], PR[n+1] from u[n] and |v_b[n]| (Eq. 4.5, 5.9);
///  4. structure: z[n+1] = Φ z[n] + Γ [a_g[n], F[n]].
/// The coil dynamics are strictly proper, so F[n] does not depend on u[n]
/// and there is no algebraic loop.

#include <string>
#include <vector>

#include "mrd/control/io.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/settling.hpp"
#include "host_sim/structure/discrete_building.hpp"

namespace mrd::run {

class Controller;

struct ClosedLoopSpec {
  double step_s = 1.0e-3;
  double idle_years = 0.0;
  structure::BuildingParams building{};
  physics::MrDamperParams damper{};
  physics::SettlingParams settling{};
};

struct ClosedLoopSummary {
  double peak_base_displacement_m = 0.0;       ///< max |x_b|, relative to the ground
  double peak_damper_force_n = 0.0;            ///< max |F|
  double peak_superstructure_accel_m_s2 = 0.0; ///< max |absolute accel| over floors 1–5
  double peak_base_accel_m_s2 = 0.0;           ///< max |absolute accel| of the base
  double peak_current_a = 0.0;                 ///< max |coil current|
  double final_participant_ratio = 0.0;
  double sq = 0.0;
  double duration_s = 0.0;
};

/// Time series at every step (optional; the sweep runs without it).
struct ClosedLoopRecord {
  std::vector<double> time_s, ground_accel_m_s2, base_disp_m, base_vel_m_s, damper_force_n, desired_force_n,
      command_a, current_a, pr, roof_accel_m_s2, peak_floor_accel_m_s2;
};

/// Runs the loop over `ground_accel_m_s2` sampled at `spec.step_s`.
ClosedLoopSummary run_closed_loop(const ClosedLoopSpec& spec, const std::vector<double>& ground_accel_m_s2,
                                  Controller& controller, ClosedLoopRecord* record = nullptr);

}  // namespace mrd::run
