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
///
/// Two plants (PlantKind):
/// - thesis: ideal sensors and drive; the coil current follows the command
///   by Eq. 4.5 (unity DC gain) and sets the damper's field directly.
/// - hardware: the rig of §3.2. The drive and coil are the electrical model
///   (pwm_drive.hpp, coil.hpp: R–L(i) coil, PI current loop, ±72 V, 30 A
///   peak / 15 A continuous, ±10 V command at 1 V/A). Eq. 4.5 is read as the
///   command-to-field response of the whole: its fast branch (0.03 s, weight
///   1/2) is the drive and coil, now the electrical model, and its slow
///   branch (0.7 s, weight 1/2) is the field's lag behind the coil current:
///   i_field = ½ i_coil + ½ i_coil/(0.7 s + 1). The damper force uses
///   i_field; the drive's sensor sees i_coil. Sensors are the rig's
///   (hardware_sensors.hpp), seeded. The damper can be parked off the centre
///   of its stroke (stroke_offset_m): the building is at rest in its
///   equilibrium and the LVDT reads the offset plus the base displacement.
///
/// Both plants heat the coil with the same thermal model (coil_thermal.hpp)
/// and count the same coil figures (coil_figures.hpp).

#include <cstdint>

#include "host_sim/plant/coil_figures.hpp"
#include "host_sim/plant/coil_thermal.hpp"
#include "host_sim/plant/hardware_sensors.hpp"
#include "host_sim/plant/pwm_drive.hpp"
#include "host_sim/plant/stages.hpp"
#include "host_sim/structure/discrete_building.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::plant {

enum class PlantKind { kThesis, kHardware };

/// "thesis" or "hardware".
const char* plant_kind_name(PlantKind k) noexcept;

/// The rig's drive, coil and sensors (used by PlantKind::kHardware only).
struct HardwarePlantSpec {
  CoilParams coil{};
  PwmDriveParams drive{};
  HardwareSensorSpec sensors{};
  double stroke_offset_m = 0.0;  ///< where the damper is parked, off the stroke's centre, m
};

struct PlantSpec {
  double step_s = 1.0e-3;    ///< simulation step, s
  double idle_time_s = 0.0;  ///< idle time before the run, s (sets SQ, Eq. 5.4–5.5)
  PlantKind kind = PlantKind::kThesis;
  structure::BuildingParams building{};
  physics::MrDamperParams damper{};
  physics::SettlingParams settling{};
  CoilThermalParams thermal{};
  HardwarePlantSpec hardware{};
};

/// Time constant that makes Eq. 4.5's fast branch pass its input through
/// within one step: exp(−T/τ) is 0 for any step above 1 µs, s.
inline constexpr double kPassThroughTau_s = 1.0e-9;

/// The damper of the hardware plant: `thesis` with Eq. 4.5's fast branch
/// passing the coil current through, so that the damper's current is the
/// field current ½ i_coil + ½ i_coil/(τ_slow s + 1).
physics::MrDamperParams hardware_damper_params(physics::MrDamperParams thesis) noexcept;

/// Peaks over a run.
struct PlantSummary {
  double peak_base_displacement_m = 0.0;       ///< max |x_b|, relative to the ground
  double peak_damper_force_n = 0.0;            ///< max |F|
  double peak_base_velocity_m_s = 0.0;         ///< max |base velocity relative to the ground| (damper velocity)
  double peak_superstructure_accel_m_s2 = 0.0; ///< max |absolute accel| over floors 1–5
  double peak_base_accel_m_s2 = 0.0;           ///< max |absolute accel| of the base
  double peak_current_a = 0.0;                 ///< max |coil current|
  double final_participant_ratio = 0.0;        ///< PR after the last step (Eq. 5.9)
  double sq = 0.0;                             ///< settling quotient at the start (Eq. 5.5)
  double duration_s = 0.0;                     ///< ticks × step
  std::uint64_t ticks = 0;                     ///< completed ticks (advance() calls)
  CoilFigures coil{};                          ///< coil current, command changes and heating
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
  /// Coil temperature above ambient at the state the last advance() reached, K.
  double coil_temperature_rise_k() const noexcept { return thermal_.rise_k(); }
  /// Current the damper's field follows (the coil current on the thesis plant), A.
  double field_current_a() const noexcept { return damper_.current_a(); }
  /// The building at the state the last advance() reached (floor displacements).
  const structure::DiscreteBuilding& building() const noexcept { return building_; }

 private:
  PlantSpec spec_{};
  structure::DiscreteBuilding building_{};
  physics::MrDamper damper_{};
  structure::Vector6 accel_{};
  double floor_peak_m_s2_ = 0.0;
  PlantState state_{};
  PlantSummary s_{};
  CoilThermal thermal_{};
  CoilFigureCounter figures_{};
  PwmDrive drive_{};
  HardwareSensors sensors_{};
};

}  // namespace mrd::plant
