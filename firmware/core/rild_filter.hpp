#pragma once
/// Causal RILD filter (thesis §6.3, Eq. 6.1; Keivan 2017): the desired damper
/// force from the base displacement,
///
///     F_d(s) = H(s) x_b(s),   H(s) = kη (s − ω_f)/(s + ω_f),
///
/// k the isolation stiffness, η the loss factor, ω_f the structure's
/// fundamental circular frequency. Sign convention (SPEC): F_d is positive
/// when it resists positive velocity; at s = iω_f, H = kη·i, so F_d leads x_b
/// by +90°, in phase with the velocity. |H(iω)| = kη at every ω (all-pass);
/// at DC H(0) = −kη.
///
/// Discretization: bilinear (Tustin) transform prewarped at ω_f,
/// s = c (z − 1)/(z + 1) with c = ω_f / tan(ω_f T/2). Tustin maps the unit
/// circle onto the imaginary axis, so the all-pass stays an exact all-pass
/// (|H| = kη at every frequency up to Nyquist), and prewarping puts the exact
/// +90° at ω_f. With θ = ω_f T/2 and the pole a = (1 − tan θ)/(1 + tan θ):
/// <pre>
///   H(z) = kη (a − z⁻¹) / (1 − a z⁻¹)
///   w[n]   = a (w[n−1] + x[n]) − x[n−1]      unit all-pass, m
///   F_d[n] = kη w[n]                          Eq. 6.1, N
/// </pre>
/// The all-pass w is computed with one product, and the numerator and the
/// denominator share the same stored `a`, so quantizing a moves the pole but
/// cannot break |W/X| = 1.
///
/// Strokes are in the controller's unit s_D m and forces in its s_F N
/// (numeric_formats.hpp; `init` takes k·s_D/s_F, k itself for the thesis),
/// so the filter is the same for any damper.
///
/// Fixed point (Formats<Fixed32Policy>): x, w in Q3.28 s_D m, a in Q2.29,
/// kη in Q23.8 s_F/s_D N/m, F_d in Q19.12 s_F N. w + x is a saturating
/// Q3.28 sum; a·(w + x) rounds the 64-bit product once to Q3.28; kη·w
/// rounds once to Q19.12 and saturates at ±524 288 s_F N (the controller
/// then clamps it to the desired-force limit, which s_F makes fit). For a
/// first-order all-pass Σ|h[n]| = a + (1 + a) < 3, so |w| < 3 max|x|: with
/// the input guard's stroke limit at most 0.42 s_D, |w| < 1.3 and
/// |w + x| < 1.7 units, far inside Q3.28 (the thesis: 0.3 m, 0.9 m, 1.2 m).
/// The worst-case accumulated rounding error of w is 2^−29 / (1 − a) units,
/// ≈ 1.2e−6 m at 1 kHz and the thesis's ω_f = 1.58 rad/s (≈ 3 N of force).

#include <cmath>

#include "firmware/core/numeric_formats.hpp"

namespace mrd::fw {

/// Pole a of the prewarped Tustin all-pass for ω_f (rad/s) at period T (s).
inline double rild_pole(double omega_f_rad_s, double period_s) noexcept {
  const double t = std::tan(0.5 * omega_f_rad_s * period_s);
  return (1.0 - t) / (1.0 + t);
}

template <class Policy>
class RildFilter {
 public:
  using Disp = typename Formats<Policy>::Disp;
  using Force = typename Formats<Policy>::Force;
  using Coef = typename Formats<Policy>::Coef;
  using Gain = typename Formats<Policy>::Gain;
  using Mask = typename LaneTypes<Policy>::Mask;

  /// Designs the filter in double and quantizes once. The caller checks the
  /// ranges (ControllerConfig validation): 0 < ω_f T < π, kη representable.
  void init(double stiffness_n_m, double loss_factor, double omega_f_rad_s, double period_s) noexcept {
    pole_ = num::from_double<Coef>(rild_pole(omega_f_rad_s, period_s));
    gain_ = num::from_double<Gain>(stiffness_n_m * loss_factor);
    reset();
  }

  /// Zero state: as if x had been 0 forever (in the lanes of `m`).
  void reset(Mask m = num::all_set<Mask>()) noexcept {
    w_ = num::select(m, Disp{}, w_);
    x_prev_ = num::select(m, Disp{}, x_prev_);
  }

  /// Steady state for a displacement held at `x` forever: w = −x
  /// (DC gain −1), so a constant input gives no transient (in the lanes of `m`).
  void prime(Disp x, Mask m = num::all_set<Mask>()) noexcept {
    w_ = num::select(m, -x, w_);
    x_prev_ = num::select(m, x, x_prev_);
  }

  /// One period: returns F_d[n] for x[n] (the lanes outside `m` keep their state).
  Force step(Disp x, Mask m = num::all_set<Mask>()) noexcept {
    w_ = num::select(m, num::mul<Disp>(pole_, w_ + x) - x_prev_, w_);
    x_prev_ = num::select(m, x, x_prev_);
    return num::mul<Force>(gain_, w_);
  }

  Coef pole() const noexcept { return pole_; }
  Gain gain() const noexcept { return gain_; }
  /// The unit all-pass output w[n], m.
  Disp allpass_m() const noexcept { return w_; }

 private:
  Coef pole_{};
  Gain gain_{};
  Disp w_{};
  Disp x_prev_{};
};

}  // namespace mrd::fw
