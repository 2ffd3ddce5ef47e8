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
/// Φ and Γ are read off one matrix exponential of the augmented 14×14 matrix
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

#include "host_sim/structure/building.hpp"

namespace mrd::structure {

/// Φ and Γ of the zero-order-hold discretization at step `dt_s`.
struct DiscreteModel {
  StateMatrix phi;
  InputMatrix gamma;
};

/// Zero-order-hold discretization of `model` at step `dt_s` (s). Throws
/// std::invalid_argument unless `dt_s` is finite and > 0.
DiscreteModel discretize_zoh(const ContinuousModel& model, double dt_s);

/// The building as a fixed-step discrete-time system. `init()` designs Φ, Γ
/// (allocates nothing afterwards); `step()` allocates nothing and throws
/// nothing.
///
/// Internally the state is kept in real modal coordinates q, z = T q, where
/// the columns of T are the real and imaginary parts of the eigenvectors of A
/// (one pair per underdamped mode). In them Φ is block diagonal,
/// <pre>
///   T⁻¹ Φ T = diag(B_1 … B_6),  B_j = e^{σ_j T}·[cos ω_j T, sin ω_j T; −sin ω_j T, cos ω_j T]
/// </pre>
/// (λ_j = σ_j ± iω_j), so a step costs 6 2×2 products plus the inputs
/// instead of a dense 12×12 product. This is the same exact ZOH solution in
/// another basis: `init()` checks that T⁻¹ Φ T is block diagonal to 1e−12
/// and otherwise (e.g. an overdamped mode) steps with the dense Φ.
///
/// The state z = [x; ẋ] holds displacements (m) and velocities (m/s) of the
/// base (DOF 0) and floors 1..5 relative to the ground.
class DiscreteBuilding {
 public:
  /// At rest, with Φ = I and Γ = 0 (stepping does nothing) until init().
  DiscreteBuilding() noexcept;

  /// Discretizes `params` at step `dt_s` (s) and resets to rest. Throws
  /// std::invalid_argument for invalid parameters or step.
  void init(const BuildingParams& params, double dt_s);

  /// Back to rest (z = 0), held inputs zero, step count zero.
  void reset() noexcept;

  /// Advances one step of dt_s() with the ground acceleration `ground_accel_m_s2`
  /// (m/s²) and the damper force `damper_force_n` (N, positive resisting a
  /// positive base velocity) held constant over the step.
  void step(double ground_accel_m_s2, double damper_force_n) noexcept;

  /// Base displacement relative to the ground, m (the damper stroke).
  double base_disp_m() const noexcept { return disp_m(kBaseDof); }
  /// Base velocity relative to the ground, m/s (the damper velocity).
  double base_vel_m_s() const noexcept { return vel_m_s(kBaseDof); }
  /// Displacement of DOF `i` (0 = base, 1..5 = floors) relative to the ground, m.
  double disp_m(int i) const noexcept { return t_.row(i).dot(q_); }
  /// Velocity of DOF `i` relative to the ground, m/s.
  double vel_m_s(int i) const noexcept { return t_.row(kDofs + i).dot(q_); }

  /// Absolute acceleration ẍ_i + a_g of DOF `i`, m/s², from the equation of
  /// motion at the end of the step just taken: after step() moved z[k] to
  /// z[k+1], this is the acceleration at t_{k+1} approached from the left
  /// (t_{k+1}⁻), i.e. the state z[k+1] with the inputs u[k] held over that step:
  /// <pre>
  ///   ẍ + 1·a_g = −M⁻¹ (K x + C ẋ + e_0 F_d)
  /// </pre>
  /// (a_g cancels, so only the held damper force enters). After init(),
  /// reset() or set_state() the held inputs are zero. Costs 12 multiply-adds;
  /// nothing is computed unless asked.
  double abs_accel_m_s2(int i) const noexcept;
  /// All six absolute accelerations, m/s², same instant as abs_accel_m_s2(int).
  Vector6 abs_accel_m_s2() const noexcept;

  /// The state [x; ẋ] (m, m/s), relative to the ground.
  State state() const noexcept { return t_ * q_; }
  /// True when steps run in the block-diagonal modal form (see above).
  bool modal_stepping() const noexcept { return modal_; }
  /// Replaces the state (e.g. an initial condition); held inputs become zero.
  void set_state(const State& z) noexcept;

  /// Step length, s (0 before init()).
  double dt_s() const noexcept { return dt_s_; }
  /// Steps taken since init() or reset().
  std::int64_t step_count() const noexcept { return steps_; }
  /// Damper force held over the step just taken, N.
  double held_damper_force_n() const noexcept { return held_force_n_; }

  const StateMatrix& phi() const noexcept { return phi_; }
  const InputMatrix& gamma() const noexcept { return gamma_; }

  /// The stepping form step() uses (see above), for steppers that must
  /// reproduce its arithmetic: rows (2j, 2j+1) of B_j (modal form only).
  const Eigen::Matrix<double, kStates, 2>& modal_blocks() const noexcept { return blocks_; }
  /// T⁻¹ Γ (Γ when stepping densely).
  const InputMatrix& stepping_gamma() const noexcept { return gamma_q_; }
  /// T, with z = T q (I when stepping densely).
  const StateMatrix& modal_basis() const noexcept { return t_; }
  /// Rows 6..11 of A times T: ẍ as a function of q.
  const Eigen::Matrix<double, kDofs, kStates>& accel_rows() const noexcept { return accel_rows_; }
  /// 1 / base mass, 1/kg.
  double inv_base_mass_per_kg() const noexcept { return inv_base_mass_per_kg_; }

 private:
  StateMatrix phi_;
  InputMatrix gamma_;
  /// Rows 6..11 of A times T: ẍ as a function of q.
  Eigen::Matrix<double, kDofs, kStates> accel_rows_;
  double inv_base_mass_per_kg_ = 0.0;
  /// z = T q (T = I when stepping densely).
  StateMatrix t_;
  StateMatrix t_inv_;
  /// Modal form: rows (2j, 2j+1) of B_j, i.e. [b00 b01; b10 b11] per mode.
  Eigen::Matrix<double, kStates, 2> blocks_;
  /// T⁻¹ Γ (or Γ when stepping densely).
  InputMatrix gamma_q_;
  bool modal_ = false;
  State q_;
  double held_force_n_ = 0.0;
  double dt_s_ = 0.0;
  std::int64_t steps_ = 0;
};

}  // namespace mrd::structure
