#pragma once
/// Damper velocity from the measured stroke: backward difference through a
/// first-order low-pass (cut-off f_v), in metres per control tick so that no
/// 1/T gain is needed.
/// <pre>
///   d[n] = d[n−1] + β (x[n] − x[n−1] − d[n−1]),   β = 1 − exp(−2π f_v T)
///   v[n] ≈ d[n] / T
/// </pre>
/// ODBDCO uses only its sign (with a deadband), to decide whether the damper
/// can produce the desired force at all. At 30 Hz and 1 kHz the estimate lags
/// the true velocity by about 5 ms at the structure's 0.25 Hz.
///
/// Fixed point: x, d in Q3.28 in the controller's stroke unit s_D m (per
/// tick for d; numeric_formats.hpp, 1 for the thesis), β in Q2.29. The
/// difference of two inputs within the stroke limit (≤ 0.42 s_D) cannot
/// leave Q3.28; β·(…) rounds once to Q3.28 (3.7e−9 s_D m per tick, 3.7e−6
/// m/s for the thesis). Rounding lets d settle up to ±0.5/β LSB (±1.6e−8 m
/// per tick, 1.6e−5 m/s, for the thesis) from the exact value, far below the
/// 6 mm/s direction threshold.

#include <cmath>

#include "firmware/core/numeric_formats.hpp"
#include "mrd/units.hpp"

namespace mrd::fw {

template <class Policy>
class VelocityEstimator {
 public:
  using Disp = typename Formats<Policy>::Disp;
  using Coef = typename Formats<Policy>::Coef;

  void init(double cutoff_hz, double period_s) noexcept {
    beta_ = num::from_double<Coef>(1.0 - std::exp(-2.0 * units::kPi * cutoff_hz * period_s));
    reset();
  }

  void reset() noexcept {
    x_prev_ = Disp{};
    d_ = Disp{};
  }

  /// Restarts from `x` at rest (used at the first sample and after a gap).
  void prime(Disp x) noexcept {
    x_prev_ = x;
    d_ = Disp{};
  }

  /// Restarts the difference at `x` but keeps the estimate (after a gap in
  /// the samples, whose difference would span several ticks).
  void resync(Disp x) noexcept { x_prev_ = x; }

  /// One period: returns the filtered displacement change per tick, m.
  Disp step(Disp x) noexcept {
    const Disp dx = x - x_prev_;
    x_prev_ = x;
    d_ = d_ + num::mul<Disp>(beta_, dx - d_);
    return d_;
  }

  Disp per_tick_m() const noexcept { return d_; }

 private:
  Coef beta_{};
  Disp x_prev_{};
  Disp d_{};
};

}  // namespace mrd::fw
