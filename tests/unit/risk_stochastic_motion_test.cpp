// Stochastic motions of the fragility study: the generator gives the model's
// sum (stochastic_motion.hpp) evaluated directly, and its work grows linearly
// with the record's duration.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "host_sim/excitation/synthetic_motion.hpp"
#include "host_sim/risk/stochastic_motion.hpp"
#include "mrd/units.hpp"

namespace mrd::risk {
namespace {

/// SplitMix64 (Steele, Lea & Flood 2014), the per-record noise seed the
/// header names.
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// The model of stochastic_motion.hpp written out term by term: every
/// h(t_k − t_i; ω_i) from its closed form, summed over every i ≤ k, then the
/// critically damped high-pass by Newmark's average acceleration and the
/// scaling to 1 g.
std::vector<double> direct_sum_motion(const StochasticMotionRanges& r, std::uint64_t seed) {
  const StochasticMotionParams p = draw_stochastic_params(r, seed);
  const auto n = static_cast<std::size_t>(std::floor(r.duration_s / r.dt_s + 1e-9)) + 1;
  excitation::StandardNormal noise(splitmix64(seed));
  const double wd = std::sqrt(1.0 - p.zeta * p.zeta);
  std::vector<double> s(n), w(n), x(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * r.dt_s;
    w[k] = 2.0 * std::numbers::pi * std::max(r.f_min_hz, p.f_mid_hz + p.f_slope_hz_s * (t - p.peak_time_s));
    s[k] = noise.next();
  }
  const double alpha = r.envelope_shape - 1.0;
  for (std::size_t k = 0; k < n; ++k) {
    double num = 0.0, var = 0.0;
    for (std::size_t i = 0; i < k; ++i) {
      const double tau = static_cast<double>(k - i) * r.dt_s;
      const double h = w[i] / wd * std::exp(-p.zeta * w[i] * tau) * std::sin(w[i] * wd * tau);
      num += h * s[i];
      var += h * h;
    }
    const double t = static_cast<double>(k) * r.dt_s;
    const double q = t > 0.0 ? std::pow(t / p.peak_time_s, alpha) * std::exp(-alpha * (t / p.peak_time_s - 1.0)) : 0.0;
    x[k] = var > 0.0 ? q * num / std::sqrt(var) : 0.0;
  }
  // ü + 2ω_c u̇ + ω_c² u = x from rest; the corrected motion is ü.
  const double wc = 2.0 * std::numbers::pi * r.high_pass_hz, dt = r.dt_s;
  std::vector<double> a(n);
  double u = 0.0, v = 0.0, acc = x[0];
  a[0] = acc;
  for (std::size_t k = 1; k < n; ++k) {
    const double u_pred = u + dt * v + dt * dt / 4.0 * acc;
    const double v_pred = v + dt / 2.0 * acc;
    acc = (x[k] - 2.0 * wc * v_pred - wc * wc * u_pred) / (1.0 + wc * dt + wc * wc * dt * dt / 4.0);
    u = u_pred + dt * dt / 4.0 * acc;
    v = v_pred + dt / 2.0 * acc;
    a[k] = acc;
  }
  double pga = 0.0;
  for (double v_k : a) pga = std::max(pga, std::abs(v_k));
  for (double& v_k : a) v_k *= units::kStandardGravity_m_s2 / pga;
  return a;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

// Three kinds of record: the default ranges (the frequency drifts and may
// reach f_min), a steep drift that reaches f_min early (most terms share it),
// and no drift at all (every term shares one frequency). Tolerance 1e-9 m/s²
// on a 9.81 m/s² record: the generator drops terms below 1e-12 of their start
// and rotates them step by step instead of taking exp and sin afresh, both
// some 1e-12 of the PGA.
TEST(RiskStochasticMotion, EqualsTheModelsSumTermByTerm) {
  StochasticMotionRanges defaults;
  defaults.duration_s = 20.0;
  StochasticMotionRanges steep = defaults;
  steep.f_slope_lo_hz_s = -0.8;
  steep.f_slope_hi_hz_s = -0.5;
  StochasticMotionRanges fixed = defaults;
  fixed.f_slope_lo_hz_s = fixed.f_slope_hi_hz_s = 0.0;
  for (const auto& r : {defaults, steep, fixed}) {
    for (std::uint64_t i = 0; i < 3; ++i) {
      const std::uint64_t seed = record_seed(7, i);
      const auto m = stochastic_motion(r, seed, i);
      const auto ref = direct_sum_motion(r, seed);
      ASSERT_EQ(m.accel_m_s2.size(), ref.size());
      EXPECT_LT(largest_difference(m.accel_m_s2, ref), 1e-9) << "slope " << r.f_slope_lo_hz_s << ", record " << i;
    }
  }
}

// Work per sample bounded by the longest impulse response, not the record:
// a term lives until e^{−ζω·m·dt} < 1e-12, at most
// m = ln(1e12) / (ζ_lo · 2π f_min · dt) = 27.631 / (0.2 · 2π · 0.3 · 0.01) = 7330 steps,
// so at most 7330 groups are updated per sample and a 600-s record (60001
// samples) costs at most 60001 · 7330 = 4.4e8 updates, where the sum over
// every earlier term costs 60001 · 60000 / 2 = 1.8e9. Ten times the duration
// costs at most ten times the work of the shorter record (its early part,
// before the frequency reaches f_min, is the dearest per sample).
TEST(RiskStochasticMotion, WorkGrowsLinearlyWithTheDuration) {
  StochasticMotionRanges r;
  for (std::uint64_t i = 0; i < 2; ++i) {
    StochasticMotionWork short_work, long_work;
    r.duration_s = 60.0;
    (void)stochastic_motion(r, record_seed(1, i), i, &short_work);
    r.duration_s = 600.0;
    (void)stochastic_motion(r, record_seed(1, i), i, &long_work);
    EXPECT_GT(short_work.term_updates, 0u);
    EXPECT_LE(long_work.term_updates, std::size_t{60001} * 7330u) << "record " << i;
    EXPECT_LE(long_work.term_updates, 10u * short_work.term_updates) << "record " << i;
  }
}

}  // namespace
}  // namespace mrd::risk
