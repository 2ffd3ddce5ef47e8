// Coil I²t (coil_i2t.hpp): the first-order mean square of the coil current
// against the closed form, and the ceiling it derates, for both numeric
// builds. Constants of the hardware plant's coil: τ = 1200 s, I_r = 2.5 A
// (60 K rise, the rating), derating from 80 % of the rated rise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "firmware/core/coil_i2t.hpp"
#include "firmware/core/controller_config.hpp"

namespace mrd::fw {
namespace {

template <class Policy>
class CoilI2tTest : public ::testing::Test {
 protected:
  using Current = typename Formats<Policy>::Current;
  CoilI2tTest() { i2t_.init(1200.0, 1e-3, 2.5, 0.8); }
  /// `seconds` at a constant coil current.
  void hold(double current_a, double seconds) {
    const Current i = num::from_double<Current>(current_a);
    const auto n = static_cast<std::uint64_t>(std::llround(seconds * 1000.0));
    for (std::uint64_t k = 0; k < n; ++k) i2t_.step(i);
  }
  double m() const { return num::to_double(i2t_.mean_square_a2()); }
  double ceiling() const { return num::to_double(i2t_.ceiling_a()); }
  CoilI2t<Policy> i2t_;
};
using Policies = ::testing::Types<num::Float32Policy, num::Fixed32Policy>;
TYPED_TEST_SUITE(CoilI2tTest, Policies);

TYPED_TEST(CoilI2tTest, MeanSquareRisesWithTheCoilsTimeConstant) {
  // 2.5 A for τ = 1200 s: m = 6.25 (1 − e^−1) = 3.9508 A² (63 % of the rated
  // rise); the 16-tick update is exact for a constant current.
  this->hold(2.5, 1200.0);
  EXPECT_NEAR(this->m(), 6.25 * (1.0 - std::exp(-1.0)), 0.01) << TypeParam::kName;
  EXPECT_NEAR(this->i2t_.heating_fraction(), 1.0 - std::exp(-1.0), 0.002);
  // Below 5.0 A² (80 %): no derating.
  EXPECT_DOUBLE_EQ(this->ceiling(), 2.5);
}

TYPED_TEST(CoilI2tTest, DeratesLinearlyFromEightyPercentToZeroAtTheRating) {
  // 3 A continuous: m(t) = 9 (1 − e^(−t/τ)). At 1100 s m = 5.4014 A², so the
  // ceiling is 2.5 − (m − 5.0)/(0.2·2.5) = 2.5 − 2·0.4014 = 1.697 A.
  this->hold(3.0, 1100.0);
  const double m_1100 = 9.0 * (1.0 - std::exp(-1100.0 / 1200.0));
  EXPECT_NEAR(this->m(), m_1100, 0.01);
  EXPECT_NEAR(this->ceiling(), 2.5 - 2.0 * (m_1100 - 5.0), 0.02);
  // At 1500 s m = 9 (1 − e^−1.25) = 6.42 A² > 6.25 A²: the rating, 0 A allowed.
  this->hold(3.0, 400.0);
  EXPECT_GT(this->m(), 6.25);
  EXPECT_DOUBLE_EQ(this->ceiling(), 0.0);
  // reset(): a coil at ambient.
  this->i2t_.reset();
  EXPECT_DOUBLE_EQ(this->m(), 0.0);
  EXPECT_DOUBLE_EQ(this->ceiling(), 2.5);
}

TYPED_TEST(CoilI2tTest, ACoilHeldAtItsCeilingSettlesBelowTheRating) {
  // A coil that always carries the ceiling c(m) = 12.5 − 2m (above 5 A²)
  // settles where c² = m: 4m² − 51m + 156.25 = 0, m = 5.119 A² (82 % of the
  // rated rise, 49 K of 60 K), c = 2.263 A. Over 3 h (9 τ) it never passes it.
  double peak_m = 0.0;
  for (int s = 0; s < 3 * 3600; ++s) {
    this->hold(this->ceiling(), 1.0);
    peak_m = std::max(peak_m, this->m());
  }
  const double m_eq = (51.0 - std::sqrt(51.0 * 51.0 - 16.0 * 156.25)) / 8.0;
  EXPECT_NEAR(this->m(), m_eq, 0.02);
  EXPECT_NEAR(this->ceiling(), 12.5 - 2.0 * m_eq, 0.03);
  EXPECT_LT(peak_m, 6.25 * 0.85);
}

TEST(CoilI2tConfig, DefaultsMatchTheHardwareCoil) {
  const ControllerConfig c;
  EXPECT_DOUBLE_EQ(c.coil_thermal_time_constant_s, 20.0 * 60.0);  // τ = 20 min
  EXPECT_DOUBLE_EQ(c.rated_current_a, 2.5);                        // 60 K at 2.5 A continuous
  EXPECT_DOUBLE_EQ(c.coil_derate_fraction, 0.8);
}

}  // namespace
}  // namespace mrd::fw
