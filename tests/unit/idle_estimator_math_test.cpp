// The fixed-point exp(−x) and ln(n/d) of the idle-time estimator
// (firmware/core/idle_estimator_math.hpp) against std::exp and std::log over
// the ranges the estimator uses, with the error bounds the header states;
// and the tick ratio and scaling helpers at 50 years of 1 ms ticks.
#include "firmware/core/idle_estimator_math.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace mrd::fw::idle_math {
namespace {

constexpr double kQ30 = 1073741824.0;  // 2^30
constexpr double kQ26 = 67108864.0;    // 2^26

// exp(−x) for x over the whole Q5.26 range [0, 32): every 977th raw value
// (2.2 million points, a stride prime to the table's period) and the range
// reduction's edges (multiples of ln2/16). Bound: 4·2^−30 = 3.8e−9.
TEST(FixedExp, WithinItsBoundOverTheRange) {
  double worst = 0.0;
  for (std::int64_t raw = 0; raw < (std::int64_t{1} << 31); raw += 977) {
    const double x = static_cast<double>(raw) / kQ26;
    worst = std::max(worst, std::fabs(exp_neg_q26(static_cast<std::int32_t>(raw)) / kQ30 - std::exp(-x)));
  }
  for (int k = 0; k < 16 * 32; ++k) {
    const double edge = k * std::log(2.0) / 16.0;
    for (int d = -2; d <= 2; ++d) {
      const auto raw = static_cast<std::int32_t>(std::llround(edge * kQ26) + d);
      if (raw < 0) continue;
      worst = std::max(worst, std::fabs(exp_neg_q26(raw) / kQ30 - std::exp(-raw / kQ26)));
    }
  }
  EXPECT_LT(worst, 4.0 / kQ30);
  EXPECT_GT(worst, 0.0);  // the method is not exact: the check can see an error
}

TEST(FixedExp, EndsOfTheRange) {
  EXPECT_EQ(exp_neg_q26(0), 1 << 30);         // exp(0) = 1 exactly
  EXPECT_EQ(exp_neg_q26(-5), 1 << 30);        // negative arguments count as 0
  EXPECT_EQ(exp_neg_q26(0x7FFFFFFF), 0);      // exp(−32) = 1.3e−14 < ½ LSB
  // exp(−ln2) = 0.5: x = ln2 in Q26 (rounded), result within the bound.
  EXPECT_NEAR(exp_neg_q26(46516320) / kQ30, 0.5, 4.0 / kQ30);
}

// ln(n/d) for n/d from 1 to 2^31, with n and d as Q1.30 values the
// estimator passes (PR spans, targets g·b down to 1e−4). Bound 1.2e−8.
TEST(FixedLog, WithinItsBoundOverTheRange) {
  double worst = 0.0;
  for (std::int64_t d = 1; d < (std::int64_t{1} << 31); d = d * 3 / 2 + 1) {
    for (double ratio = 1.0; ratio < 2.1e9; ratio *= 1.0137) {
      const double nd = static_cast<double>(d) * ratio;
      if (nd >= 2147483647.0) break;
      const auto n = static_cast<std::int32_t>(nd);
      const double exact = std::log(static_cast<double>(n) / static_cast<double>(d));
      const double got = ln_quotient_q26(n, static_cast<std::int32_t>(d)) / kQ26;
      worst = std::max(worst, std::fabs(got - std::min(exact, 32.0 - 1.0 / kQ26)));
    }
  }
  EXPECT_LT(worst, 1.2e-8);
  EXPECT_GT(worst, 0.0);
}

TEST(FixedLog, EdgeCases) {
  EXPECT_EQ(ln_quotient_q26(5, 5), 0);   // ln 1
  EXPECT_EQ(ln_quotient_q26(4, 5), 0);   // below 1: not used, 0
  EXPECT_EQ(ln_quotient_q26(5, 0), 0);   // no denominator
  // ln 2: exact value 0.693147…; one step of the table (j = 0, m = 1).
  EXPECT_NEAR(ln_quotient_q26(2 << 20, 1 << 20) / kQ26, std::log(2.0), 1.2e-8);
  // PR near 0.1 (a_PR⁻¹ at the settled end): ln(0.9/(0.100821 − 0.1)).
  const auto span = static_cast<std::int32_t>(0.9 * kQ30);
  const auto above = static_cast<std::int32_t>(0.000821 * kQ30);
  EXPECT_NEAR(ln_quotient_q26(span, above) / kQ26, std::log(0.9 / 0.000821), 1.2e-8 + 1e-6);
}

// 50 years of 1 ms ticks (1.578e12 > 2^40): SQ as a Q1.30 ratio and a
// fraction of that count, without overflow; exact to the ratio's rounding.
TEST(TickRatio, FiftyYearsOfMillisecondTicks) {
  const std::uint64_t fifty_years = 1577880000000ull;  // 50·365.25·86400·1000
  const std::uint64_t t_max = 26932324551ull;           // Eq. 5.4 in 1 ms ticks
  EXPECT_EQ(ratio_q(t_max / 2, t_max, 30), 1 << 29);
  EXPECT_NEAR(ratio_q(t_max / 5 * 4, t_max, 30) / kQ30, 0.8, 1.0 / kQ30 + 1e-10);  // SQ near the 0.8 threshold
  EXPECT_EQ(ratio_q(fifty_years, t_max, 30), 0x7FFFFFFF);                          // saturates (ratio 58)
  EXPECT_EQ(ratio_q(fifty_years, fifty_years * 2, 30), 1 << 29);
  EXPECT_EQ(scale_count(1 << 29, fifty_years, 30), fifty_years / 2);
  EXPECT_EQ(scale_count(1 << 30, fifty_years, 30), fifty_years);
  EXPECT_NEAR(static_cast<double>(scale_count(static_cast<std::int32_t>(0.8 * kQ30), fifty_years, 30)),
              0.8 * 1577880000000.0, 1577880000000.0 / kQ30 + 1.0);
}

}  // namespace
}  // namespace mrd::fw::idle_math
