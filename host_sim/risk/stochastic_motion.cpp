#include "host_sim/risk/stochastic_motion.hpp"

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "host_sim/excitation/synthetic_motion.hpp"
#include "mrd/units.hpp"

namespace mrd::risk {
namespace {

double uniform(std::mt19937_64& engine, double lo, double hi) {
  const double u = static_cast<double>(engine() >> 11) * 0x1.0p-53;
  return lo + (hi - lo) * u;
}

std::uint64_t splitmix64(std::uint64_t x) noexcept {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// ü of ü + 2ω_c u̇ + ω_c² u = x, from rest, Newmark average acceleration.
std::vector<double> high_pass(const std::vector<double>& x, double dt_s, double corner_hz) {
  const double w = 2.0 * std::numbers::pi * corner_hz;
  const double c = 2.0 * w, k = w * w;
  std::vector<double> a(x.size(), 0.0);
  double u = 0.0, v = 0.0, acc = x.empty() ? 0.0 : x[0];
  if (!x.empty()) a[0] = acc;
  const double m_eff = 1.0 + c * dt_s / 2.0 + k * dt_s * dt_s / 4.0;
  for (std::size_t n = 1; n < x.size(); ++n) {
    const double u_pred = u + dt_s * v + dt_s * dt_s / 4.0 * acc;
    const double v_pred = v + dt_s / 2.0 * acc;
    const double acc_new = (x[n] - c * v_pred - k * u_pred) / m_eff;
    u = u_pred + dt_s * dt_s / 4.0 * acc_new;
    v = v_pred + dt_s / 2.0 * acc_new;
    acc = acc_new;
    a[n] = acc;
  }
  return a;
}

}  // namespace

std::uint64_t record_seed(std::uint64_t study_seed, std::uint64_t index) noexcept {
  return splitmix64(splitmix64(study_seed) ^ index);
}

StochasticMotionParams draw_stochastic_params(const StochasticMotionRanges& r, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  StochasticMotionParams p;
  p.f_mid_hz = uniform(engine, r.f_mid_lo_hz, r.f_mid_hi_hz);
  p.f_slope_hz_s = uniform(engine, r.f_slope_lo_hz_s, r.f_slope_hi_hz_s);
  p.zeta = uniform(engine, r.zeta_lo, r.zeta_hi);
  p.peak_time_s = uniform(engine, r.peak_time_lo_s, r.peak_time_hi_s);
  return p;
}

StochasticLabel stochastic_motion_label(const StochasticMotionRanges& r, std::uint64_t seed, std::uint64_t index) {
  const StochasticMotionParams p = draw_stochastic_params(r, seed);
  char name[64];
  std::snprintf(name, sizeof name, "stochastic-%llu", static_cast<unsigned long long>(index));
  char source[256];
  std::snprintf(source, sizeof source,
                "evolving-spectrum model (Rezaeian & Der Kiureghian 2008): seed=%llu f_mid=%.4g Hz f'=%.4g Hz/s "
                "zeta=%.4g t_peak=%.4g s duration=%.4g s",
                static_cast<unsigned long long>(seed), p.f_mid_hz, p.f_slope_hz_s, p.zeta, p.peak_time_s, r.duration_s);
  return {name, source};
}

excitation::GroundMotion stochastic_motion(const StochasticMotionRanges& r, std::uint64_t seed, std::uint64_t index) {
  const StochasticMotionParams p = draw_stochastic_params(r, seed);
  const auto n = static_cast<std::size_t>(std::floor(r.duration_s / r.dt_s + 1e-9)) + 1;
  excitation::StandardNormal noise(splitmix64(seed));
  const double wd_factor = std::sqrt(1.0 - p.zeta * p.zeta);

  // z_i = e^{(−ζω_i + iω_i√(1−ζ²))(t_k − t_i)}, advanced by one step's rotation r_i per k.
  std::vector<std::complex<double>> z(n), rot(n);
  std::vector<double> gain(n), s(n);
  std::vector<double> x(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * r.dt_s;
    const double f = std::max(r.f_min_hz, p.f_mid_hz + p.f_slope_hz_s * (t - p.peak_time_s));
    const double w = 2.0 * std::numbers::pi * f;
    gain[k] = w / wd_factor;
    rot[k] = std::exp(std::complex<double>(-p.zeta * w, w * wd_factor) * r.dt_s);
    z[k] = 1.0;
    s[k] = noise.next();
    double num = 0.0, var = 0.0;
    for (std::size_t i = 0; i < k; ++i) {
      z[i] *= rot[i];
      const double h = gain[i] * z[i].imag();
      num += h * s[i];
      var += h * h;
    }
    const double a = r.envelope_shape - 1.0;
    const double q = t > 0.0 ? std::pow(t / p.peak_time_s, a) * std::exp(-a * (t / p.peak_time_s - 1.0)) : 0.0;
    x[k] = var > 0.0 ? q * num / std::sqrt(var) : 0.0;
  }
  excitation::GroundMotion m;
  m.dt_s = r.dt_s;
  m.accel_m_s2 = high_pass(x, r.dt_s, r.high_pass_hz);
  const StochasticLabel label = stochastic_motion_label(r, seed, index);
  m.name = label.name;
  m.source = label.source;
  return excitation::scaled_to_pga(m, units::kStandardGravity_m_s2);
}

}  // namespace mrd::risk
