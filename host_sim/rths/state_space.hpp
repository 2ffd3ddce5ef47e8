#pragma once
/// Linear time-invariant blocks in state-space form and their exact
/// zero-order-hold discretization, for the RTHS's laboratory plant and its
/// compensators.

#include <Eigen/Core>
#include <complex>

namespace mrd::rths {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

/// ẋ = A x + B u, y = C x + D u.
struct ContinuousSystem {
  Matrix a, b, c, d;
};

/// x[k+1] = Φ x[k] + Γ u[k], y[k] = C x[k] + D u[k].
struct DiscreteSystem {
  Matrix phi, gamma, c, d;
  double dt_s = 0.0;
};

/// Exact zero-order hold at step dt_s: [Φ Γ; 0 I] = exp([A B; 0 0]·dt).
/// Throws std::invalid_argument for a non-positive or non-finite step or
/// inconsistent sizes.
DiscreteSystem zero_order_hold(const ContinuousSystem& sys, double dt_s);

/// The steady-state gain C (−A)⁻¹ B + D of a stable continuous system.
Matrix dc_gain(const ContinuousSystem& sys);

/// The frequency response C (jωI − A)⁻¹ B + D at ω rad/s, input j, output i.
std::complex<double> frequency_response(const ContinuousSystem& sys, double omega_rad_s, int out = 0, int in = 0);

/// A discrete system stepped in time (one state vector).
class DiscreteBlock {
 public:
  explicit DiscreteBlock(DiscreteSystem sys);
  /// Output for input u at this step, then advances the state.
  Vector step(const Vector& u);
  /// As above for a single input and the first output.
  double step(double u);
  const Vector& state() const noexcept { return x_; }
  void reset() { x_.setZero(); }

 private:
  DiscreteSystem sys_;
  Vector x_;
};

}  // namespace mrd::rths
