#pragma once
/// What a building is, as the user describes it (a building file, README
/// "Your building"): a planar shear building of N lumped masses on a chain of
/// N elements, optionally isolated on nonlinear bearings, with MR dampers in
/// parallel with chosen elements. The thesis building (§6.1, Table 6.1,
/// Fig. 6.2) is the default value of every field.
///
/// Degrees of freedom: 0 is the lowest mass (the base of an isolated
/// building, the first floor of a fixed-base one), N−1 the roof. x_i is the
/// displacement of mass i relative to the ground. Element i joins DOF i to
/// DOF i−1; element 0 joins DOF 0 to the ground. Element i's deformation is
/// u_i = x_i − x_{i−1} (u_0 = x_0).
///
/// <pre>
///   M ẍ + C ẋ + K x = −M·1·a_g − Σ_isolators e_0 F_iso − Σ_dampers count·(e_e − e_{e−1}) F_d
/// </pre>
///
/// (e_{−1} = 0). Isolators act in parallel with element 0:
/// - lead-rubber bearing:  F = count·(k_p·u_0 + Q·z)
/// - friction pendulum:    F = count·(W/R·u_0 + μ(u̇_0)·W·z),
///                         μ(v) = μ_fast − (μ_fast − μ_slow)·exp(−a·|v|)
/// with the Bouc–Wen variable ż = (u̇_0/D_y)·(1 − |z|ⁿ·(γ·sgn(u̇_0 z) + β)),
/// β = γ = ½.

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace mrd::structure {

/// β = γ of the isolators' Bouc–Wen variable (building file format).
inline constexpr double kBoucWenBeta = 0.5;
inline constexpr double kBoucWenGamma = 0.5;

/// A group of identical lead-rubber bearings (values per bearing).
struct LeadRubberBearing {
  unsigned count = 1;
  double characteristic_strength_n = 0.0;  ///< Q, the force at zero displacement on the hysteresis, N
  double post_yield_stiffness_n_m = 0.0;   ///< k_p, N/m
  double yield_displacement_m = 0.0;       ///< D_y of the Bouc–Wen variable, m
  double exponent = 2.0;                   ///< n of the Bouc–Wen variable
  double displacement_capacity_m = 0.0;    ///< beyond it a run warns; 0: not given
};

/// A group of identical friction-pendulum bearings (values per bearing).
struct FrictionPendulumBearing {
  unsigned count = 1;
  double radius_m = 0.0;               ///< R of the sliding surface, m (period 2π√(R/g))
  double friction_slow = 0.0;          ///< μ at zero sliding velocity
  double friction_fast = 0.0;          ///< μ at high sliding velocity
  double rate_s_per_m = 0.0;           ///< a of μ(v), s/m
  double yield_displacement_m = 0.0;   ///< D_y of the Bouc–Wen variable, m
  double exponent = 2.0;               ///< n of the Bouc–Wen variable
  double weight_n = 0.0;               ///< load per bearing, N; 0: the building's weight / count
  double displacement_capacity_m = 0.0;///< beyond it a run warns; 0: not given
};

using Isolator = std::variant<LeadRubberBearing, FrictionPendulumBearing>;

/// C = a0·M + a1·K, the ratio exact at two undamped modes of (M, K) (1-based).
struct RayleighDamping {
  double ratio = 0.02;
  int mode_a = 1;
  int mode_b = 2;
};

/// Identical MR dampers in parallel with one element (each sees its deformation).
struct DamperPlacement {
  unsigned element = 0;
  unsigned count = 1;
};

/// Whether DOF 0 is the base of an isolated building or the first floor of a
/// fixed-base one. It decides which elements are stories (fixed: all; isolated:
/// 1..N−1) and which masses are the superstructure (fixed: all; isolated:
/// 1..N−1). The equations are the same.
enum class BaseKind { kIsolated, kFixed };

/// Lumped masses, element dampers and springs, bearings and dampers, SI.
/// Defaults: the thesis building (Table 6.1 and Fig. 6.2):
/// - masses from Fig. 6.2 (Table 6.1 rounds the floors to 212.3 t);
/// - damping from Table 6.1, except floor 1 which Fig. 6.2 gives to one more
///   digit (C(0,1) = −1.0444e6 kg/s; the table says 1,044 kN·s/m);
/// - stiffness from Table 6.1, except the base which Fig. 6.2 gives to one
///   more digit (K(0,0) = 408,071.3 kN/m = 3,287.3 + 404,784; the table says
///   3,287 kN/m);
/// - the isolation layer linear (its spring and dashpot are element 0), one
///   damper in parallel with it.
struct BuildingParams {
  std::string name = "thesis-6dof";
  BaseKind base = BaseKind::kIsolated;
  /// Lumped masses, kg: DOF 0 first (Fig. 6.2).
  std::vector<double> mass_kg{244800.0, 212292.0, 212292.0, 212292.0, 212292.0, 212292.0};
  /// Element stiffnesses, N/m (Table 6.1, Fig. 6.2). Element 0 may be 0 when
  /// isolators carry the restoring force.
  std::vector<double> story_stiffness_n_m{3287.3e3, 404784.0e3, 349116.0e3, 343452.0e3, 299448.0e3, 228708.0e3};
  /// Element dashpots, N·s/m (Table 6.1, Fig. 6.2); unused when `rayleigh` is set.
  std::vector<double> story_damping_n_s_m{209.8e3, 1044.4e3, 904.1e3, 888.5e3, 779.4e3, 592.4e3};
  std::optional<RayleighDamping> rayleigh;
  std::vector<Isolator> isolators;
  std::vector<DamperPlacement> dampers{DamperPlacement{}};
  /// A full stiffness matrix K, N/m, N×N row-major (a condensed frame, whose
  /// floors are not a chain): when not empty it replaces the shear chain of
  /// story_stiffness_n_m, which then holds the chain seen from it
  /// (k_i = −K(i,i−1) for i ≥ 1, k_0 = K(0,0) − k_1) for the readers that
  /// need one element's stiffness. No isolators with it.
  std::vector<double> stiffness_matrix_n_m;
  /// A full damping matrix C, N·s/m, N×N row-major: when not empty it replaces
  /// the element dashpots (and excludes `rayleigh`).
  std::vector<double> damping_matrix_n_s_m;

  /// Number of degrees of freedom.
  int dofs() const noexcept { return static_cast<int>(mass_kg.size()); }
};

/// Largest number of degrees of freedom a building may have.
inline constexpr int kMaxDofs = 200;

}  // namespace mrd::structure
