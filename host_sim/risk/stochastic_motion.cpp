#include "host_sim/risk/stochastic_motion.hpp"

#include <algorithm>
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

/// Amplitude, relative to its start, below which a term of the sum is
/// dropped: e^{−ζωτ} < 1e-12. What the dropped terms would still add to a
/// sample is of that order relative to the sample's scale, far below any
/// statistic of the record (the samples differ from the full sum by about
/// 1e-12 of the PGA).
constexpr double kNegligibleAmplitude = 1e-12;

/// Steps until e^{−decay_per_step·m} falls below kNegligibleAmplitude (at
/// least 1, at most `cap`: a filter without damping never decays).
std::size_t steps_to_negligible(double decay_per_step, double log_negligible, std::size_t cap) {
  if (!(decay_per_step > 0.0)) return cap;
  const double steps = std::ceil(-log_negligible / decay_per_step);
  return steps < static_cast<double>(cap) ? std::max<std::size_t>(1, static_cast<std::size_t>(steps)) : cap;
}

/// Consecutive terms of the sum whose filter frequency ω_i is the same (bit
/// for bit; the drifting frequency is held at f_min, or f' = 0): their
/// z_i = e^{(−ζω + iω√(1−ζ²))(t_k − t_i)} rotate and decay by the same factor
/// each step, so three running sums carry any number of them:
/// <pre>
///   A = Σ s_i z_i,   P = Σ z_i²,   Q = Σ |z_i|²
///   Σ h_i s_i = g·Im A,   Σ h_i² = g²·Σ Im(z_i)² = g²·(Q − Re P)/2
/// </pre>
/// A group of one term is the term itself. Each step costs one update per
/// group, and a group is dropped once its youngest term has decayed below
/// kNegligibleAmplitude, so the work per sample is bounded by the longest
/// impulse response, not by the record's length.
struct TermGroup {
  double f_hz = 0.0;
  double gain = 0.0;                   ///< ω/√(1−ζ²)
  std::complex<double> rot, rot_sq;    ///< one step's factor of z, and of z²
  double decay_sq = 0.0;               ///< one step's factor of |z|²
  std::complex<double> noise_sum;      ///< A
  std::complex<double> square_sum;     ///< P
  double magnitude_sum = 0.0;          ///< Q
  std::size_t steps_left = 0;          ///< until the youngest term is negligible

  static TermGroup start(double f_hz, double zeta, double wd_factor, double dt_s, double s, std::size_t life) {
    const double w = 2.0 * std::numbers::pi * f_hz;
    TermGroup g;
    g.f_hz = f_hz;
    g.gain = w / wd_factor;
    g.rot = std::exp(std::complex<double>(-zeta * w, w * wd_factor) * dt_s);
    g.rot_sq = g.rot * g.rot;
    g.decay_sq = std::norm(g.rot);
    g.add(s, life);
    return g;
  }
  /// A term with z = 1 (its first step).
  void add(double s, std::size_t life) {
    noise_sum += s;
    square_sum += 1.0;
    magnitude_sum += 1.0;
    steps_left = life;
  }
  void advance() {
    noise_sum *= rot;
    square_sum *= rot_sq;
    magnitude_sum *= decay_sq;
  }
  /// Σ Im(z_i)² (never below 0, whatever the rounding).
  double imag_square_sum() const { return std::max(0.0, 0.5 * (magnitude_sum - square_sum.real())); }
};

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

excitation::GroundMotion stochastic_motion(const StochasticMotionRanges& r, std::uint64_t seed, std::uint64_t index,
                                           StochasticMotionWork* work) {
  const StochasticMotionParams p = draw_stochastic_params(r, seed);
  const auto n = static_cast<std::size_t>(std::floor(r.duration_s / r.dt_s + 1e-9)) + 1;
  excitation::StandardNormal noise(splitmix64(seed));
  const double wd_factor = std::sqrt(1.0 - p.zeta * p.zeta);
  const double a = r.envelope_shape - 1.0;
  const double log_negligible = std::log(kNegligibleAmplitude);

  std::vector<TermGroup> groups;
  std::vector<double> x(n, 0.0);
  std::size_t updates = 0;
  for (std::size_t k = 0; k < n; ++k) {
    // The terms i < k, each z_i advanced one step: Σ h_i s_i and Σ h_i².
    double num = 0.0, var = 0.0;
    for (TermGroup& g : groups) {
      g.advance();
      num += g.gain * g.noise_sum.imag();
      var += g.gain * g.gain * g.imag_square_sum();
      --g.steps_left;
    }
    updates += groups.size();
    std::erase_if(groups, [](const TermGroup& g) { return g.steps_left == 0; });

    const double t = static_cast<double>(k) * r.dt_s;
    const double q = t > 0.0 ? std::pow(t / p.peak_time_s, a) * std::exp(-a * (t / p.peak_time_s - 1.0)) : 0.0;
    x[k] = var > 0.0 ? q * num / std::sqrt(var) : 0.0;

    // Term k joins the sum from the next step (h(0) = 0).
    const double f = std::max(r.f_min_hz, p.f_mid_hz + p.f_slope_hz_s * (t - p.peak_time_s));
    const double s = noise.next();
    const std::size_t life = steps_to_negligible(p.zeta * 2.0 * std::numbers::pi * f * r.dt_s, log_negligible, n);
    if (!groups.empty() && groups.back().f_hz == f) {
      groups.back().add(s, life);
    } else {
      groups.push_back(TermGroup::start(f, p.zeta, wd_factor, r.dt_s, s, life));
    }
  }
  if (work) work->term_updates = updates;
  excitation::GroundMotion m;
  m.dt_s = r.dt_s;
  m.accel_m_s2 = high_pass(x, r.dt_s, r.high_pass_hz);
  const StochasticLabel label = stochastic_motion_label(r, seed, index);
  m.name = label.name;
  m.source = label.source;
  return excitation::scaled_to_pga(m, units::kStandardGravity_m_s2);
}

}  // namespace mrd::risk
