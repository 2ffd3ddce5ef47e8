#pragma once
/// A damper law behind a compliance in series: the fluid's and the body's
/// give between the piston and the valve. The pressure that makes the law's
/// force builds only as the fluid column is compressed, so the law acts on
/// the fluid's velocity, not the piston's:
/// <pre>
///   F = f(u),   u = v − Ḟ / k_s
/// </pre>
/// (f the law, nondecreasing in u; k_s the series stiffness, N/m). Through a
/// reversal the force turns over in the time it takes the piston to move
/// ΔF / k_s, so its lag behind the motion grows with the force: at a higher
/// current, F/v and with it the lag τ ≈ (F/v) / k_s are larger. Backward
/// Euler over a step of dt:
/// <pre>
///   F[n] = f(u[n]),   u[n] = v[n] − c (F[n] − F[n−1]),   c = 1 / (k_s dt)   (m/s per N)
/// </pre>
/// h(u) = u + c (f(u) − F[n−1]) − v increases with u and changes sign
/// between v and v − c (f(v) − F[n−1]) (the fluid moves slower than the
/// piston while the force rises toward the law's, faster while it falls), so
/// the step has one solution for any k_s > 0 and step, however stiff.
///
/// Pure, allocation-free, exception-free.

#include <algorithm>
#include <cmath>

namespace mrd::physics {

/// A law's force at a velocity and its slope there: N, N·s/m.
struct ForceSlope {
  double force_n = 0.0;
  double slope_ns_m = 0.0;
};

/// F[n] of the header's step for the law `f` (f(u) → ForceSlope, the slope
/// ≥ 0), the step's velocity `v_m_s`, the last force `f_prev_n` and
/// c = 1/(k_s dt) in m/s per N. Newton's steps on h(u) from `u_m_s` (a
/// guess of the fluid's velocity: the last step's, moved by the piston's
/// change of velocity) until |h| is within 1e−12 of the velocities; each h
/// narrows a bracket of the root, and a step that would leave the bracket
/// halves it instead (once a side is unknown, the bracket between v and
/// v − c (f(v) − F_prev) is taken). `u_m_s` returns the fluid's velocity.
/// c = 0 is the law itself, f(v).
template <class Law>
double series_force_n(double v_m_s, double f_prev_n, double c_m_s_per_n, const Law& f, double& u_m_s) noexcept {
  if (!(c_m_s_per_n > 0.0)) {
    u_m_s = v_m_s;
    return f(v_m_s).force_n;
  }
  constexpr double kInf = HUGE_VAL;
  double lo = -kInf;
  double hi = kInf;
  bool bracketed = false;  // the bracket from v taken
  double u = std::isfinite(u_m_s) ? u_m_s : v_m_s;
  ForceSlope fs = f(u);
  for (int it = 0; it < 200; ++it) {
    const double h = u + c_m_s_per_n * (fs.force_n - f_prev_n) - v_m_s;
    if (std::fabs(h) <= 1e-12 * (std::fabs(u) + std::fabs(v_m_s)) || lo == hi) break;
    if (h > 0.0) {
      hi = std::min(hi, u);
    } else {
      lo = std::max(lo, u);
    }
    double next = u - h / (1.0 + c_m_s_per_n * fs.slope_ns_m);
    if (!(next > lo && next < hi)) {
      if (!(lo > -kInf && hi < kInf) && !bracketed) {
        const double other = v_m_s - c_m_s_per_n * (f(v_m_s).force_n - f_prev_n);
        lo = std::max(lo, std::min(v_m_s, other));
        hi = std::min(hi, std::max(v_m_s, other));
        bracketed = true;
      }
      next = next > lo && next < hi ? next : 0.5 * (lo + hi);
    }
    if (next == u) break;
    u = next;
    fs = f(u);
  }
  u_m_s = u;
  return fs.force_n;
}

}  // namespace mrd::physics
