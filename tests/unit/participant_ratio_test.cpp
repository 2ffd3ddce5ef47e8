// Participant ratio, Eq. 5.6–5.9 with Table 5.6.
#include "mrd/physics/participant_ratio.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mrd::physics {
namespace {

// Fully mixed (SQ = 0): every exponential is 1, so a_PR = a_initial = 1,
// b_PR = a_final = 1, c_PR = a_rise = 5.474.
TEST(ParticipantRatio, FullyMixedCoefficients) {
  const auto c = pr_coefficients({}, 0.0);
  EXPECT_DOUBLE_EQ(c.a_pr, 1.0);
  EXPECT_DOUBLE_EQ(c.b_pr, 1.0);
  EXPECT_DOUBLE_EQ(c.c_pr, 5.474);
}

// Fully settled (SQ = 1), by hand:
//   a_PR = 0.10 + 0.90·e^−7    = 0.10 + 0.90·0.000911882 = 0.100821
//   b_PR = 0.605 + 0.395·e^−4.5 = 0.605 + 0.395·0.011109   = 0.609388
//   c_PR = 5.474·e^−3.65                                   = 0.142275
TEST(ParticipantRatio, FullySettledCoefficients) {
  const auto c = pr_coefficients({}, 1.0);
  EXPECT_NEAR(c.a_pr, 0.100821, 1e-6);
  EXPECT_NEAR(c.b_pr, 0.609388, 1e-6);
  EXPECT_NEAR(c.c_pr, 0.142275, 1e-6);
}

TEST(ParticipantRatio, NoMotionKeepsTheInitialRatio) {
  ParticipantRatio pr({}, 0.6);
  const double a = pr.coefficients().a_pr;
  EXPECT_DOUBLE_EQ(pr.pr(), a);
  for (int i = 0; i < 1000; ++i) pr.step(0.0, 1e-3);
  EXPECT_DOUBLE_EQ(pr.pr(), a);
}

TEST(ParticipantRatio, MuchDisplacedVolumeReachesTheFinalRatio) {
  ParticipantRatio pr({}, 1.0);
  pr.add_displaced_volume_m3(10.0);  // 10 m³ = 10 000 L: c_PR·∫Q ≈ 1400
  EXPECT_NEAR(pr.pr(), pr.coefficients().b_pr, 1e-12);
}

// PR rises monotonically from a_PR to b_PR as the damper moves, whichever
// the direction of motion (Q uses |v|).
TEST(ParticipantRatio, MonotoneRecoveryForEitherDirection) {
  ParticipantRatio pr({}, 1.0);
  double last = pr.pr();
  for (int i = 0; i < 200000; ++i) {
    const double v = (i / 500) % 2 == 0 ? 0.05 : -0.05;
    const double now = pr.step(v, 1e-3);
    ASSERT_GE(now, last);
    last = now;
  }
  EXPECT_GT(last, pr.coefficients().a_pr);
  EXPECT_LE(last, pr.coefficients().b_pr);
}

// ∫Q dt = |v|·A·t: 0.05 m/s for 2 s through 0.0312 m² = 3.12e−3 m³.
TEST(ParticipantRatio, DisplacedVolumeIsIntegralOfFlow) {
  ParticipantRatioParams p;
  p.flow_area_m2 = 0.0312;
  p.volume_unit_m3 = 1.0e-3;
  ParticipantRatio pr(p, 1.0);
  for (int i = 0; i < 2000; ++i) pr.step(-0.05, 1e-3);
  EXPECT_NEAR(pr.displaced_volume_m3(), 0.05 * 0.0312 * 2.0, 1e-12);
  // Eq. 5.9 with ∫Q in litres (3.12 L).
  const auto& c = pr.coefficients();
  EXPECT_NEAR(pr.pr(), c.b_pr + (c.a_pr - c.b_pr) * std::exp(-c.c_pr * 3.12), 1e-12);
}

TEST(ParticipantRatio, ResetStartsANewEpisode) {
  ParticipantRatio pr({}, 1.0);
  pr.add_displaced_volume_m3(0.01);
  pr.reset(0.0);
  EXPECT_DOUBLE_EQ(pr.displaced_volume_m3(), 0.0);
  EXPECT_DOUBLE_EQ(pr.pr(), 1.0);
}

}  // namespace
}  // namespace mrd::physics
