#pragma once
/// The equations of motion of a nonlinear shear building in continuous time,
///
///   M ẍ + C ẋ + K x = −M·1·a_g(t) − e_0·Σ_groups F_iso − Σ_dampers count·(e_e − e_{e−1})·F_d,
///
/// with each bearing group's Bouc–Wen variable
///
///   ż = (u̇_0 / D_y)·(1 − |z|ⁿ·(γ·sgn(u̇_0·z) + β)),  β = γ = ½,
///
/// and the MR dampers at a constant current command (constant_current_damper.hpp),
/// each seeing its element's deformation rate u̇_e. State y = [x (N), ẋ (N),
/// z (one per bearing group)], x relative to the ground. C is the element
/// dashpots or a0·M + a1·K.
///
/// simulate_earthquake() integrates it with the adaptive Dormand–Prince 5(4)
/// pair (dormand_prince.hpp), record sample by record sample (a_g is linear
/// in between, so no step straddles a kink of a_g), and keeps the peaks.

#include <cstddef>
#include <vector>

#include "building_model.hpp"
#include "dormand_prince.hpp"
#include "ground_record.hpp"

namespace ibuild {

/// β = γ of the bearings' Bouc–Wen variable.
inline constexpr double kBoucWenBeta = 0.5;
inline constexpr double kBoucWenGamma = 0.5;

/// ż for the deformation rate `velocity_m_s`, 1/s.
double bouc_wen_rate_per_s(double z, double velocity_m_s, double yield_displacement_m, double exponent);

/// μ(v) = μ_fast − (μ_fast − μ_slow)·e^(−a|v|) of a friction pendulum.
double pendulum_friction(const IsolatorGroup& g, double velocity_m_s);

/// The building's forces at one state.
struct Forces {
  std::vector<double> abs_accel_m_s2;  ///< ẍ + a_g = −(restoring forces)/m, per DOF
  double isolator_force_n = 0.0;       ///< Σ over bearing groups, counts included
  std::vector<double> damper_force_n;  ///< one damper of each group
};

class BuildingEquations {
 public:
  /// Throws std::invalid_argument for a building the equations cannot hold
  /// (lengths, element indices, Rayleigh modes).
  explicit BuildingEquations(Building b);

  int dofs() const { return n_; }
  std::size_t state_size() const { return static_cast<std::size_t>(2 * n_) + b_.isolators.size(); }
  const Building& building() const { return b_; }

  /// dy/dt at ground acceleration `ground_accel_m_s2` and coil current `current_a`.
  void derivative(double ground_accel_m_s2, double current_a, const std::vector<double>& y,
                  std::vector<double>& dydt) const;

  /// The forces at state y.
  void forces(double current_a, const std::vector<double>& y, Forces& out) const;

  /// Force of one bearing group (count included) at state y, N.
  double isolator_group_force_n(std::size_t group, const std::vector<double>& y) const;

 private:
  Building b_;
  int n_ = 0;
  RayleighCoefficients rayleigh_{};
  std::vector<double> bearing_weight_n_;  ///< W per bearing of each group (friction pendulum)
  mutable std::vector<double> restoring_n_;

  /// restoring_n_ = C ẋ + K x + isolator and damper forces on each DOF; returns the isolators' sum.
  double restoring_forces(double current_a, const std::vector<double>& y, std::vector<double>* damper_n) const;
};

/// Peaks over a run, with the meanings of mrd's summary.json.
struct Peaks {
  double base_displacement_m = 0.0;        ///< max |x_0|
  double base_velocity_m_s = 0.0;          ///< max |ẋ_0|
  double isolator_force_n = 0.0;           ///< max |Σ bearing forces|
  double damper_force_n = 0.0;             ///< max |force of one damper| over every damper
  double superstructure_accel_m_s2 = 0.0;  ///< max |ẍ_i + a_g|, isolated: i ≥ 1; fixed: every i
  double story_drift_m = 0.0;              ///< max |u_i|, isolated: i ≥ 1; fixed: every i
};

struct RunSpec {
  double duration_s = 0.0;
  double command_a = 0.0;  ///< constant current command from t = 0, coil at 0 A then
  Dp45Options options{};
};

/// Step bounds and tolerances for this building: rtol 1e-8, and a largest
/// step of a fifth of the Bouc–Wen time scale D_y / (1 m/s) of its smallest
/// yield displacement (0.1 ms for D_y = 0.5 mm), at most 0.5 ms.
Dp45Options default_options(const Building& b);

/// The building at rest at t = 0, shaken by `record` (already scaled) for
/// `spec.duration_s`. Peaks are taken at every accepted step.
Peaks simulate_earthquake(const Building& b, const GroundRecord& record, const RunSpec& spec,
                          Dp45Stats* stats = nullptr);

}  // namespace ibuild
