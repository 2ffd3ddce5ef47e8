#pragma once
/// The 5-story base-isolated building of thesis §6.1 as a 6-DOF lumped-mass
/// shear building (Table 6.1, Fig. 6.2), and its continuous state-space form.
///
/// Degrees of freedom: 0 = base (isolation layer), 1..5 = floors 1..5.
/// x_i is the displacement of mass i relative to the ground, positive in the
/// direction of positive ground motion. With the MR damper between the ground
/// and the base:
///
/// <pre>
///   M ẍ + C ẋ + K x = −M·1·a_g − e_0·F_d
/// </pre>
///
/// a_g is the ground acceleration (m/s²), e_0 = [1 0 0 0 0 0]ᵀ, and F_d the
/// damper force (N), positive when it resists a positive base velocity
/// relative to the ground (so a passive viscous damper would be F_d = c·ẋ_0).
/// Fig. 6.2 is this equation without the damper term.

#include <Eigen/Core>
#include <array>

namespace mrd::structure {

/// Number of degrees of freedom (base + 5 floors).
inline constexpr int kDofs = 6;
/// Number of states z = [x; ẋ].
inline constexpr int kStates = 2 * kDofs;
/// Number of inputs u = [a_g; F_d].
inline constexpr int kInputs = 2;
/// Index of the base (isolation layer) DOF.
inline constexpr int kBaseDof = 0;

using Matrix6 = Eigen::Matrix<double, kDofs, kDofs>;
using Vector6 = Eigen::Matrix<double, kDofs, 1>;
using StateMatrix = Eigen::Matrix<double, kStates, kStates>;
using InputMatrix = Eigen::Matrix<double, kStates, kInputs>;
using State = Eigen::Matrix<double, kStates, 1>;
using Input = Eigen::Matrix<double, kInputs, 1>;

/// Lumped masses, story dampers and story springs of the building, SI.
///
/// Element i (i = 1..5) of `story_*` connects floor i to the mass below it
/// (floor i−1, or the base for i = 1); element 0 connects the base to the
/// ground (the isolation layer). Defaults are Table 6.1 and Fig. 6.2:
/// - masses from Fig. 6.2 (Table 6.1 rounds the floors to 212.3 t);
/// - damping from Table 6.1, except floor 1 which Fig. 6.2 gives to one more
///   digit (C(0,1) = −1.0444e6 kg/s; the table says 1,044 kN·s/m);
/// - stiffness from Table 6.1, except the base which Fig. 6.2 gives to one
///   more digit (K(0,0) = 408,071.3 kN/m = 3,287.3 + 404,784; the table says
///   3,287 kN/m).
struct BuildingParams {
  /// Lumped masses, kg: base, floors 1..5 (Fig. 6.2).
  std::array<double, kDofs> mass_kg{244800.0, 212292.0, 212292.0, 212292.0, 212292.0, 212292.0};
  /// Story damping coefficients, N·s/m: isolation layer, stories 1..5 (Table 6.1, Fig. 6.2).
  std::array<double, kDofs> story_damping_n_s_m{209.8e3, 1044.4e3, 904.1e3, 888.5e3, 779.4e3, 592.4e3};
  /// Story stiffnesses, N/m: isolation layer, stories 1..5 (Table 6.1, Fig. 6.2).
  std::array<double, kDofs> story_stiffness_n_m{3287.3e3, 404784.0e3, 349116.0e3,
                                                343452.0e3, 299448.0e3, 228708.0e3};
};

/// Throws std::invalid_argument unless every mass and stiffness is finite and
/// positive and every damping coefficient finite and non-negative.
void validate(const BuildingParams& p);

/// Diagonal mass matrix M, kg (Fig. 6.2).
Matrix6 mass_matrix(const BuildingParams& p);

/// Tridiagonal shear-building damping matrix C, N·s/m (Fig. 6.2):
/// C(i,i) = c_i + c_{i+1} (c_6 = 0), C(i,i+1) = C(i+1,i) = −c_{i+1}.
Matrix6 damping_matrix(const BuildingParams& p);

/// Tridiagonal shear-building stiffness matrix K, N/m (Fig. 6.2), same
/// pattern as damping_matrix().
Matrix6 stiffness_matrix(const BuildingParams& p);

/// Sum of the lumped masses, kg.
double total_mass_kg(const BuildingParams& p);

/// Continuous state-space model ż = A z + B u with z = [x; ẋ] (m, m/s) and
/// u = [a_g (m/s²); F_d (N)]:
/// <pre>
///   A = [  0       I    ]      B = [  0       0        ]
///       [ −M⁻¹K  −M⁻¹C  ]          [ −1   −M⁻¹·e_0     ]
/// </pre>
/// (the a_g column is −1 in every acceleration row since M⁻¹·M·1 = 1).
struct ContinuousModel {
  StateMatrix a;
  InputMatrix b;
};

/// Builds A and B from the parameters (validated first).
ContinuousModel continuous_model(const BuildingParams& p);

}  // namespace mrd::structure
