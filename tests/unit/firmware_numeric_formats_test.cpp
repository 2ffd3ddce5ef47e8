// The core's number formats (numeric_formats.hpp) and the run-time float
// conversions of num/policy.hpp that carry sensor values into them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "firmware/core/numeric_formats.hpp"

namespace mrd::fw {
namespace {

using Fx = Formats<num::Fixed32Policy>;

TEST(FirmwareFormats, FromFloatRoundsToTheNearestStep) {
  // Q3.28: 0.1 m · 2^28 = 26 843 545.6 → raw 26 843 546 (float 0.1f is
  // 0.100000001490116, ·2^28 = 26 843 546.0 exactly).
  EXPECT_EQ(num::from_float<Fx::Disp>(0.1f).raw(), 26843546);
  EXPECT_EQ(num::from_float<Fx::Disp>(-0.1f).raw(), -26843546);
  // Q19.12: 1234.5 N · 4096 = 5 056 512 exactly.
  EXPECT_EQ(num::from_float<Fx::Force>(1234.5f).raw(), 5056512);
  // Q7.24: 2.5 A · 2^24 = 41 943 040 exactly.
  EXPECT_EQ(num::from_float<Fx::Current>(2.5f).raw(), 41943040);
  // Half a step rounds away from zero: 2^−29 m is half of Q3.28's 2^−28.
  EXPECT_EQ(num::from_float<Fx::Disp>(std::ldexp(1.0f, -29)).raw(), 1);
  EXPECT_EQ(num::from_float<Fx::Disp>(-std::ldexp(1.0f, -29)).raw(), -1);
}

TEST(FirmwareFormats, FromFloatSaturatesAndMapsNanToZero) {
  EXPECT_EQ(num::from_float<Fx::Disp>(9.0f), Fx::Disp::max());  // above 8 m
  EXPECT_EQ(num::from_float<Fx::Disp>(-9.0f), Fx::Disp::lowest());
  EXPECT_EQ(num::from_float<Fx::Force>(std::numeric_limits<float>::infinity()), Fx::Force::max());
  EXPECT_EQ(num::from_float<Fx::Force>(-std::numeric_limits<float>::infinity()), Fx::Force::lowest());
  EXPECT_EQ(num::from_float<Fx::Force>(1e30f), Fx::Force::max());
  EXPECT_EQ(num::from_float<Fx::Current>(std::numeric_limits<float>::quiet_NaN()).raw(), 0);
  // Float passes through unchanged.
  EXPECT_EQ(num::from_float<float>(0.125f), 0.125f);
}

TEST(FirmwareFormats, ToFloatIsTheInverseWithinFloatPrecision) {
  for (float v : {0.0f, 0.2921f, -0.2921f, 1e-6f}) {
    EXPECT_NEAR(num::to_float(num::from_float<Fx::Disp>(v)), v, 4e-9f);
  }
  for (float v : {0.0f, 199999.5f, -4100.25f}) EXPECT_NEAR(num::to_float(num::from_float<Fx::Force>(v)), v, 0.02f);
  EXPECT_EQ(num::to_float(num::from_float<Fx::Current>(-10.0f)), -10.0f);
}

TEST(FirmwareFormats, RangesMatchTheDocumentedTable) {
  EXPECT_DOUBLE_EQ(Fx::Disp::max_value(), 8.0 - std::ldexp(1.0, -28));
  EXPECT_DOUBLE_EQ(Fx::Force::lowest_value(), -524288.0);
  EXPECT_DOUBLE_EQ(Fx::Current::lowest_value(), -128.0);
  EXPECT_DOUBLE_EQ(Fx::Coef::lowest_value(), -4.0);
  EXPECT_DOUBLE_EQ(Fx::Gain::lowest_value(), -8388608.0);
  EXPECT_TRUE(representable<Fx::Gain>(3287e3 * 0.8));
  EXPECT_FALSE(representable<Fx::Gain>(1e7));
  EXPECT_TRUE(representable<float>(1e7));
  EXPECT_FALSE(representable<float>(std::numeric_limits<double>::quiet_NaN()));
  // Square, Q9.22 A²: ±512 A², 2^−22 A² = 2.4e−7 A²; holds (15 A)² = 225 A².
  EXPECT_DOUBLE_EQ(Fx::Square::lowest_value(), -512.0);
  EXPECT_DOUBLE_EQ(Fx::Square::epsilon().to_double(), std::ldexp(1.0, -22));
  EXPECT_TRUE(representable<Fx::Square>(15.0 * 15.0));
}

TEST(FirmwareFormats, SquareOfACurrentRoundsOnceIntoQ9_22) {
  // 2.5 A · 2.5 A = 6.25 A² exactly: raw 6.25 · 2^22 = 26 214 400.
  const Fx::Current i = num::from_float<Fx::Current>(2.5f);
  EXPECT_EQ(num::mul<Fx::Square>(i, i).raw(), 26214400);
  // 30 A (the sensor guard's limit): 900 A² saturates at the top of Q9.22.
  const Fx::Current big = num::from_float<Fx::Current>(30.0f);
  EXPECT_EQ(num::mul<Fx::Square>(big, big), Fx::Square::max());
}

}  // namespace
}  // namespace mrd::fw
