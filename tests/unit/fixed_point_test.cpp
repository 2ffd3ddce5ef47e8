// Numeric policies: Fixed<I, F> saturating Q arithmetic and the generic
// helpers that let one block compile for float and fixed point.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

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
