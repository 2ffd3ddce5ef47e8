#pragma once
/// Adaptive explicit Runge–Kutta, the embedded Dormand–Prince 5(4) pair
/// (Dormand & Prince 1980; Hairer, Nørsett & Wanner, Solving ODEs I,
/// Table 5.2): the 5th-order solution is propagated, the 4th-order one
/// estimates the error. Step control on the RMS of err_i / (atol + rtol ·
/// max(|y_i|, |y_new_i|)): accepted when ≤ 1, next step h · 0.9 · err^(−1/5)
/// within ×0.2 … ×5 (no growth right after a rejection), never above h_max.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace ibuild {

struct Dp45Options {
  double rtol = 1e-8;
  double atol = 1e-10;        ///< absolute tolerance, same units as each state
  double h_max_s = 1e-3;      ///< largest step
  double h_first_s = 1e-5;    ///< first trial step
  double h_min_s = 1e-14;     ///< below it the integration gives up (throws)
};

struct Dp45Stats {
  std::size_t accepted = 0;
  std::size_t rejected = 0;
  std::size_t evaluations = 0;
};

/// Integrates y' = f(t, y) from t0 to t1 (t1 > t0), steps ending exactly at
/// t1. `h` is the trial step, updated for the next call (so a caller that
/// integrates piecewise keeps its step). After every accepted step
/// observe(t, y) is called. f has the signature f(double t, const
/// std::vector<double>& y, std::vector<double>& dydt).
template <class Rhs, class Observer>
void integrate_dp45(Rhs& f, double t0, double t1, std::vector<double>& y, double& h, const Dp45Options& o,
                    Dp45Stats& stats, Observer&& observe) {
  static constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
  static constexpr double a21 = 1.0 / 5;
  static constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
  static constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
  static constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
  static constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                          a65 = -5103.0 / 18656;
  static constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784, b6 = 11.0 / 84;
  // 5th-order minus embedded 4th-order weights.
  static constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                          e6 = 22.0 / 525, e7 = -1.0 / 40;

  const std::size_t n = y.size();
  std::vector<double> k1(n), k2(n), k3(n), k4(n), k5(n), k6(n), k7(n), tmp(n), ynew(n);

  double t = t0;
  f(t, y, k1);
  ++stats.evaluations;
  bool last_rejected = false;
  double h_free = h;  // the step the error control asks for, before it is cut to end at t1
  while (t < t1) {
    h_free = std::min(h, o.h_max_s);
    h = std::min(h_free, t1 - t);
    // A step that would leave a sliver shorter than 1e-9 of the span ends at t1 instead.
    if (t1 - (t + h) < 1e-9 * (t1 - t0)) h = t1 - t;
    if (!(h >= o.h_min_s)) throw std::runtime_error("Dormand-Prince: step below h_min at t = " + std::to_string(t));

    for (std::size_t i = 0; i < n; ++i) tmp[i] = y[i] + h * a21 * k1[i];
    f(t + c2 * h, tmp, k2);
    for (std::size_t i = 0; i < n; ++i) tmp[i] = y[i] + h * (a31 * k1[i] + a32 * k2[i]);
    f(t + c3 * h, tmp, k3);
    for (std::size_t i = 0; i < n; ++i) tmp[i] = y[i] + h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
    f(t + c4 * h, tmp, k4);
    for (std::size_t i = 0; i < n; ++i) tmp[i] = y[i] + h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
    f(t + c5 * h, tmp, k5);
    for (std::size_t i = 0; i < n; ++i)
      tmp[i] = y[i] + h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
    const double t_new = (h == t1 - t) ? t1 : t + h;
    f(t_new, tmp, k6);
    for (std::size_t i = 0; i < n; ++i)
      ynew[i] = y[i] + h * (b1 * k1[i] + b3 * k3[i] + b4 * k4[i] + b5 * k5[i] + b6 * k6[i]);
    f(t_new, ynew, k7);
    stats.evaluations += 6;

    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double err = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
      const double scale = o.atol + o.rtol * std::max(std::fabs(y[i]), std::fabs(ynew[i]));
      sum += (err / scale) * (err / scale);
    }
    const double err = n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
    if (!std::isfinite(err)) throw std::runtime_error("Dormand-Prince: non-finite state at t = " + std::to_string(t));

    if (err <= 1.0) {
      t = t_new;
      y.swap(ynew);
      k1.swap(k7);  // first same as last
      ++stats.accepted;
      observe(t, y);
      const double grow = err > 0.0 ? 0.9 * std::pow(err, -0.2) : 5.0;
      const bool cut = h < h_free;
      h *= last_rejected ? std::min(1.0, grow) : std::clamp(grow, 0.2, 5.0);
      if (cut && t >= t1) h = std::max(h, h_free);  // the next call starts from the uncut step
      last_rejected = false;
    } else {
      ++stats.rejected;
      h *= std::max(0.2, 0.9 * std::pow(err, -0.2));
      last_rejected = true;
    }
  }
}

}  // namespace ibuild
