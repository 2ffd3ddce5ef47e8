#pragma once
/// The building's linear part as matrices, and its continuous state-space
/// form. What a building is (masses, elements, isolators, dampers) is in
/// building_params.hpp; the thesis building (§6.1, Table 6.1, Fig. 6.2) is its
/// default.
///
/// With the linear parts of the isolators (k_p, W/R) folded into K and their
/// hysteretic parts (Q·z, μ·W·z) and the dampers as element forces:
///
/// <pre>
///   M ẍ + C ẋ + K x = −M·1·a_g − Σ_e (e_e − e_{e−1}) F_e
/// </pre>
///
/// F_e is the force of element e's devices (N), positive when it resists a
/// positive deformation rate u̇_e (so a passive viscous damper would be
/// F_e = c·u̇_e), e_{−1} = 0. Fig. 6.2 is this equation without the damper
/// term.

#include <Eigen/Core>
#include <vector>

#include "host_sim/structure/building_params.hpp"

namespace mrd::structure {

/// Index of the base (isolation layer) DOF, and the element between it and the ground.
inline constexpr int kBaseDof = 0;

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

/// Throws std::invalid_argument unless the building is one the equations
/// describe: 1..kMaxDofs masses, finite and positive; element stiffnesses
/// finite, positive (element 0 may be 0 when an isolator restores); damping
/// finite and non-negative, arrays of one length; a Rayleigh form with a ratio
/// in (0, 1) and two distinct modes in 1..N; isolators only on an isolated
/// base, with physical values; dampers on elements 0..N−1, count ≥ 1.
void validate(const BuildingParams& p);

/// Diagonal mass matrix M, kg (Fig. 6.2).
Matrix mass_matrix(const BuildingParams& p);

/// Shear-chain stiffness matrix K, N/m (Fig. 6.2): element stiffnesses plus
/// the isolators' linear parts (count·k_p for a lead-rubber bearing,
/// count·W/R for a friction pendulum) on element 0.
/// K(i,i) = k_i + k_{i+1} (k_N = 0), K(i,i+1) = K(i+1,i) = −k_{i+1}.
/// A building with a full stiffness_matrix_n_m returns that matrix.
Matrix stiffness_matrix(const BuildingParams& p);

/// Damping matrix C, N·s/m: the element dashpots in the pattern of
/// stiffness_matrix(), or Rayleigh C = a0·M + a1·K with the ratio ζ exact at
/// the undamped modes ω_a, ω_b of (M, K):
/// a0 = 2ζ·ω_a·ω_b/(ω_a + ω_b), a1 = 2ζ/(ω_a + ω_b); or the full
/// damping_matrix_n_s_m when given.
Matrix damping_matrix(const BuildingParams& p);

/// Sum of the lumped masses, kg.
double total_mass_kg(const BuildingParams& p);

/// Load on one friction-pendulum bearing of `b`, N: weight_n, or the
/// building's weight g·Σm over the bearings of that group.
double bearing_weight_n(const BuildingParams& p, const FrictionPendulumBearing& b);

/// The elements that carry an input force, ascending: every damper's element,
/// and element 0 when there are isolators. Column 1 + k of B is element
/// force_elements()[k].
std::vector<int> force_elements(const BuildingParams& p);

/// Continuous state-space model ż = A z + B u with z = [x; ẋ] (m, m/s) and
/// u = [a_g (m/s²); F_e (N) for each force element]:
/// <pre>
///   A = [  0       I    ]      B = [  0       0                 ]
///       [ −M⁻¹K  −M⁻¹C  ]          [ −1   −M⁻¹·(e_e − e_{e−1})  ]
/// </pre>
/// (the a_g column is −1 in every acceleration row since M⁻¹·M·1 = 1).
struct ContinuousModel {
  Matrix a;
  Matrix b;
};

/// Builds A and B from the parameters (validated first).
ContinuousModel continuous_model(const BuildingParams& p);

}  // namespace mrd::structure
