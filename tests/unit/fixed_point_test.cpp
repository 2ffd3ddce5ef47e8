// Numeric policies: Fixed<I, F> saturating Q arithmetic and the generic
// helpers that let one block compile for float and fixed point.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "mrd/num/fixed.hpp"
#include "mrd/num/policy.hpp"

namespace mrd::num {
namespace {

TEST(Fixed, RangeAndResolutionOfQ15_16) {
  // Q15.16: [−2^15, 2^15 − 2^−16], step 2^−16 = 1.52587890625e−5.
  EXPECT_DOUBLE_EQ(Q15_16::epsilon().to_double(), 1.52587890625e-5);
  EXPECT_DOUBLE_EQ(Q15_16::max_value(), 32768.0 - 1.52587890625e-5);
  EXPECT_DOUBLE_EQ(Q15_16::lowest_value(), -32768.0);
  EXPECT_DOUBLE_EQ(Q31::lowest_value(), -1.0);
}

TEST(Fixed, ConversionRoundsToNearest) {
  // 1/3 in Q15.16: 65536/3 = 21845.33 → raw 21845.
  EXPECT_EQ(Q15_16::from_double(1.0 / 3.0).raw(), 21845);
  // 2/3: 43690.67 → 43691; negative rounds symmetrically.
  EXPECT_EQ(Q15_16::from_double(2.0 / 3.0).raw(), 43691);
  EXPECT_EQ(Q15_16::from_double(-2.0 / 3.0).raw(), -43691);
  EXPECT_EQ(Q15_16::from_double(1.5).raw(), 3 << 15);
}

TEST(Fixed, ConversionSaturatesAndMapsNanToZero) {
  EXPECT_EQ(Q15_16::from_double(1e9), Q15_16::max());
  EXPECT_EQ(Q15_16::from_double(-1e9), Q15_16::lowest());
  EXPECT_EQ(Q15_16::from_double(std::numeric_limits<double>::infinity()), Q15_16::max());
  EXPECT_EQ(Q15_16::from_double(-std::numeric_limits<double>::infinity()), Q15_16::lowest());
  EXPECT_EQ(Q15_16::from_double(std::nan("")).raw(), 0);
  EXPECT_EQ(Q31::from_double(1.0), Q31::max());  // +1 is just out of Q0.31
}

TEST(Fixed, AdditionAndSubtractionSaturateNeverWrap) {
  const auto big = Q15_16::from_double(30000.0);
  EXPECT_EQ(big + big, Q15_16::max());
  EXPECT_EQ(-big - big, Q15_16::lowest());
  EXPECT_EQ(-Q15_16::lowest(), Q15_16::max());  // −(−2^15) does not fit
  EXPECT_DOUBLE_EQ((Q15_16::from_double(1.25) + Q15_16::from_double(-3.5)).to_double(), -2.25);
}

// +, − and negation equal the exact integer result clamped to int32, at the
// range ends and on a spread of raw values (the reference is 64-bit integer
// arithmetic written here).
TEST(Fixed, SumsDifferencesAndNegationAreTheClampedExactResults) {
  constexpr std::int64_t kMax = std::numeric_limits<std::int32_t>::max();
  constexpr std::int64_t kMin = std::numeric_limits<std::int32_t>::min();
  const auto clamped = [](std::int64_t v) { return v > kMax ? kMax : (v < kMin ? kMin : v); };
  std::vector<std::int32_t> raws = {std::numeric_limits<std::int32_t>::min(),
                                    std::numeric_limits<std::int32_t>::min() + 1,
                                    -(1 << 30) - 1, -(1 << 30), -2, -1, 0, 1, 2, 1 << 30, (1 << 30) + 1,
                                    std::numeric_limits<std::int32_t>::max() - 1,
                                    std::numeric_limits<std::int32_t>::max()};
  std::mt19937 rng(20261128);
  std::uniform_int_distribution<std::int32_t> any_raw(std::numeric_limits<std::int32_t>::min(),
                                                      std::numeric_limits<std::int32_t>::max());
  for (int k = 0; k < 200; ++k) raws.push_back(any_raw(rng));
  for (const std::int32_t a : raws) {
    const Q15_16 x = Q15_16::from_raw(a);
    EXPECT_EQ((-x).raw(), clamped(-std::int64_t{a})) << a;
    for (const std::int32_t b : raws) {
      const Q15_16 y = Q15_16::from_raw(b);
      ASSERT_EQ((x + y).raw(), clamped(std::int64_t{a} + b)) << a << " + " << b;
      ASSERT_EQ((x - y).raw(), clamped(std::int64_t{a} - b)) << a << " - " << b;
    }
  }
  static_assert((Q15_16::max() + Q15_16::epsilon()) == Q15_16::max());
  static_assert((Q15_16::lowest() - Q15_16::epsilon()) == Q15_16::lowest());
  static_assert((Q15_16{} - Q15_16::lowest()) == Q15_16::max());
}

TEST(Fixed, MultiplicationRoundsAndSaturates) {
  EXPECT_DOUBLE_EQ((Q15_16::from_double(1.5) * Q15_16::from_double(-2.25)).to_double(), -3.375);
  EXPECT_EQ(Q15_16::from_double(300.0) * Q15_16::from_double(300.0), Q15_16::max());
  EXPECT_EQ(Q15_16::from_double(300.0) * Q15_16::from_double(-300.0), Q15_16::lowest());
  // Q0.31: 0.5 · 0.5 = 0.25 exactly; (−1)·(−1) = +1 saturates to max.
  EXPECT_DOUBLE_EQ((Q31::from_double(0.5) * Q31::from_double(0.5)).to_double(), 0.25);
  EXPECT_EQ(Q31::lowest() * Q31::lowest(), Q31::max());
  // Rounding: eps · 0.5 = half a step → rounds up to one step.
  EXPECT_EQ((Q15_16::epsilon() * Q15_16::from_double(0.5)).raw(), 1);
}

TEST(Fixed, DivisionIncludingByZero) {
  EXPECT_DOUBLE_EQ((Q15_16::from_double(3.0) / Q15_16::from_double(-2.0)).to_double(), -1.5);
  EXPECT_EQ(Q15_16::from_double(3.0) / Q15_16{}, Q15_16::max());
  EXPECT_EQ(Q15_16::from_double(-3.0) / Q15_16{}, Q15_16::lowest());
  EXPECT_EQ((Q15_16{} / Q15_16{}).raw(), 0);
  EXPECT_EQ(Q15_16::from_double(20000.0) / Q15_16::from_double(0.01), Q15_16::max());
}

TEST(Fixed, MixedFormatMultiplyAndCast) {
  using Coef = Fixed<2, 29>;
  // A coefficient 0.9987 (Q2.29) times a state 1234.5 (Q15.16) into Q15.16:
  // 1232.895... within one output step of the exact product.
  const auto c = Coef::from_double(0.9987);
  const auto x = Q15_16::from_double(1234.5);
  const auto y = mul<Q15_16>(c, x);
  EXPECT_NEAR(y.to_double(), c.to_double() * x.to_double(), Q15_16::epsilon().to_double());
  // Casting to a narrower integer range saturates; to more fraction bits is exact.
  EXPECT_EQ(q_cast<Q7_24>(Q15_16::from_double(1000.0)), Q7_24::max());
  EXPECT_DOUBLE_EQ(q_cast<Q7_24>(Q15_16::from_double(-3.25)).to_double(), -3.25);
  // Dropping fraction bits rounds to nearest.
  EXPECT_EQ(q_cast<Q15_16>(Q7_24::from_raw(1 << 7)).raw(), 1);  // 0.5 step → rounds up
}

// Conversions round to nearest with ties away from zero, exactly: adding ½
// and truncating rounds twice (0.49999997 + 0.5 is 1 in float; an odd
// integer in [2^23, 2^24), where floats step by 1, plus 0.5 ties to the even
// one above). Fixed<31, 0> counts whole units, so raw = round(v). The
// reference: trunc and fraction in double, where both are exact.
TEST(Fixed, FloatConversionRoundsHalfAwayFromZeroOnWholeBinades) {
  using Units = Fixed<31, 0>;
  const auto reference = [](float v) {
    const double t = std::trunc(static_cast<double>(v));
    const double frac = static_cast<double>(v) - t;
    return static_cast<std::int64_t>(t) + (frac >= 0.5 ? 1 : 0) - (frac <= -0.5 ? 1 : 0);
  };
  EXPECT_EQ(from_float<Units>(0.49999997f).raw(), 0);
  EXPECT_EQ(from_float<Units>(-0.49999997f).raw(), 0);
  EXPECT_EQ(from_float<Units>(0.5f).raw(), 1);
  EXPECT_EQ(from_float<Units>(-0.5f).raw(), -1);
  EXPECT_EQ(from_float<Units>(2.5f).raw(), 3);
  EXPECT_EQ(from_float<Units>(8388609.0f).raw(), 8388609);
  EXPECT_EQ(from_float<Units>(-8388609.0f).raw(), -8388609);
  EXPECT_EQ(from_float<Units>(8388607.5f).raw(), 8388608);  // a tie, away from zero
  EXPECT_EQ(from_float<Units>(-8388607.5f).raw(), -8388608);
  EXPECT_EQ(from_float<Units>(-0.0f).raw(), 0);
  EXPECT_EQ(from_float<Units>(2147483520.0f).raw(), 2147483520);  // the largest float below 2^31
  EXPECT_EQ(from_float<Units>(2147483648.0f), Units::max());
  EXPECT_EQ(from_float<Units>(-2147483648.0f), Units::lowest());
  EXPECT_EQ(from_float<Units>(std::numeric_limits<float>::quiet_NaN()).raw(), 0);
  // Every third float of the binades where rounding twice goes wrong:
  // [0.25, 1) around ½, and [2^22, 2^24) where the step is ½ and 1.
  std::int64_t wrong = 0;
  for (const auto& [lo, hi] : {std::pair{0.25f, 1.0f}, std::pair{4194304.0f, 16777216.0f}}) {
    const auto first = std::bit_cast<std::uint32_t>(lo);
    const auto end = std::bit_cast<std::uint32_t>(hi);
    for (std::uint32_t b = first; b < end; b += 3) {
      const float v = std::bit_cast<float>(b);
      if (from_float<Units>(v).raw() != reference(v)) ++wrong;
      if (from_float<Units>(-v).raw() != reference(-v)) ++wrong;
    }
  }
  EXPECT_EQ(wrong, 0);
}

TEST(Fixed, DoubleConversionRoundsHalfAwayFromZeroExactly) {
  using Units = Fixed<31, 0>;
  EXPECT_EQ(Units::from_double(0.49999999999999994).raw(), 0);
  EXPECT_EQ(Units::from_double(-0.49999999999999994).raw(), 0);
  EXPECT_EQ(Units::from_double(0.5).raw(), 1);
  EXPECT_EQ(Units::from_double(-0.5).raw(), -1);
  EXPECT_EQ(Units::from_double(1e9 + 0.5).raw(), 1000000001);
  EXPECT_EQ(Units::from_double(-1e9 - 0.5).raw(), -1000000001);
  EXPECT_EQ(Units::from_double(2147483646.5), Units::max());
  EXPECT_EQ(Units::from_double(-2147483647.5), Units::lowest());
  static_assert(Units::from_double(0.49999999999999994).raw() == 0);
}

TEST(Fixed, ConstexprUsable) {
  constexpr auto a = Q15_16::from_double(2.0) * Q15_16::from_double(4.0);
  static_assert(a.raw() == (8 << 16));
  SUCCEED();
}

// The generic helpers make one source compile for both representations.
template <class T>
T accumulate_gain(double gain, double input, int n) {
  T acc = from_double<T>(0.0);
  const T g = from_double<T>(gain);
  const T x = from_double<T>(input);
  for (int i = 0; i < n; ++i) acc = acc + mul<T>(g, x);
  return acc;
}

template <class T>
class PolicyTest : public ::testing::Test {};
using Scalars = ::testing::Types<float, Q15_16>;
TYPED_TEST_SUITE(PolicyTest, Scalars);

TYPED_TEST(PolicyTest, SameResultWithinResolution) {
  // 100 · (0.75 · 2.5) = 187.5, exact in both.
  EXPECT_DOUBLE_EQ(to_double(accumulate_gain<TypeParam>(0.75, 2.5, 100)), 187.5);
}

TYPED_TEST(PolicyTest, ClampSaturates) {
  const auto lo = from_double<TypeParam>(-2.5);
  const auto hi = from_double<TypeParam>(2.5);
  EXPECT_DOUBLE_EQ(to_double(clamp(from_double<TypeParam>(7.0), lo, hi)), 2.5);
  EXPECT_DOUBLE_EQ(to_double(clamp(from_double<TypeParam>(-7.0), lo, hi)), -2.5);
  EXPECT_DOUBLE_EQ(to_double(clamp(from_double<TypeParam>(1.0), lo, hi)), 1.0);
}

}  // namespace
}  // namespace mrd::num
