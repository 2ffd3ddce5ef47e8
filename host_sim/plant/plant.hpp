#pragma once
/// The simulated world the controller acts on: the 6-DOF base-isolated
/// building (Table 6.1) and, between ground and base, the MR damper with
/// idle-time effects and coil dynamics. Every closed loop steps it the same
/// way: `mrd sim`, the sweeps and the study (run::run_closed_loop) and the
/// DAQ + plant node on CAN (peers::PlantNode).
///
/// Tick n (step T, inputs held over the step, ZOH-exact structure):
/// <pre>
///   sense(a_g[n]):    x_b[n], v_b[n], F[n] = damper(v_b[n], i[n], PR[n]),
///                     accelerations, i[n]; sensor stage → PlantSensors
///   advance(drive):   command stage → u[n];
///                     i[n+1], PR[n+1] from u[n] and |v_b[n]|   (Eq. 4.5, 5.9)
///                     z[n+1] = Φ z[n] + Γ [a_g[n], F[n]]
/// </pre>
/// The coil dynamics are strictly proper, so F[n] does not depend on u[n]
/// and there is no algebraic loop. The sensor and command stages are in
/// host_sim/plant/stages.hpp.

#include <cstdint>

#include "host_sim/plant/stages.hpp"
#include "host_sim/structure/discrete_building.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::plant {

struct PlantSpec {
  double step_s = 1.0e-3;    ///< simulation step, s
  double idle_time_s = 0.0;  ///< idle time before the run, s (sets SQ, Eq. 5.4–5.5)
  structure::BuildingParams building{};
  physics::MrDamperParams damper{};
  physics::SettlingParams settling{};
};

/// Peaks over a run.
struct PlantSummary {
  double peak_base_displacement_m = 0.0;       ///< max |x_b|, relative to the ground
  double peak_damper_force_n = 0.0;            ///< max |F|
  double peak_superstructure_accel_m_s2 = 0.0; ///< max |absolute accel| over floors 1–5
  double peak_base_accel_m_s2 = 0.0;           ///< max |absolute accel| of the base
  double peak_current_a = 0.0;                 ///< max |coil current|
  double final_participant_ratio = 0.0;        ///< PR after the last step (Eq. 5.9)
  double sq = 0.0;                             ///< settling quotient at the start (Eq. 5.5)
  double duration_s = 0.0;                     ///< ticks × step
  std::uint64_t ticks = 0;                     ///< completed ticks (advance() calls)
};

class Plant {
 public:
  /// Designs the building at spec.step_s, at rest, and sets the damper's
  /// settling quotient from spec.idle_time_s (Eq. 5.4–5.5). Throws
  /// std::invalid_argument for a bad step.
  void init(const PlantSpec& spec);

  /// Starts tick n: takes the state at t_n with the ground acceleration
  /// `ground_accel_m_s2` (held over the step) and returns what the sensors
  /// measure of it.
  PlantSensors sense(double ground_accel_m_s2) noexcept;

  /// Completes tick n: advances to t_{n+1} with `drive` held over the step.
  void advance(const CoilDrive& drive) noexcept;

  /// The state sense() took at t_n.
  const PlantState& state() const noexcept { return state_; }
  /// Absolute roof acceleration at the state the last advance() reached, m/s².
  double roof_accel_m_s2() const noexcept { return accel_(structure::kDofs - 1); }
  /// Largest |absolute acceleration| over floors 1–5 at that state, m/s².
  double peak_floor_accel_m_s2() const noexcept { return floor_peak_m_s2_; }

  /// Peaks so far, including the state reached by the last advance().
  PlantSummary summary() const noexcept;

  double step_s() const noexcept { return spec_.step_s; }

 private:
  PlantSpec spec_{};
  structure::DiscreteBuilding building_{};
  physics::MrDamper damper_{};
  structure::Vector6 accel_{};
  double floor_peak_m_s2_ = 0.0;
  PlantState state_{};
  PlantSummary s_{};
};

}  // namespace mrd::plant
