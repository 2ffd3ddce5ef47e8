#pragma once
/// The simulated world the controller acts on: the building (any shear
/// building of structure/building_params.hpp; the thesis's 6-DOF base-isolated
/// building by default) with its isolators and, in parallel with the chosen
/// elements, the MR dampers with idle-time effects and coil dynamics. Every
/// closed loop steps it the same way: `mrd sim`, the sweeps and the study
/// (run::run_closed_loop) and the DAQ + plant node on CAN (peers::PlantNode).
///
/// Tick n (step T, inputs held over the step, ZOH-exact linear structure):
/// <pre>
///   sense(a_g[n]):    x_b[n], v_b[n], F[n] = damper(v_b[n], x_b[n], i[n], PR[n]),
///                     accelerations, i[n]; sensor stage → PlantSensors
///   advance(drive):   command stage → u[n];
///                     i[n+1], PR[n+1] from u[n] and |v_b[n]|   (Eq. 4.5, 5.9)
///                     z[n+1] = Φ z[n] + Γ [a_g[n], F[n]]
/// </pre>
/// The coil dynamics are strictly proper, so F[n] does not depend on u[n]
/// and there is no algebraic loop. The sensor and command stages are in
/// host_sim/plant/stages.hpp.
///
/// Every damper gets the one controller's command; the controller senses the
/// first damper (building_params.hpp's dampers[0]): x_b and v_b are its
/// element's deformation and rate (the base relative to the ground for a
/// damper on element 0), F its force. Each damper has its own participant
/// ratio and coil state and sees its own element's deformation rate and
/// deformation (its stroke, which the Bouc–Wen law of a calibrated damper
/// uses; the Bingham laws ignore it); `count` identical dampers act as one
/// of count times the force. The force law is spec.damper.law
/// (physics::MrDamper: the thesis's Eq. 4.4 or a calibrated law); the coil
/// figures' "above rated" is spec.damper.rating.current_a.
///
/// Isolators: their linear parts are in the structure's K; their hysteretic
/// forces (structure/isolators.hpp) change within a tick, so a building with
/// isolators is stepped in `substeps` equal sub-steps (ZOH-exact at T/s each):
/// at each, the hysteretic force is taken at the sub-step's start and held,
/// and the Bouc–Wen variables follow the isolation layer's displacement
/// increment. s is the smallest integer with T/s ≤ 0.2 ms and
/// T/s · ω_0 ≤ 0.1, ω_0 = √(k_0/m_0) with k_0 the isolators' largest tangent
/// stiffness (Q/D_y, μ_fast·W/D_y) and m_0 the base mass: the pre-yield
/// oscillation the explicit hold must resolve. The dampers' forces are held
/// over the whole tick (they change with the tick's command). Without
/// isolators s = 1 and a tick is one exact step.
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
#include <vector>

#include "host_sim/plant/coil_figures.hpp"
#include "host_sim/plant/coil_thermal.hpp"
#include "host_sim/plant/hardware_sensors.hpp"
#include "host_sim/plant/pwm_drive.hpp"
#include "host_sim/plant/stages.hpp"
#include "host_sim/structure/discrete_building.hpp"
#include "host_sim/structure/isolators.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::plant {

enum class PlantKind { kThesis, kHardware };

/// "thesis" or "hardware".
const char* plant_kind_name(PlantKind k) noexcept;

/// The rig's drive, coil and sensors (used by PlantKind::kHardware only).
struct HardwarePlantSpec {
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
  double peak_base_displacement_m = 0.0;       ///< max |x_0|, relative to the ground
  double peak_damper_force_n = 0.0;            ///< max |F| of the first damper (one damper)
  double peak_base_velocity_m_s = 0.0;         ///< max |rate of the first damper's element| (damper velocity)
  double peak_superstructure_accel_m_s2 = 0.0; ///< max |absolute accel| over the superstructure (DOFs 1..N−1; fixed base: all)
  double peak_base_accel_m_s2 = 0.0;           ///< max |absolute accel| of DOF 0
  double peak_current_a = 0.0;                 ///< max |coil current|
  double peak_isolator_force_n = 0.0;          ///< max |Σ isolator forces, counts included| (0 without isolators)
  double peak_story_drift_m = 0.0;             ///< max |element deformation| over the stories (elements 1..N−1; fixed base: all)
  double peak_damper_stroke_m = 0.0;           ///< max |deformation of the first damper's element|
  double final_participant_ratio = 0.0;        ///< PR after the last step (Eq. 5.9)
  double sq = 0.0;                             ///< settling quotient at the start (Eq. 5.5)
  double duration_s = 0.0;                     ///< ticks × step
  std::uint64_t ticks = 0;                     ///< completed ticks (advance() calls)
  CoilFigures coil{};                          ///< coil current, command changes and heating
};

/// Structural sub-steps per tick of `step_s` for `building` (see above).
int structural_substeps(const structure::BuildingParams& building, double step_s);

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
  double roof_accel_m_s2() const noexcept { return accel_.back(); }
  /// Largest |absolute acceleration| over the superstructure at that state, m/s².
  double peak_floor_accel_m_s2() const noexcept { return floor_peak_m_s2_; }
  /// Isolators' whole force at that state, N (0 without isolators).
  double isolator_force_n() const noexcept { return isolator_force_n_; }
  /// Deformation of element `e` at that state, m.
  double element_deformation_m(int e) const noexcept { return building_.element_deformation_m(e); }
  /// First story element (1 on an isolated base, 0 on a fixed one).
  int first_story() const noexcept { return first_story_; }

  /// Peaks so far, including the state reached by the last advance().
  PlantSummary summary() const noexcept;

  double step_s() const noexcept { return spec_.step_s; }
  /// Structural sub-steps per tick (1 without isolators).
  int substeps() const noexcept { return substeps_; }
  /// Coil temperature above ambient at the state the last advance() reached, K.
  double coil_temperature_rise_k() const noexcept { return thermal_.rise_k(); }
  /// Current the first damper's field follows (the coil current on the thesis plant), A.
  double field_current_a() const noexcept { return dampers_.front().current_a(); }
  /// The building at the state the last advance() reached (floor displacements).
  const structure::DiscreteBuilding& building() const noexcept { return building_; }

 private:
  void add_peaks_after_advance() noexcept;

  PlantSpec spec_{};
  structure::DiscreteBuilding building_{};
  structure::IsolatorBank isolators_{};
  /// One damper model per placement (spec.building.dampers), the first sensed.
  std::vector<physics::MrDamper> dampers_;
  std::vector<double> damper_force_n_;   ///< force of one damper of each placement over the tick, N
  std::vector<double> element_force_n_;  ///< per building_.force_elements(), N
  std::vector<int> damper_slot_;         ///< placement → index into element_force_n_
  std::vector<char> damper_first_on_slot_;  ///< placement is the first on its element
  int isolator_slot_ = -1;               ///< element 0's index into element_force_n_, or −1
  int substeps_ = 1;
  int first_story_ = 1;
  std::vector<double> accel_;
  double floor_peak_m_s2_ = 0.0;
  double isolator_force_n_ = 0.0;
  PlantState state_{};
  PlantSummary s_{};
  CoilThermal thermal_{};
  CoilFigureCounter figures_{};
  PwmDrive drive_{};
  HardwareSensors sensors_{};
};

}  // namespace mrd::plant
