#pragma once
/// A planar shear building as the building file describes it, in plain
/// structs of this folder (standard library only), and what follows from it
/// in closed form: the undamped frequencies and mode shapes of (M, K) and the
/// Rayleigh coefficients.
///
/// N lumped masses on a chain of N elements: element i joins DOF i to DOF
/// i−1, element 0 joins DOF 0 to the ground. x_i is DOF i relative to the
/// ground, u_i = x_i − x_{i−1} (u_0 = x_0) element i's deformation.

#include <optional>
#include <string>
#include <vector>

namespace ibuild {

/// Standard gravity, m/s² (the definition, 9.80665).
inline constexpr double kGravity_m_s2 = 9.80665;

/// Whether DOF 0 is the base of an isolated building (stories are elements
/// 1..N−1, the superstructure DOFs 1..N−1) or a fixed-base frame's first
/// floor (every element a story, every DOF the superstructure).
enum class Base { kIsolated, kFixed };

enum class IsolatorKind { kLeadRubber, kFrictionPendulum };

/// A group of `count` identical bearings in parallel with element 0 (values
/// per bearing). Lead-rubber: F = count·(k_p·u_0 + Q·z). Friction pendulum:
/// F = count·(W/R·u_0 + μ(u̇_0)·W·z), μ(v) = μ_fast − (μ_fast − μ_slow)·e^(−a|v|).
struct IsolatorGroup {
  IsolatorKind kind = IsolatorKind::kLeadRubber;
  unsigned count = 1;
  double yield_displacement_m = 0.0;   ///< D_y of the Bouc–Wen variable
  double exponent = 2.0;               ///< n of the Bouc–Wen variable
  // lead-rubber
  double characteristic_strength_n = 0.0;  ///< Q
  double post_yield_stiffness_n_m = 0.0;   ///< k_p
  // friction pendulum
  double radius_m = 0.0;        ///< R
  double friction_slow = 0.0;   ///< μ at rest
  double friction_fast = 0.0;   ///< μ at high velocity
  double rate_s_per_m = 0.0;    ///< a
  double weight_n = 0.0;        ///< W per bearing; 0: the building's weight / count
};

/// `count` identical MR dampers in parallel with one element.
struct DamperGroup {
  int element = 0;
  unsigned count = 1;
};

/// C = a0·M + a1·K with `ratio` exact at the undamped modes mode_a, mode_b (1-based).
struct RayleighSpec {
  double ratio = 0.0;
  int mode_a = 1;
  int mode_b = 2;
};

struct Building {
  std::string name;
  Base base = Base::kIsolated;
  std::vector<double> mass_kg;
  std::vector<double> stiffness_n_m;
  std::vector<double> damping_n_s_m;  ///< element dashpots; empty with Rayleigh damping
  std::optional<RayleighSpec> rayleigh;
  std::vector<IsolatorGroup> isolators;
  std::vector<DamperGroup> dampers;

  int dofs() const { return static_cast<int>(mass_kg.size()); }
};

/// Undamped circular frequencies of (M, K), ascending, rad/s. K is the
/// chain of the elements' stiffnesses (isolators not included). Bisection
/// on the Sturm sequence of the symmetric tridiagonal M^(−½) K M^(−½), to
/// a relative 1e-14.
std::vector<double> undamped_frequencies_rad_s(const Building& b);

/// Mode shape of (M, K) at the undamped frequency `omega_rad_s`, DOF 0 to
/// N−1, scaled to a largest |entry| of 1: the chain's recurrence
/// (K − ω² M) φ = 0 row by row from φ_0 = 1.
std::vector<double> mode_shape(const Building& b, double omega_rad_s);

struct RayleighCoefficients {
  double a0_per_s = 0.0;  ///< mass-proportional part, 1/s
  double a1_s = 0.0;      ///< stiffness-proportional part, s
};

/// ζ(ω) = a0/(2ω) + a1·ω/2 equal to `spec.ratio` at the two modes:
/// a0 = 2ζ ω_a ω_b / (ω_a + ω_b), a1 = 2ζ / (ω_a + ω_b).
RayleighCoefficients rayleigh_coefficients(const Building& b, const RayleighSpec& spec);

/// Total weight of the building, Σ m · g, N.
double total_weight_n(const Building& b);

}  // namespace ibuild
