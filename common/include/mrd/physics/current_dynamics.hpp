#pragma once
/// Coil-current dynamics of the damper and its PWM drive, Eq. 4.5.
///
/// As printed, Eq. 4.5 is H(s) = 1/(0.7 s + 1) + 1/(0.03 s + 1), whose DC gain
/// is 2: every steady command would produce twice its current. We use
///
///     H(s) = w_slow/(τ_slow s + 1) + w_fast/(τ_fast s + 1),  w_slow = w_fast = 1/2,
///
/// i.e. Eq. 4.5 divided by two, so that a steady command of I amperes gives
/// I amperes. Both branches are discretized exactly for a command held
/// constant over each sample period T (zero-order hold):
///
/// <pre>
///   y_k[n+1] = a_k y_k[n] + (1 − a_k) u[n],   a_k = exp(−T/τ_k)
///   y[n]     = w_slow y_slow[n] + w_fast y_fast[n]
/// </pre>
///
/// The output at sample n depends on commands up to n−1 (strictly proper).

#include <cmath>

namespace mrd::physics {

struct CurrentDynamicsParams {
  double tau_slow_s = 0.7;   ///< Eq. 4.5, first term
  double tau_fast_s = 0.03;  ///< Eq. 4.5, second term
  double weight_slow = 0.5;  ///< unity DC gain: weights sum to 1 (see above)
  double weight_fast = 0.5;
};

class CurrentDynamics {
 public:
  CurrentDynamics() = default;
  CurrentDynamics(const CurrentDynamicsParams& p, double period_s) noexcept { init(p, period_s); }

  void init(const CurrentDynamicsParams& p, double period_s) noexcept {
    p_ = p;
    period_s_ = period_s;
    a_slow_ = std::exp(-period_s / p.tau_slow_s);
    a_fast_ = std::exp(-period_s / p.tau_fast_s);
    reset();
  }

  /// Sets the coil current to a steady value (both branches at rest there).
  void reset(double current_a = 0.0) noexcept { y_slow_ = y_fast_ = current_a; }

  /// Present coil current, A.
  double current_a() const noexcept { return p_.weight_slow * y_slow_ + p_.weight_fast * y_fast_; }

  /// Holds `command_a` for one period and returns the coil current at its end.
  double step(double command_a) noexcept {
    y_slow_ = a_slow_ * y_slow_ + (1.0 - a_slow_) * command_a;
    y_fast_ = a_fast_ * y_fast_ + (1.0 - a_fast_) * command_a;
    return current_a();
  }

  double period_s() const noexcept { return period_s_; }
  double dc_gain() const noexcept { return p_.weight_slow + p_.weight_fast; }

 private:
  CurrentDynamicsParams p_{};
  double period_s_ = 1.0e-3;
  double a_slow_ = 0.0;
  double a_fast_ = 0.0;
  double y_slow_ = 0.0;
  double y_fast_ = 0.0;
};

}  // namespace mrd::physics
