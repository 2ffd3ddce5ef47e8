#pragma once
/// Exact zero-order-hold discretization of the building (thesis §6.1,
/// Fig. 6.2) and the stepping model the simulator advances.
///
/// With the inputs u = [a_g; F_d] held constant over each step of length T
/// (as the damper force is between controller updates), the sampled states
/// of ż = A z + B u obey exactly
///
/// <pre>
///   z[k+1] = Φ z[k] + Γ u[k],   Φ = e^{A T},   Γ = ∫₀ᵀ e^{A s} ds · B
/// </pre>
///
/// Φ and Γ are read off one matrix exponential of the augmented matrix
///
/// <pre>
///   exp( [A B; 0 0] · T ) = [Φ Γ; 0 I]
/// </pre>
///
/// computed with Eigen's `MatrixFunctions` module (unsupported/), whose
/// `exp()` is the scaling-and-squaring Padé method of Higham (2005).
/// There is no integration error for piecewise-constant inputs; only
/// rounding.

#include <cstdint>
#include <vector>

#include "host_sim/structure/building.hpp"

namespace mrd::structure {

/// Φ and Γ of the zero-order-hold discretization at step `dt_s`.
struct DiscreteModel {
  Matrix phi;
  Matrix gamma;
};

/// Zero-order-hold discretization of `model` at step `dt_s` (s). Throws
/// std::invalid_argument unless `dt_s` is finite and > 0.
DiscreteModel discretize_zoh(const ContinuousModel& model, double dt_s);

/// The building's linear part as a fixed-step discrete-time system. `init()`
/// designs Φ, Γ (allocates); `step()` and the readers allocate nothing and
/// throw nothing.
///
/// Internally the state is kept in real modal coordinates q, z = T q, where
/// the columns of T are the real and imaginary parts of the eigenvectors of A
/// (one pair per underdamped mode). In them Φ is block diagonal,
/// <pre>
///   T⁻¹ Φ T = diag(B_1 … B_N),  B_j = e^{σ_j T}·[cos ω_j T, sin ω_j T; −sin ω_j T, cos ω_j T]
/// </pre>
/// (λ_j = σ_j ± iω_j), so a step costs N 2×2 products plus the inputs
/// instead of a dense 2N×2N product. This is the same exact ZOH solution in
/// another basis: `init()` checks that T⁻¹ Φ T is block diagonal to 1e−12
/// and otherwise (e.g. an overdamped mode) steps with the dense Φ.
///
/// Sums over states are taken in one fixed order (the order Eigen's
/// fixed-size kernels use, see dot_halving and sum_in_order), so that the
/// results do not depend on how the matrices are stored.
///
/// The state z = [x; ẋ] holds displacements (m) and velocities (m/s) of the
/// DOFs relative to the ground.
class DiscreteBuilding {
 public:
  /// At rest, with no DOF, until init().
  DiscreteBuilding() noexcept = default;

  /// Discretizes `params` at step `dt_s` (s) and resets to rest. Throws
  /// std::invalid_argument for invalid parameters or step.
  void init(const BuildingParams& params, double dt_s);

  /// Back to rest (z = 0), held inputs zero, step count zero.
  void reset() noexcept;

  /// Advances one step of dt_s() with the ground acceleration
  /// `ground_accel_m_s2` (m/s²) and the element forces `element_forces_n`
  /// (N, one per force_elements() entry, positive resisting a positive
  /// deformation rate) held constant over the step.
  void step(double ground_accel_m_s2, const double* element_forces_n) noexcept;

  /// The elements whose forces step() takes, ascending (structure::force_elements).
  const std::vector<int>& force_elements() const noexcept { return elements_; }
  /// Number of degrees of freedom.
  int dofs() const noexcept { return dofs_; }

  /// Base displacement relative to the ground, m.
  double base_disp_m() const noexcept { return disp_m(kBaseDof); }
  /// Base velocity relative to the ground, m/s.
  double base_vel_m_s() const noexcept { return vel_m_s(kBaseDof); }
  /// Displacement of DOF `i` relative to the ground, m.
  double disp_m(int i) const noexcept;
  /// Velocity of DOF `i` relative to the ground, m/s.
  double vel_m_s(int i) const noexcept;
  /// Deformation u_e = x_e − x_{e−1} of element `e` (x_{−1} = 0), m.
  double element_deformation_m(int e) const noexcept { return e == 0 ? disp_m(0) : disp_m(e) - disp_m(e - 1); }
  /// Deformation rate of element `e`, m/s.
  double element_rate_m_s(int e) const noexcept { return e == 0 ? vel_m_s(0) : vel_m_s(e) - vel_m_s(e - 1); }

  /// Absolute acceleration ẍ_i + a_g of DOF `i`, m/s², from the equation of
  /// motion at the end of the step just taken: after step() moved z[k] to
  /// z[k+1], this is the acceleration at t_{k+1} approached from the left
  /// (t_{k+1}⁻), i.e. the state z[k+1] with the inputs u[k] held over that step:
  /// <pre>
  ///   ẍ + 1·a_g = −M⁻¹ (K x + C ẋ + Σ_e (e_e − e_{e−1}) F_e)
  /// </pre>
  /// (a_g cancels, so only the held element forces enter). After init(),
  /// reset() or set_state() the held inputs are zero. Nothing is computed
  /// unless asked.
  double abs_accel_m_s2(int i) const noexcept;
  /// All absolute accelerations, m/s², same instant as abs_accel_m_s2(int),
  /// into `out` (dofs() values).
  void abs_accel_m_s2(double* out) const noexcept;

  /// The state [x; ẋ] (m, m/s), relative to the ground.
  Vector state() const;
  /// True when steps run in the block-diagonal modal form (see above).
  bool modal_stepping() const noexcept { return modal_; }
  /// Replaces the state (e.g. an initial condition); held inputs become zero.
  void set_state(const Vector& z) noexcept;

  /// Step length, s (0 before init()).
  double dt_s() const noexcept { return dt_s_; }
  /// Steps taken since init() or reset().
  std::int64_t step_count() const noexcept { return steps_; }
  /// Force held on element force_elements()[k] over the step just taken, N.
  double held_element_force_n(std::size_t k) const noexcept { return held_[k]; }

  const Matrix& phi() const noexcept { return phi_; }
  const Matrix& gamma() const noexcept { return gamma_; }

  /// The stepping form step() uses (see above), for steppers that must
  /// reproduce its arithmetic: rows (2j, 2j+1) of B_j (modal form only).
  const Matrix& modal_blocks() const noexcept { return blocks_; }
  /// T⁻¹ Γ (Γ when stepping densely).
  const Matrix& stepping_gamma() const noexcept { return gamma_q_; }
  /// T, with z = T q (I when stepping densely).
  const Matrix& modal_basis() const noexcept { return t_; }
  /// Rows N..2N−1 of A times T: ẍ as a function of q.
  const Matrix& accel_rows() const noexcept { return accel_rows_; }
  /// 1 / base mass, 1/kg.
  double inv_base_mass_per_kg() const noexcept { return inv_mass_.size() ? inv_mass_(0) : 0.0; }

 private:
  int dofs_ = 0;
  std::vector<int> elements_;
  Matrix phi_;
  Matrix gamma_;
  Matrix accel_rows_;
  Vector inv_mass_;
  /// z = T q (T = I when stepping densely).
  Matrix t_;
  Matrix t_inv_;
  /// Modal form: rows (2j, 2j+1) of B_j, i.e. [b00 b01; b10 b11] per mode.
  Matrix blocks_;
  /// T⁻¹ Γ (or Γ when stepping densely).
  Matrix gamma_q_;
  bool modal_ = false;
  Vector q_;
  Vector next_;
  std::vector<double> held_;
  double dt_s_ = 0.0;
  std::int64_t steps_ = 0;
};

}  // namespace mrd::structure
