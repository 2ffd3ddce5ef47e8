#pragma once
/// The calibrated damper force laws of `mrd calibrate` (host_sim/discrepancy/
/// baseline.hpp), for a yield force f_c and a viscous coefficient c_0 already
/// evaluated at the coil current and participant ratio (Eq. 5.10–5.11):
/// <pre>
///   bingham_tanh:  F = f_c tanh(v / v_TF) + c_0 v                      baseline.hpp, "tanh transition"
///   bouc_wen:      F = f_c z + c_0 v + k_0 x                           baseline.hpp, "bouc_wen"
///                  dz/dx = (1/x_y) (1 − |z|^n (β + γ sgn(ẋ z))),  β = γ = ½, n = 2
/// </pre>
/// x is the damper's stroke (its element's deformation), positive with
/// positive velocity; F is positive when it resists positive velocity. z is
/// Spencer et al. (1997)'s evolutionary variable normalized to |z| ≤ 1, so
/// f_c is a yield force and x_y the stroke over which the force builds after
/// a reversal. With β = γ = ½ the variable unloads linearly (dz/dx = 1/x_y
/// while ẋ z < 0) and loads as dz/dx = (1 − z²)/x_y, that is
/// z = tanh(atanh z_0 + Δx/x_y): rate-independent, a function of the stroke
/// path alone. Pure, allocation-free, exception-free.

#include <algorithm>
#include <cmath>

namespace mrd::physics {

/// f_c tanh(v/v_TF) + c_0 v (baseline.hpp, bingham_tanh_force_n), N.
inline double bingham_tanh_force_n(double yield_n, double viscous_ns_m, double velocity_m_s,
                                   double v_tf_m_s) noexcept {
  return yield_n * std::tanh(velocity_m_s / v_tf_m_s) + viscous_ns_m * velocity_m_s;
}

/// tanh(x) as 1 − 2 / (e^{2x} + 1): within about 1e−15 of std::tanh in
/// absolute terms (the division's rounding, at most half an ulp of 2, and
/// exp()'s; the relative error grows as |x| falls below 1e−3, where the force
/// f_c tanh(x) it serves is below f_c/1000), and faster (glibc's exp()
/// against the expm1() its tanh() calls: a calibration with a series
/// compliance took 15.0 s against 17.5 s). The tanh law behind a series
/// compliance evaluates it several times a step (series_compliance.hpp); the
/// law alone keeps std::tanh.
inline double tanh_by_exp(double x) noexcept { return 1.0 - 2.0 / (std::exp(2.0 * x) + 1.0); }

/// dF/dv of the Bingham laws at v, N·s/m (a series compliance's solve,
/// series_compliance.hpp), their viscous force c v_r (|v|/v_r)^m sgn v given
/// as `viscous_ns_m` = c (|v|/v_r)^(m−1) at this v (m = 1: c), band v_TF:
/// <pre>
///   tanh:     f_c (1 − t²) / v_TF + m c_eff,   t = tanh(v/v_TF)   (given: the force's own)
///   Eq. 4.4:  (f_c + (m + 1) c_eff |v|) / v_TF below v_TF, m c_eff above
/// </pre>
/// (below v_TF Eq. 4.4 is (f_c v + c_eff v |v|) / v_TF).
inline double bingham_tanh_slope_ns_m(double yield_n, double viscous_ns_m, double viscous_exponent, double t,
                                      double v_tf_m_s) noexcept {
  return yield_n * (1.0 - t * t) / v_tf_m_s + viscous_exponent * viscous_ns_m;
}
inline double bingham_slope_ns_m(double yield_n, double viscous_ns_m, double viscous_exponent, double velocity_m_s,
                                 double v_tf_m_s) noexcept {
  const double av = std::fabs(velocity_m_s);
  return av < v_tf_m_s ? (yield_n + (viscous_exponent + 1.0) * viscous_ns_m * av) / v_tf_m_s
                       : viscous_exponent * viscous_ns_m;
}

/// f_c z + c_0 v + k_0 x (baseline.hpp, the Bouc–Wen form; the sum in
/// discrepancy::DamperModel's order), N.
inline double bouc_wen_force_n(double yield_n, double viscous_ns_m, double stiffness_n_m, double z,
                               double velocity_m_s, double stroke_m) noexcept {
  return (yield_n * z + viscous_ns_m * velocity_m_s) + stiffness_n_m * stroke_m;
}

/// The Bouc–Wen variable after the stroke moves by `stroke_increment_m`
/// (no reversal within the increment), solved exactly as
/// discrepancy::bouc_wen_step (baseline.hpp) solves it for v·dt: linear
/// unloading until z crosses zero, then z = tanh(atanh z_0 + s), evaluated by
/// the addition theorem (z_0 + tanh s)/(1 + z_0 tanh s), s = the remaining
/// travel over x_y. |z| stays below 1 − 10⁻¹⁵. x_y ≤ 0 is the rigid-plastic
/// limit: z = sgn Δx (unchanged when Δx = 0).
inline double bouc_wen_z_after(double z, double stroke_increment_m, double yield_disp_m) noexcept {
  if (!(yield_disp_m > 0.0)) {
    return stroke_increment_m > 0.0 ? 1.0 : (stroke_increment_m < 0.0 ? -1.0 : z);
  }
  const double s = stroke_increment_m / yield_disp_m;
  if (s == 0.0) return z;
  const double d = s > 0.0 ? 1.0 : -1.0;
  double travel = std::fabs(s);
  double mag = z * d;  // z along the direction of motion
  if (mag < 0.0) {
    // Unloading: dz/dx = 1/x_y until z crosses zero.
    if (travel <= -mag) return z + s;
    travel += mag;
    mag = 0.0;
  }
  constexpr double kEdge = 1.0 - 1e-15;
  const double t = std::tanh(travel);
  mag = std::min(mag, kEdge);
  mag = (mag + t) / (1.0 + mag * t);
  return d * std::min(mag, kEdge);
}

}  // namespace mrd::physics
