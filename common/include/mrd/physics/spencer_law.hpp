#pragma once
/// Spencer, Dyke, Sain and Carlson (1997), "Phenomenological model for
/// magnetorheological dampers", J. Eng. Mech. 123(3): the modified Bouc–Wen
/// model, numbered as in the paper:
/// <pre>
///   F = c_1 ẏ + k_1 (x − x_0)                                             Eq. (8)
///   ż = −γ |ẋ − ẏ| z |z|^(n−1) − β (ẋ − ẏ) |z|^n + A (ẋ − ẏ)              Eq. (9)
///   ẏ = [α z + c_0 ẋ + k_0 (x − y)] / (c_0 + c_1)                         Eq. (10)
///   α(u), c_1(u), c_0(u) affine in the filtered command u                 Eq. (11)–(13)
///   u̇ = −η (u − v)                                                        Eq. (14)
/// </pre>
/// x is the damper's stroke, y the internal displacement between the
/// Bouc–Wen element with the dashpot c_0 and the dashpot c_1 (the fluid's
/// behaviour at low velocity, the roll-off of the force through a reversal),
/// k_1 the accumulator's spring about x_0, k_0 the stiffness at large
/// velocity. z has the units of a length here (A dimensionless, γ and β in
/// 1/m^n, α in N/m).
///
/// Current laws: the laws of SpencerParams in the coil current i (A), as the
/// laboratory's published fit of its damper gives them: α quadratic, c_0 and
/// c_1 affine (the paper's Eq. (11)–(13) with i in place of u), γ exponential
/// and β = (beta_over_gamma) γ. The paper's first-order filter of Eq. (14)
/// is not part of this law: the current it acts on is the coil's (Eq. 4.5 of
/// the thesis, whose two time constants, equal, are that filter with
/// η = 1/τ), so that one coil model serves every law.
///
/// Integration: the state (y, z) is advanced over a step with the stroke's
/// velocity held (x(s) = x + ẋ s) by classical fourth-order Runge–Kutta on
/// sub-steps no longer than kSpencerStepStiffness over the system's largest
/// rate (spencer_rate_bound_per_s): the z equation is stiff near saturation
/// (some 7500 1/s for the laboratory damper at 0 A), so a 1 ms sample takes
/// one to about ten sub-steps. Pure, allocation-free, exception-free.

#include <algorithm>
#include <cmath>

namespace mrd::physics {

/// The model's coefficients at one current.
struct SpencerCoefficients {
  double alpha_n_m = 0.0;
  double c0_ns_m = 0.0;
  double c1_ns_m = 1.0;
  double gamma_per_m_pow_n = 0.0;
  double beta_per_m_pow_n = 0.0;
  double a = 0.0;  ///< A, dimensionless
  double n = 2.0;
  double k0_n_m = 0.0;
  double k1_n_m = 0.0;
  double x0_m = 0.0;
};

/// The model with its current laws (i in A, its magnitude):
/// <pre>
///   α(i)   = alpha_n_m + alpha_per_a_n_m |i| + alpha_per_a2_n_m i²
///   c_0(i) = c0_ns_m + c0_per_a_ns_m |i|,   c_1(i) = c1_ns_m + c1_per_a_ns_m |i|
///   γ(i)   = gamma_per_m_pow_n exp(−gamma_rate_per_a |i|),   β(i) = beta_over_gamma γ(i)
/// </pre>
/// A participant ratio PR (thesis Eq. 5.10–5.11) scales the part of α, c_0
/// and c_1 the field adds to their value at 0 A, as it scales the
/// field-induced part of the yield force and the viscous coefficient.
struct SpencerParams {
  double alpha_n_m = 0.0;         ///< α at 0 A, N/m
  double alpha_per_a_n_m = 0.0;   ///< N/(m·A)
  double alpha_per_a2_n_m = 0.0;  ///< N/(m·A²)
  double c0_ns_m = 0.0;           ///< c_0 at 0 A, N·s/m
  double c0_per_a_ns_m = 0.0;     ///< N·s/(m·A)
  double c1_ns_m = 0.0;           ///< c_1 at 0 A, N·s/m
  double c1_per_a_ns_m = 0.0;     ///< N·s/(m·A)
  double gamma_per_m_pow_n = 0.0;  ///< γ at 0 A, 1/m^n
  double gamma_rate_per_a = 0.0;   ///< 1/A
  double beta_over_gamma = 1.0;    ///< β/γ
  double a = 300.0;                ///< A
  double n = 2.0;
  double k0_n_m = 0.0;
  double k1_n_m = 0.0;
  double x0_m = 0.0;

  [[nodiscard]] double alpha_at(double current_a) const noexcept {
    const double i = std::fabs(current_a);
    return alpha_n_m + (alpha_per_a_n_m + alpha_per_a2_n_m * i) * i;
  }
  [[nodiscard]] double c0_at(double current_a) const noexcept { return c0_ns_m + c0_per_a_ns_m * std::fabs(current_a); }
  [[nodiscard]] double c1_at(double current_a) const noexcept { return c1_ns_m + c1_per_a_ns_m * std::fabs(current_a); }
  [[nodiscard]] double gamma_at(double current_a) const noexcept {
    return gamma_per_m_pow_n * std::exp(-gamma_rate_per_a * std::fabs(current_a));
  }

  /// The coefficients at a current and participant ratio.
  [[nodiscard]] SpencerCoefficients at(double current_a, double participant_ratio = 1.0) const noexcept {
    SpencerCoefficients c;
    const auto pr = [participant_ratio](double at_zero, double at_i) { return at_zero + participant_ratio * (at_i - at_zero); };
    c.alpha_n_m = pr(alpha_n_m, alpha_at(current_a));
    c.c0_ns_m = pr(c0_ns_m, c0_at(current_a));
    c.c1_ns_m = pr(c1_ns_m, c1_at(current_a));
    c.gamma_per_m_pow_n = gamma_at(current_a);
    c.beta_per_m_pow_n = beta_over_gamma * c.gamma_per_m_pow_n;
    c.a = a;
    c.n = n;
    c.k0_n_m = k0_n_m;
    c.k1_n_m = k1_n_m;
    c.x0_m = x0_m;
    return c;
  }
};

/// The internal displacement y and the evolutionary variable z, m.
struct SpencerState {
  double y_m = 0.0;
  double z_m = 0.0;
};

/// |z|^p for the model's exponents (n = 2, the usual one, without pow).
inline double spencer_abs_pow(double z, double p) noexcept {
  const double az = std::fabs(z);
  if (p == 1.0) return az;
  if (p == 2.0) return az * az;
  if (p == 0.0) return 1.0;
  return std::pow(az, p);
}

/// ẏ, Eq. (10), m/s.
inline double spencer_y_rate(const SpencerCoefficients& c, const SpencerState& s, double x_m,
                             double v_m_s) noexcept {
  return (c.alpha_n_m * s.z_m + c.c0_ns_m * v_m_s + c.k0_n_m * (x_m - s.y_m)) / (c.c0_ns_m + c.c1_ns_m);
}

/// ż, Eq. (9), for the relative velocity u = ẋ − ẏ, m/s.
inline double spencer_z_rate(const SpencerCoefficients& c, double z_m, double u_m_s) noexcept {
  const double zn1 = spencer_abs_pow(z_m, c.n - 1.0);
  const double zn = zn1 * std::fabs(z_m);
  return -c.gamma_per_m_pow_n * std::fabs(u_m_s) * z_m * zn1 - c.beta_per_m_pow_n * u_m_s * zn + c.a * u_m_s;
}

/// F, Eq. (8), N.
inline double spencer_force_n(const SpencerCoefficients& c, const SpencerState& s, double x_m,
                              double v_m_s) noexcept {
  return c.c1_ns_m * spencer_y_rate(c, s, x_m, v_m_s) + c.k1_n_m * (x_m - c.x0_m);
}

/// The largest |z| the variable reaches under steady motion: (A/(β+γ))^(1/n), m
/// (infinite without saturation).
inline double spencer_z_saturation_m(const SpencerCoefficients& c) noexcept {
  const double bg = c.beta_per_m_pow_n + c.gamma_per_m_pow_n;
  return bg > 0.0 && c.n > 0.0 ? std::pow(c.a / bg, 1.0 / c.n) : HUGE_VAL;
}

/// The force the hysteretic element carries once z saturates,
/// α z_sat c_1/(c_0 + c_1), N: the model's analogue of a yield force
/// (with ẏ = (α z + c_0 ẋ)/(c_0 + c_1) and F = c_1 ẏ at steady motion).
inline double spencer_yield_force_n(const SpencerCoefficients& c) noexcept {
  return c.alpha_n_m * spencer_z_saturation_m(c) * c.c1_ns_m / (c.c0_ns_m + c.c1_ns_m);
}

/// A bound on the magnitude of the Jacobian's eigenvalues of (y, z) over a
/// step at velocity v from state s, 1/s: with S = c_0 + c_1, |z| ≤ z_m =
/// max(|z|, z_sat) and |u| ≤ (c_1|v| + α z_m + k_0 |x − y|)/S,
/// n (β+γ) |u| z_m^(n−1) + (A + (β+γ) z_m^n) α/S + k_0/S.
inline double spencer_rate_bound_per_s(const SpencerCoefficients& c, const SpencerState& s, double x_m,
                                       double v_m_s) noexcept {
  const double sum = c.c0_ns_m + c.c1_ns_m;
  const double bg = std::fabs(c.beta_per_m_pow_n) + std::fabs(c.gamma_per_m_pow_n);
  const double zs = spencer_z_saturation_m(c);
  const double zm = std::max(std::fabs(s.z_m), std::isfinite(zs) ? zs : 0.0);
  const double alpha = std::fabs(c.alpha_n_m);
  const double u = (std::fabs(c.c1_ns_m * v_m_s) + alpha * zm + c.k0_n_m * std::fabs(x_m - s.y_m)) / sum;
  return c.n * bg * u * spencer_abs_pow(zm, c.n - 1.0) + (c.a + bg * spencer_abs_pow(zm, c.n)) * alpha / sum +
         c.k0_n_m / sum;
}

/// Largest sub-step times the rate bound: RK4 is stable to 2.78 on the
/// negative real axis; at 1 its error on a decaying mode is 7·10⁻³ of the
/// mode per sub-step (R(−1) = 0.375 against e⁻¹ = 0.368), and the bound
/// takes z at saturation, above what most sub-steps see.
inline constexpr double kSpencerStepStiffness = 1.0;
/// Most sub-steps in one step: 256 take a 1 ms sample at rates up to
/// 2.6·10⁵ 1/s, 35 times the laboratory damper's largest; a step that
/// needs more (parameters far from any damper's, which a fit may try) is
/// taken with this many, beyond the stability limit, and its force grows
/// without bound or turns NaN, which the fit rejects.
inline constexpr int kSpencerMaxSubsteps = 256;

/// The state after `dt_s` with the stroke moving from x_m at v_m_s (held).
inline SpencerState spencer_state_after(const SpencerCoefficients& c, SpencerState s, double x_m, double v_m_s,
                                        double dt_s) noexcept {
  if (!(dt_s > 0.0)) return s;
  const double rate = spencer_rate_bound_per_s(c, s, x_m, v_m_s);
  const double want = std::ceil(rate * dt_s / kSpencerStepStiffness);
  const int m = want < 1.0 ? 1 : (want > kSpencerMaxSubsteps ? kSpencerMaxSubsteps : static_cast<int>(want));
  const double h = dt_s / m;
  const auto f = [&](const SpencerState& q, double x, SpencerState& d) {
    d.y_m = spencer_y_rate(c, q, x, v_m_s);
    d.z_m = spencer_z_rate(c, q.z_m, v_m_s - d.y_m);
  };
  double x = x_m;
  for (int j = 0; j < m; ++j) {
    SpencerState k1, k2, k3, k4;
    f(s, x, k1);
    f({s.y_m + 0.5 * h * k1.y_m, s.z_m + 0.5 * h * k1.z_m}, x + 0.5 * h * v_m_s, k2);
    f({s.y_m + 0.5 * h * k2.y_m, s.z_m + 0.5 * h * k2.z_m}, x + 0.5 * h * v_m_s, k3);
    f({s.y_m + h * k3.y_m, s.z_m + h * k3.z_m}, x + h * v_m_s, k4);
    s.y_m += h / 6.0 * (k1.y_m + 2.0 * k2.y_m + 2.0 * k3.y_m + k4.y_m);
    s.z_m += h / 6.0 * (k1.z_m + 2.0 * k2.z_m + 2.0 * k3.z_m + k4.z_m);
    x += h * v_m_s;
  }
  return s;
}

}  // namespace mrd::physics
