// Bingham plastic damper model, Eq. 4.1–4.4 and 5.10–5.12 with Table 4.1.
#include "mrd/physics/bingham.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mrd::physics {
namespace {

// Hand calculation from Table 4.1 (f_c: 4.1 / 170 kN, 0.7 1/A;
// c_0: 0.0825 / 0.365 kN·s/mm, 1.15 1/A), at v = 0.1 m/s = 100 mm/s
// (above v_TF, so the transition factor is 1):
//   I = 0 A:   f_c = 4.1 kN;  c_0 = 0.0825 kN·s/mm;  F = 4.1 + 8.25 = 12.35 kN
//   I = 1 A:   f_c = 170 − 165.9·e^−0.7  = 170 − 165.9·0.496585 = 87.6165 kN
//              c_0 = 0.365 − 0.2825·e^−1.15 = 0.365 − 0.2825·0.316637 = 0.275550 kN·s/mm
//              F = 87.6165 + 27.5550 = 115.1715 kN
//   I = 2.5 A: f_c = 170 − 165.9·e^−1.75 = 170 − 165.9·0.173774 = 141.1709 kN
//              c_0 = 0.365 − 0.2825·e^−2.875 = 0.365 − 0.2825·0.056416 = 0.349062 kN·s/mm
//              F = 141.1709 + 34.9062 = 176.0771 kN
struct TableCase {
  double current_a;
  double fc_kn;
  double c0_kns_mm;
  double force_kn;
};
constexpr TableCase kTable41[] = {
    {0.0, 4.1, 0.0825, 12.35},
    {1.0, 87.6165, 0.275550, 115.1715},
    {2.5, 141.1709, 0.349062, 176.0771},
};

TEST(Bingham, Table41CoulombViscousAndForce) {
  const BinghamParams p;
  for (const auto& c : kTable41) {
    SCOPED_TRACE(c.current_a);
    EXPECT_NEAR(coulomb_force_n(p, c.current_a) / 1e3, c.fc_kn, 1e-3);
    EXPECT_NEAR(viscous_coeff_ns_m(p, c.current_a) / 1e6, c.c0_kns_mm, 1e-6);
    EXPECT_NEAR(damper_force_n(p, c.current_a, 0.1) / 1e3, c.force_kn, 1e-3);
  }
}

TEST(Bingham, ForceIsOddInVelocity) {
  const BinghamParams p;
  for (double v : {0.001, 0.005, 0.01, 0.05, 0.2}) {
    EXPECT_DOUBLE_EQ(damper_force_n(p, 2.5, -v), -damper_force_n(p, 2.5, v));
  }
}

TEST(Bingham, NegativeCurrentActsByItsMagnitude) {
  const BinghamParams p;
  EXPECT_DOUBLE_EQ(damper_force_n(p, -1.0, 0.1), damper_force_n(p, 1.0, 0.1));
}

// Eq. 4.4 corners: TF = 0 at rest, |v|/v_TF below 10 mm/s, exactly 1 at and
// above 10 mm/s.
TEST(Bingham, TransitionFunctionCorners) {
  const BinghamParams p;
  EXPECT_DOUBLE_EQ(transition_factor(p, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(transition_factor(p, 0.005), 0.5);
  EXPECT_DOUBLE_EQ(transition_factor(p, -0.0025), 0.25);
  EXPECT_DOUBLE_EQ(transition_factor(p, 0.010), 1.0);
  EXPECT_DOUBLE_EQ(transition_factor(p, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(damper_force_n(p, 2.5, 0.0), 0.0);
  // At 5 mm/s and 0 A: TF = 0.5, Bingham = 4100 + 82500·0.005 = 4512.5 N.
  EXPECT_NEAR(damper_force_n(p, 0.0, 0.005), 0.5 * 4512.5, 1e-9);
}

// Eq. 5.10–5.11: PR multiplies only the 'b' parameters. At 0 A the force
// does not depend on PR (the exponential is 1); at high current it scales
// with PR.
TEST(Bingham, ParticipantRatioScalesOnlyTheFieldDependentPart) {
  const BinghamParams p;
  EXPECT_DOUBLE_EQ(coulomb_force_n(p, 0.0, 0.1), 4100.0);
  EXPECT_DOUBLE_EQ(viscous_coeff_ns_m(p, 0.0, 0.1), 82500.0);
  // Hand: f_c(2.5, 0.5) = 0.5·170 + (4.1 − 85)·e^−1.75 = 85 − 80.9·0.173774 = 70.9417 kN
  EXPECT_NEAR(coulomb_force_n(p, 2.5, 0.5) / 1e3, 70.9417, 1e-3);
  EXPECT_DOUBLE_EQ(coulomb_force_n(p, 2.5, 1.0), coulomb_force_n(p, 2.5));
}

}  // namespace
}  // namespace mrd::physics
