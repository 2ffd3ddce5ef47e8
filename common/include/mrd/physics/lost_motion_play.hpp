#pragma once
/// The play of a calibrated damper's lost motion at reversals (LawShape's
/// λ, share and band; physics::MrDamper): a hard play of half width h
/// between the stroke x and the side it drives r, and its engagement e[n],
/// the engaged share (r[k+1] − r[k−1])/(x[k+1] − x[k−1]) clamped to [0, 1]
/// averaged over the steps k within ±kLostMotionHalfWindow_s of n, the
/// strokes after x[n] extrapolated at the last step's increment (see
/// mr_damper.hpp). One play per damper; the closed loop's SIMD lanes keep one
/// per lane (host_sim/batch), stepped by this same code.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace mrd::physics {

/// Half the window the lost motion's engagement is averaged over
/// (LawShape), s: discrepancy::kContactHalfWindow_s, which the calibration
/// uses (damper_file.cpp holds the two equal).
inline constexpr double kLostMotionHalfWindow_s = 0.003;
/// The most steps either side of that window: 3 ms at 47.6 µs a step and
/// longer; at a shorter step the window is this many steps.
inline constexpr int kLostMotionMaxHalfSteps = 63;

class LostMotionPlay {
 public:
  /// The window at the step `period_s`, s, and no step yet.
  void init(double period_s) noexcept {
    // discrepancy's windowed_mean: the samples within the half window (and a nanosecond), at least one.
    const double half_steps = period_s > 0.0 ? (kLostMotionHalfWindow_s + 1e-9) / period_s : 1.0;
    lm_half_ = static_cast<int>(std::clamp(half_steps, 1.0, static_cast<double>(kLostMotionMaxHalfSteps)));
    reset();
  }

  /// The play as at reset: no step yet.
  void reset() noexcept {
    lm_x_m_.fill(0.0);
    lm_rod_m_.fill(0.0);
    lm_head_ = 0;
    lm_count_ = 0;
  }

  /// discrepancy::DamperModel's hard play of half width h: the driven side after the stroke reaches x.
  static double play_rod_m(double rod_m, double stroke_m, double h_m) noexcept {
    if (stroke_m - rod_m > h_m) return stroke_m - h_m;
    if (rod_m - stroke_m > h_m) return stroke_m + h_m;
    return rod_m;
  }

  /// e[n] at this step's stroke `stroke_m` with the play's half width
  /// `half_width_m`: the engaged shares of the steps within ±H of this one
  /// (the record's start cuts the window, as the calibration's), the steps
  /// after this one extrapolated at the last increment.
  double engaged_mean(double stroke_m, double half_width_m) const noexcept {
    const int H = lm_half_;
    const double h = half_width_m;
    // Steps n − H − 1 … n + H + 1 at indices 0 … 2H + 2; index H + 1 is this step.
    std::array<double, 2 * kLostMotionMaxHalfSteps + 3> x{}, r{};
    const int now = H + 1;
    const int known = static_cast<int>(std::min<long long>(lm_count_, H + 1));  // committed steps in the window
    for (int back = 1; back <= known; ++back) {
      x[static_cast<std::size_t>(now - back)] = lm_x_m_[ring_at(back)];
      r[static_cast<std::size_t>(now - back)] = lm_rod_m_[ring_at(back)];
    }
    x[static_cast<std::size_t>(now)] = stroke_m;
    r[static_cast<std::size_t>(now)] = rod_now_m(stroke_m, h);
    const double dx_step = lm_count_ > 0 ? stroke_m - lm_x_m_[ring_at(1)] : 0.0;
    for (int j = 1; j <= H + 1; ++j) {
      const auto k = static_cast<std::size_t>(now + j);
      x[k] = stroke_m + j * dx_step;
      r[k] = play_rod_m(r[k - 1], x[k], h);
    }
    // The first step there is (the record's start, or H back).
    const int first = now - static_cast<int>(std::min<long long>(lm_count_, H));
    double sum = 0.0;
    for (int k = first; k <= now + H; ++k) {
      const int a = k > now - known ? k - 1 : k;  // the record's first step has no step before it
      const int b = k + 1;
      const double dx = x[static_cast<std::size_t>(b)] - x[static_cast<std::size_t>(a)];
      const double dr = r[static_cast<std::size_t>(b)] - r[static_cast<std::size_t>(a)];
      double e = 1.0;
      if (std::fabs(dx) > 1e-15) e = std::clamp(dr / dx, 0.0, 1.0);
      else if (dr == 0.0 && h > 0.0) e = 0.0;
      sum += e;
    }
    return sum / static_cast<double>(now + H - first + 1);
  }

  /// Commits this step's stroke and driven side (after the force used them),
  /// the play's half width `half_width_m`.
  void commit(double stroke_m, double half_width_m) noexcept {
    const double rod = rod_now_m(stroke_m, half_width_m);
    lm_x_m_[static_cast<std::size_t>(lm_head_)] = stroke_m;
    lm_rod_m_[static_cast<std::size_t>(lm_head_)] = rod;
    lm_head_ = (lm_head_ + 1) % kLostMotionRing;
    if (lm_count_ < kLostMotionRing) ++lm_count_;
  }

 private:
  /// The play's committed steps, a ring of the last kLostMotionRing: strokes and driven sides, m.
  static constexpr int kLostMotionRing = kLostMotionMaxHalfSteps + 1;
  std::array<double, kLostMotionRing> lm_x_m_{};
  std::array<double, kLostMotionRing> lm_rod_m_{};
  int lm_head_ = 0;         ///< where the next committed step goes
  long long lm_count_ = 0;  ///< steps committed since reset (capped at kLostMotionRing)
  int lm_half_ = 3;         ///< H: steps either side averaged

  /// The committed step `back` steps before this one (1: the last), stroke and driven side.
  std::size_t ring_at(int back) const noexcept {
    return static_cast<std::size_t>((lm_head_ - back + 2 * kLostMotionRing) % kLostMotionRing);
  }

  /// The driven side at this step's stroke (centred on it at the first step).
  double rod_now_m(double stroke_m, double h_m) const noexcept {
    return lm_count_ == 0 ? stroke_m : play_rod_m(lm_rod_m_[ring_at(1)], stroke_m, h_m);
  }
};

}  // namespace mrd::physics
