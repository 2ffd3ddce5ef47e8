// Causal RILD filter, Eq. 6.1, prewarped Tustin: frequency response of both
// numeric builds against the analog all-pass, hand-calculated samples.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <type_traits>
#include <vector>

#include "firmware/core/rild_filter.hpp"
#include "mrd/units.hpp"

namespace mrd::fw {
namespace {

constexpr double kPi = units::kPi;
constexpr double kK_n_m = 3287.0e3;                  // SPEC: 3287 kN/m
constexpr double kEta = 0.8;                         // §6.3
constexpr double kOmegaF = 2.0 * kPi * 0.2508;       // SPEC: 2π·0.2508 rad/s
constexpr double kT = 1.0e-3;                        // 1 kHz
constexpr double kGain = kK_n_m * kEta;              // 2629.6 kN/m

template <class Policy>
class RildFilterTest : public ::testing::Test {};
using Policies = ::testing::Types<num::Float32Policy, num::Fixed32Policy>;
TYPED_TEST_SUITE(RildFilterTest, Policies);

struct Response {
  double gain;       // |F_d| / |x|, N/m
  double phase_deg;  // phase of F_d relative to x
};

/// Drives the filter with x = A sin(2π f n T) until the pole's transient
/// (time constant T/(1 − a) ≈ 0.64 s) has died out, then projects the output
/// on sin and cos over a whole number of periods (least squares, exact for a
/// sinusoid sampled over whole periods).
template <class Policy>
Response measure(double freq_hz, double amplitude_m) {
  RildFilter<Policy> f;
  f.init(kK_n_m, kEta, kOmegaF, kT);
  using Disp = typename RildFilter<Policy>::Disp;
  const double period_samples = 1.0 / (freq_hz * kT);
  const long settle = 12000;  // 19 time constants
  // Whole periods, at least 2 s of samples.
  long cycles = static_cast<long>(std::ceil(2000.0 / period_samples));
  if (cycles < 1) cycles = 1;
  const long n_meas = std::lround(static_cast<double>(cycles) * period_samples);
  const long settle_whole = std::lround(std::ceil(settle / period_samples) * period_samples);
  double s_ys = 0, s_yc = 0, s_ss = 0, s_cc = 0, s_sc = 0;
  for (long n = 0; n < settle_whole + n_meas; ++n) {
    const double ph = 2.0 * kPi * freq_hz * static_cast<double>(n) * kT;
    const double x = amplitude_m * std::sin(ph);
    const double y = num::to_double(f.step(num::from_double<Disp>(x)));
    if (n >= settle_whole) {
      const double s = std::sin(ph), c = std::cos(ph);
      s_ys += y * s;
      s_yc += y * c;
      s_ss += s * s;
      s_cc += c * c;
      s_sc += s * c;
    }
  }
  // y ≈ B sin + C cos: solve the 2×2 normal equations.
  const double det = s_ss * s_cc - s_sc * s_sc;
  const double b = (s_ys * s_cc - s_yc * s_sc) / det;
  const double c = (s_yc * s_ss - s_ys * s_sc) / det;
  return {std::hypot(b, c) / amplitude_m, std::atan2(c, b) * 180.0 / kPi};
}

/// Phase of the analog H(iω_a) = kη (iω_a − ω_f)/(iω_a + ω_f) at the
/// prewarped frequency ω_a = ω_f tan(ωT/2)/tan(ω_f T/2) that Tustin maps ω to.
double analog_phase_deg(double freq_hz) {
  const double w = 2.0 * kPi * freq_hz;
  const double wa = kOmegaF * std::tan(w * kT / 2.0) / std::tan(kOmegaF * kT / 2.0);
  const std::complex<double> h = (std::complex<double>(0.0, wa) - kOmegaF) / (std::complex<double>(0.0, wa) + kOmegaF);
  return std::arg(h) * 180.0 / kPi;
}

TYPED_TEST(RildFilterTest, GainIsKEtaWithinATenthOfAPercentFrom0p01To20Hz) {
  for (double f_hz : {0.01, 0.03, 0.1, 0.2508, 0.5, 1.0, 3.0, 10.0, 20.0}) {
    const Response r = measure<TypeParam>(f_hz, 0.05);
    EXPECT_NEAR(r.gain / kGain, 1.0, 1e-3) << f_hz << " Hz, " << TypeParam::kName;
  }
}

TYPED_TEST(RildFilterTest, GainHoldsForASmallStroke) {
  // 5 mm: the fixed-point rounding error (≤ 1.2e−6 m) is still < 0.1 %.
  for (double f_hz : {0.05, 0.2508, 5.0}) {
    const Response r = measure<TypeParam>(f_hz, 0.005);
    EXPECT_NEAR(r.gain / kGain, 1.0, 1e-3) << f_hz << " Hz, " << TypeParam::kName;
  }
}

TYPED_TEST(RildFilterTest, LeadsDisplacementByNinetyDegreesAtOmegaF) {
  // SPEC: at ω_f, H = kη·i, F_d leads x_b by +90° (in phase with velocity).
  const Response r = measure<TypeParam>(kOmegaF / (2.0 * kPi), 0.05);
  EXPECT_NEAR(r.phase_deg, 90.0, 0.5) << TypeParam::kName;
}

TYPED_TEST(RildFilterTest, PhaseFollowsTheAnalogAllPassAtThePrewarpedFrequency) {
  // Low frequencies: F_d → −kη x (phase → ±180°); high: → +kη x (0°).
  for (double f_hz : {0.01, 0.1, 1.0, 20.0}) {
    const Response r = measure<TypeParam>(f_hz, 0.05);
    double diff = r.phase_deg - analog_phase_deg(f_hz);
    diff = std::remainder(diff, 360.0);
    EXPECT_NEAR(diff, 0.0, 0.5) << f_hz << " Hz, " << TypeParam::kName;
  }
  // Hand check of the analog values used above: at 0.01 Hz, ω/ω_f = 0.0399,
  // arg((i·0.0399 − 1)/(i·0.0399 + 1)) = 180° − 2·atan(0.0399) = 175.4°.
  EXPECT_NEAR(analog_phase_deg(0.01), 180.0 - 2.0 * std::atan(0.01 / 0.2508) * 180.0 / kPi, 0.01);
}

TYPED_TEST(RildFilterTest, PoleAndFirstSamplesByHand) {
  // θ = ω_f T/2 = π·0.2508e−3 = 7.8791e−4; a = (1 − tan θ)/(1 + tan θ) = 0.9984254.
  const double theta = kPi * 0.2508e-3;
  const double a = (1.0 - std::tan(theta)) / (1.0 + std::tan(theta));
  EXPECT_NEAR(rild_pole(kOmegaF, kT), 0.9984254, 1e-7);
  RildFilter<TypeParam> f;
  f.init(kK_n_m, kEta, kOmegaF, kT);
  // Quantized once: half an ulp of float near 1 (3.0e−8), half an LSB of Q2.29 (9.3e−10).
  const double half_step = std::is_same_v<TypeParam, num::Float32Policy> ? 3.0e-8 : 9.4e-10;
  EXPECT_NEAR(num::to_double(f.pole()), a, half_step);
  using Disp = typename RildFilter<TypeParam>::Disp;
  // Unit step of 10 mm from rest: w[0] = a·x, w[1] = a(w[0] + x) − x.
  const double x = 0.01;
  const double f0 = num::to_double(f.step(num::from_double<Disp>(x)));
  EXPECT_NEAR(f0, kGain * a * x, 0.05);  // 26 283 N
  const double f1 = num::to_double(f.step(num::from_double<Disp>(x)));
  EXPECT_NEAR(f1, kGain * (a * (a * x + x) - x), 0.05);
}

TYPED_TEST(RildFilterTest, HeldDisplacementSettlesToMinusKEtaX) {
  // DC gain of Eq. 6.1: H(0) = kη(0 − ω_f)/(0 + ω_f) = −kη; Tustin keeps it.
  RildFilter<TypeParam> f;
  f.init(kK_n_m, kEta, kOmegaF, kT);
  using Disp = typename RildFilter<TypeParam>::Disp;
  double y = 0.0;
  for (int n = 0; n < 20000; ++n) y = num::to_double(f.step(num::from_double<Disp>(0.02)));
  EXPECT_NEAR(y, -kGain * 0.02, 0.01 * kGain * 0.02 * 1e-2);  // −52 592 N within 0.01 %
}

TYPED_TEST(RildFilterTest, PrimedFilterHasNoTransient) {
  RildFilter<TypeParam> f;
  f.init(kK_n_m, kEta, kOmegaF, kT);
  using Disp = typename RildFilter<TypeParam>::Disp;
  const auto x = num::from_double<Disp>(0.03);
  f.prime(x);
  for (int n = 0; n < 10; ++n) EXPECT_NEAR(num::to_double(f.step(x)), -kGain * 0.03, 0.01);
}

TEST(RildFilterFixed, SaturatesInsteadOfWrappingAtFullScale) {
  // A 7.9 m "displacement" (near the top of Q3.28) makes w + x overflow; the
  // sums and products must stick at the rails with the right sign, and the
  // force at +524 kN (top of Q19.12), never wrap to a negative value.
  RildFilter<num::Fixed32Policy> f;
  f.init(kK_n_m, kEta, kOmegaF, kT);
  using Disp = RildFilter<num::Fixed32Policy>::Disp;
  using Force = RildFilter<num::Fixed32Policy>::Force;
  // n = 0: w = a·7.9 = 7.888 m fits; kη·w = 20.7 MN saturates at +524 kN.
  EXPECT_EQ(f.step(Disp::from_double(7.9)), Force::max());
  // n = 1: w + x = 15.79 m saturates at 8 m, w = a·8 − 7.9 = +0.087 m.
  // Wrapping would have made w + x ≈ −0.21 m and w ≈ −8 m.
  (void)f.step(Disp::from_double(7.9));
  EXPECT_NEAR(num::to_double(f.allpass_m()), 0.9984254 * 8.0 - 7.9, 1e-6);
  // n = 2: w + x = −7.81 m, w = a(−7.81) − 7.9 = −15.7 m saturates at −8 m.
  EXPECT_EQ(f.step(Disp::from_double(-7.9)), Force::lowest());
  EXPECT_EQ(f.allpass_m(), Disp::lowest());
}

}  // namespace
}  // namespace mrd::fw
