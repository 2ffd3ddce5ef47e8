// Synthetic Kanai–Tajimi / Clough–Penzien ground motion with a Jennings-type
// envelope.
#include "host_sim/excitation/synthetic_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "host_sim/io/usage_error.hpp"

namespace mrd::excitation {
namespace {

TEST(StandardNormal, MomentsOfManyDeviates) {
  // 200 000 deviates: standard errors are 1/√n = 0.0022 for the mean,
  // √(2/n) = 0.0032 for the variance, √(p(1−p)/n) = 0.0010 for P(|z| < 1),
  // which is erf(1/√2) = 0.682689 for a standard normal.
  StandardNormal normal(42);
  constexpr int kCount = 200000;
  double sum = 0.0;
  double sum_sq = 0.0;
  int within_one = 0;
  for (int i = 0; i < kCount; ++i) {
    const double z = normal.next();
    ASSERT_TRUE(std::isfinite(z));
    sum += z;
    sum_sq += z * z;
    if (std::abs(z) < 1.0) ++within_one;
  }
  const double mean = sum / kCount;
  EXPECT_NEAR(mean, 0.0, 0.01);
  EXPECT_NEAR(sum_sq / kCount - mean * mean, 1.0, 0.015);
  EXPECT_NEAR(static_cast<double>(within_one) / kCount, 0.682689, 0.005);
}

TEST(StandardNormal, SameSeedSameSequence) {
  StandardNormal a(7);
  StandardNormal b(7);
  StandardNormal c(8);
  int differing = 0;
  for (int i = 0; i < 100; ++i) {
    const double za = a.next();
    EXPECT_EQ(za, b.next());
    if (za != c.next()) ++differing;
  }
  EXPECT_EQ(differing, 100);
}

// Defaults: t₁ = 2 s, t₂ = 12 s, c = 0.3 1/s.
//   e(1) = (1/2)² = 0.25;  e(2) = e(5) = e(12) = 1;
//   e(17) = exp(−0.3·5) = exp(−1.5) = 0.2231302;  e(30) = exp(−5.4) = 0.0045166
TEST(SyntheticMotion, EnvelopeByHand) {
  const SyntheticMotionParams p;
  EXPECT_EQ(jennings_envelope(-1.0, p), 0.0);
  EXPECT_EQ(jennings_envelope(0.0, p), 0.0);
  EXPECT_DOUBLE_EQ(jennings_envelope(1.0, p), 0.25);
  EXPECT_EQ(jennings_envelope(2.0, p), 1.0);
  EXPECT_EQ(jennings_envelope(5.0, p), 1.0);
  EXPECT_EQ(jennings_envelope(12.0, p), 1.0);
  EXPECT_NEAR(jennings_envelope(17.0, p), 0.2231302, 1e-7);
  EXPECT_NEAR(jennings_envelope(30.0, p), 0.0045166, 1e-7);
}

// Defaults ω_g = 15.6 rad/s, ζ_g = 0.6, ω_f = 1.5 rad/s, ζ_f = 0.6.
//   Kanai–Tajimi at ω = ω_g: (1 + 4ζ²)/(4ζ²) = 2.44/1.44 = 1.6944444
//   Clough–Penzien at ω = 15.6 (r = 10.4, r² = 108.16, r⁴ = 11698.5856):
//     r⁴/((1 − r²)² + 4ζ²r²) = 11698.5856/(11483.2656 + 155.7504) = 1.0051181
//   product 1.7031167.  At ω = 0: Kanai–Tajimi 1, Clough–Penzien 0.
//   Kanai–Tajimi at ω = 12.8 (x = r² = (12.8/15.6)² = 0.673241):
//     (1 + 1.44x)/((1 − x)² + 1.44x) = 1.969467/(0.106771 + 0.969467) = 1.829954
TEST(SyntheticMotion, FilterPowerGainByHand) {
  SyntheticMotionParams p;
  EXPECT_NEAR(filter_power_gain(15.6, p), 1.7031167, 1e-6);
  EXPECT_EQ(filter_power_gain(0.0, p), 0.0);
  p.high_pass = false;
  EXPECT_NEAR(filter_power_gain(15.6, p), 1.6944444, 1e-6);
  EXPECT_DOUBLE_EQ(filter_power_gain(0.0, p), 1.0);
  EXPECT_NEAR(filter_power_gain(12.8, p), 1.829954, 2e-6);
}

TEST(SyntheticMotion, LengthStepNameAndExactPga) {
  SyntheticMotionParams p;
  p.seed = 7;
  const GroundMotion m = synthetic_motion(p);
  EXPECT_EQ(m.accel_m_s2.size(), 3001u);  // 30 s / 0.01 s + 1
  EXPECT_EQ(m.dt_s, 0.01);
  EXPECT_EQ(m.name, "synthetic-kanai-tajimi(seed=7)");
  EXPECT_NE(m.source.find("omega_g=15.6 rad/s"), std::string::npos) << m.source;
  EXPECT_EQ(m.pga_m_s2(), p.target_pga_m_s2);
  EXPECT_NEAR(p.target_pga_m_s2, 1.105209455, 1e-9);  // 0.1127 g, Table 6.3
}

TEST(SyntheticMotion, DeterministicForTheSameSeed) {
  SyntheticMotionParams p;
  p.seed = 123;
  const GroundMotion a = synthetic_motion(p);
  const GroundMotion b = synthetic_motion(p);
  EXPECT_EQ(a.accel_m_s2, b.accel_m_s2);
  EXPECT_EQ(a.name, b.name);
}

TEST(SyntheticMotion, DifferentSeedDifferentMotion) {
  SyntheticMotionParams p;
  p.seed = 1;
  const GroundMotion a = synthetic_motion(p);
  p.seed = 2;
  const GroundMotion b = synthetic_motion(p);
  ASSERT_EQ(a.accel_m_s2.size(), b.accel_m_s2.size());
  std::size_t differing = 0;
  for (std::size_t i = 1; i < a.accel_m_s2.size(); ++i) {
    if (a.accel_m_s2[i] != b.accel_m_s2[i]) ++differing;
  }
  EXPECT_EQ(differing, a.accel_m_s2.size() - 1);  // all but the first (zero) sample
  EXPECT_NE(a.name, b.name);
}

// The envelope is 0 at t = 0, at most (0.2/2)² = 0.01 in the first 0.2 s
// and at most exp(−0.3·(29 − 12)) = 0.0061 in the last second. The peak of
// the stationary part is a few standard deviations, so the samples there
// stay a few percent of the PGA at most.
TEST(SyntheticMotion, EnvelopeMakesStartAndEndSmall) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    SyntheticMotionParams p;
    p.seed = seed;
    const GroundMotion m = synthetic_motion(p);
    const double pga = m.pga_m_s2();
    EXPECT_EQ(m.accel_m_s2.front(), 0.0);
    for (std::size_t i = 0; i <= 20; ++i) EXPECT_LT(std::abs(m.accel_m_s2[i]), 0.05 * pga) << "sample " << i;
    const std::size_t n = m.accel_m_s2.size();
    for (std::size_t i = n - 101; i < n; ++i) EXPECT_LT(std::abs(m.accel_m_s2[i]), 0.03 * pga) << "sample " << i;
    // The strong phase is in the plateau (2 s ≤ t ≤ 12 s) or shortly after.
    EXPECT_GE(m.pga_time_s(), 1.0);
    EXPECT_LE(m.pga_time_s(), 16.0);
  }
}

/// Periodogram |Σ a_k e^(−iω t_k)|² at each ω, summed over realizations with
/// seeds 1 … count.
std::vector<double> summed_periodogram(SyntheticMotionParams p, int count, const std::vector<double>& omegas_rad_s) {
  std::vector<double> power(omegas_rad_s.size(), 0.0);
  for (int r = 1; r <= count; ++r) {
    p.seed = static_cast<std::uint64_t>(r);
    const GroundMotion m = synthetic_motion(p);
    for (std::size_t j = 0; j < omegas_rad_s.size(); ++j) {
      const double step_cos = std::cos(omegas_rad_s[j] * m.dt_s);
      const double step_sin = -std::sin(omegas_rad_s[j] * m.dt_s);
      double c = 1.0;
      double s = 0.0;
      double re = 0.0;
      double im = 0.0;
      for (const double a : m.accel_m_s2) {
        re += a * c;
        im += a * s;
        const double c_next = c * step_cos - s * step_sin;
        s = c * step_sin + s * step_cos;
        c = c_next;
      }
      power[j] += re * re + im * im;
    }
  }
  return power;
}

double band_mean(const std::vector<double>& omegas, const std::vector<double>& power, double lo, double hi) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t j = 0; j < omegas.size(); ++j) {
    if (omegas[j] >= lo && omegas[j] <= hi) {
      sum += power[j];
      ++n;
    }
  }
  return sum / n;
}

// Theory (FilterPowerGainByHand and the header): the spectrum peaks at
// 0.821·ω_g = 12.8 rad/s with gain 1.83, is 1.47 at 0.5·ω_g and 0.88 at
// 1.5·ω_g (Kanai–Tajimi; the high-pass changes these by < 2 %). So the
// averaged, smoothed periodogram of 32 realizations should peak between
// 0.5·ω_g and 1.5·ω_g. Band ratios: around the peak (10–16 rad/s, gain
// ≈ 1.8) against 45–60 rad/s (gain at 52 rad/s: x = 11.11,
// 17.0/(10.11² + 16.0) = 0.144) is about 12; against 0.5–1.0 rad/s about
// 20: there Kanai–Tajimi is ≈ 1 and the high-pass r⁴/((1 − r²)² + 1.44r²),
// r = ω/1.5, is 0.0130, 0.0323, 0.0678, 0.1252, 0.2082 at ω = 0.5, 0.625,
// 0.75, 0.875, 1.0 rad/s (mean 0.089). The envelope leaks a little power
// across frequencies, so the tests ask only for a ratio above 5.
TEST(SyntheticMotion, SpectrumPeaksNearKanaiTajimiFrequency) {
  const SyntheticMotionParams p;
  std::vector<double> omegas;
  for (double w = 0.5; w <= 60.0; w += 0.25) omegas.push_back(w);
  const std::vector<double> power = summed_periodogram(p, 32, omegas);

  // ±1 rad/s moving average, then the peak.
  std::size_t best = 0;
  double best_power = -1.0;
  for (std::size_t j = 4; j + 4 < omegas.size(); ++j) {
    double s = 0.0;
    for (std::size_t k = j - 4; k <= j + 4; ++k) s += power[k];
    if (s > best_power) {
      best_power = s;
      best = j;
    }
  }
  const double wg = p.ground_frequency_rad_s;
  EXPECT_GE(omegas[best], 0.5 * wg);
  EXPECT_LE(omegas[best], 1.5 * wg);

  const double peak_band = band_mean(omegas, power, 10.0, 16.0);
  EXPECT_GT(peak_band / band_mean(omegas, power, 45.0, 60.0), 5.0);
  EXPECT_GT(peak_band / band_mean(omegas, power, 0.5, 1.0), 5.0);
}

// Without the high-pass the 0.5–1.0 rad/s band keeps Kanai–Tajimi's gain of
// about 1.0 (against 1.8 at the peak), so the ratio is about 0.55 instead of
// 0.089/1.8 = 0.05.
TEST(SyntheticMotion, HighPassRemovesLowFrequencies) {
  SyntheticMotionParams p;
  const std::vector<double> omegas = {0.5, 0.625, 0.75, 0.875, 1.0, 10.0, 11.0, 12.0, 13.0, 14.0, 15.0, 16.0};
  const std::vector<double> with_hp = summed_periodogram(p, 32, omegas);
  p.high_pass = false;
  const std::vector<double> without_hp = summed_periodogram(p, 32, omegas);
  const double ratio_with = band_mean(omegas, with_hp, 0.5, 1.0) / band_mean(omegas, with_hp, 10.0, 16.0);
  const double ratio_without = band_mean(omegas, without_hp, 0.5, 1.0) / band_mean(omegas, without_hp, 10.0, 16.0);
  EXPECT_LT(ratio_with, 0.15);
  EXPECT_GT(ratio_without, 0.25);
}

TEST(SyntheticMotion, RunsAtTheSimulatorStep) {
  SyntheticMotionParams p;
  p.dt_s = 0.001;
  p.duration_s = 20.0;
  p.plateau_end_s = 8.0;
  const GroundMotion m = synthetic_motion(p);
  EXPECT_EQ(m.accel_m_s2.size(), 20001u);
  EXPECT_EQ(m.pga_m_s2(), p.target_pga_m_s2);
}

TEST(SyntheticMotion, InvalidParametersRejected) {
  const auto expect_error = [](SyntheticMotionParams p, const std::string& piece) {
    try {
      synthetic_motion(p);
      ADD_FAILURE() << "expected io::UsageError for " << piece;
    } catch (const io::UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(piece), std::string::npos) << e.what();
    }
  };
  SyntheticMotionParams p;
  p.dt_s = 0.0;
  expect_error(p, "dt_s");
  p = {};
  p.duration_s = std::nan("");
  expect_error(p, "duration_s");
  p = {};
  p.duration_s = 0.005;  // less than one step
  expect_error(p, "between 2 and 1e9 samples");
  p = {};
  p.target_pga_m_s2 = -1.0;
  expect_error(p, "target PGA");
  p = {};
  p.ground_damping_ratio = 0.0;
  expect_error(p, "zeta_g");
  p = {};
  p.high_pass_frequency_rad_s = 0.0;
  expect_error(p, "omega_f");
  p = {};
  p.plateau_end_s = 1.0;
  expect_error(p, "t2");
  p = {};
  p.dt_s = 0.25;  // Nyquist π/0.25 = 12.6 rad/s, below ω_g = 15.6 rad/s
  expect_error(p, "Nyquist");
  p = {};
  p.decay_rate_1_s = -0.1;
  expect_error(p, "decay rate");
}

}  // namespace
}  // namespace mrd::excitation
