// ODBDCO current logic (§6.3, Phillips & Spencer 2012): every branch of the
// law in odbdco.hpp, its limits, and the validation of its parameters, for
// both numeric builds.
#include <gtest/gtest.h>

#include "firmware/core/controller_config.hpp"
#include "firmware/core/odbdco.hpp"

namespace mrd::fw {
namespace {

template <class Policy>
class OdbdcoTest : public ::testing::Test {
 protected:
  using Force = typename Formats<Policy>::Force;
  using Current = typename Formats<Policy>::Current;
  using Disp = typename Formats<Policy>::Disp;

  // The defaults of ControllerConfig, with I_ceil lowered to 6 A where a test
  // needs the ceiling to differ from I_od.
  OdbdcoParams<Policy> params(double ceiling_a = 10.0) const {
    OdbdcoParams<Policy> p;
    p.overdrive_a = num::from_double<Current>(10.0);
    p.ceiling_a = num::from_double<Current>(ceiling_a);
    p.backdrive_a = num::from_double<Current>(-10.0);
    p.release_a = num::from_double<Current>(0.05);
    p.deadband_n = num::from_double<Force>(2000.0);
    p.velocity_deadband_m = num::from_double<Disp>(1e-3 * 1e-3);  // 1 mm/s at 1 kHz
    return p;
  }
  /// Runs the law with SI doubles; velocity in m/s at T = 1 ms.
  OdbdcoDecision<Policy> decide(double fd_n, double fm_n, double coil_a, double v_m_s, double ceiling_a = 10.0) const {
    return odbdco<Policy>(params(ceiling_a), num::from_double<Force>(fd_n), num::from_double<Force>(fm_n),
                          num::from_double<Current>(coil_a), num::from_double<Disp>(v_m_s * 1e-3));
  }
  static double amps(const OdbdcoDecision<Policy>& d) { return num::to_double(d.command_a); }
};
using Policies = ::testing::Types<num::Float32Policy, num::Fixed32Policy>;
TYPED_TEST_SUITE(OdbdcoTest, Policies);

TYPED_TEST(OdbdcoTest, OverDrivesWhenTheForceMustGrow) {
  // Moving up at 50 mm/s, F_d = 100 kN, F_m = 50 kN: e = 50 kN > 2 kN.
  const auto d = this->decide(100e3, 50e3, 1.0, 0.05);
  EXPECT_EQ(d.branch, OdbdcoBranch::kOverDrive);
  EXPECT_DOUBLE_EQ(this->amps(d), 10.0);  // 4× the nominal 2.5 A
  // Mirror image: moving down, both forces negative.
  const auto m = this->decide(-100e3, -50e3, 1.0, -0.05);
  EXPECT_EQ(m.branch, OdbdcoBranch::kOverDrive);
  EXPECT_DOUBLE_EQ(this->amps(m), 10.0);
}

TYPED_TEST(OdbdcoTest, OverDriveStopsAtTheCoilCurrentCeiling) {
  // I_ceil = 6 A: below it the command is I_od, at or above it I_ceil.
  EXPECT_DOUBLE_EQ(this->amps(this->decide(100e3, 50e3, 5.9, 0.05, 6.0)), 10.0);
  const auto d = this->decide(100e3, 50e3, 6.0, 0.05, 6.0);
  EXPECT_EQ(d.branch, OdbdcoBranch::kOverDrive);
  EXPECT_DOUBLE_EQ(this->amps(d), 6.0);
  EXPECT_DOUBLE_EQ(this->amps(this->decide(100e3, 50e3, 8.0, 0.05, 6.0)), 6.0);
}

TYPED_TEST(OdbdcoTest, BackDrivesWhenTheForceMustShrinkUntilTheCoilHasFallen) {
  // F_d = 50 kN, F_m = 100 kN: e = −50 kN < −2 kN.
  const auto d = this->decide(50e3, 100e3, 2.0, 0.05);
  EXPECT_EQ(d.branch, OdbdcoBranch::kBackDrive);
  EXPECT_DOUBLE_EQ(this->amps(d), -10.0);
  // Coil at 0.06 A > I_rel = 0.05 A: still back-driving.
  EXPECT_DOUBLE_EQ(this->amps(this->decide(50e3, 100e3, 0.06, 0.05)), -10.0);
  // Coil at 0.04 A ≤ I_rel: no current.
  const auto off = this->decide(50e3, 100e3, 0.04, 0.05);
  EXPECT_EQ(off.branch, OdbdcoBranch::kOff);
  EXPECT_DOUBLE_EQ(this->amps(off), 0.0);
  // Coil already negative (overshoot of the back-drive): no current, never
  // more back-drive (|i| magnetizes the fluid either way).
  EXPECT_DOUBLE_EQ(this->amps(this->decide(50e3, 100e3, -0.8, 0.05)), 0.0);
  // Mirror image moving down.
  EXPECT_DOUBLE_EQ(this->amps(this->decide(-50e3, -100e3, 2.0, -0.05)), -10.0);
}

TYPED_TEST(OdbdcoTest, NoCurrentForAForceTheDamperCannotProduce) {
  // Moving up, the damper can only push with F > 0; F_d = −80 kN opposes it.
  const auto d = this->decide(-80e3, 20e3, 3.0, 0.05);
  EXPECT_EQ(d.branch, OdbdcoBranch::kBackDrive);  // coil still at 3 A: pull it down
  EXPECT_DOUBLE_EQ(this->amps(d), -10.0);
  const auto off = this->decide(-80e3, 20e3, 0.0, 0.05);
  EXPECT_EQ(off.branch, OdbdcoBranch::kOff);
  EXPECT_DOUBLE_EQ(this->amps(off), 0.0);
  // Moving down, F_d = +80 kN: the same, whatever the measured force.
  EXPECT_DOUBLE_EQ(this->amps(this->decide(80e3, -4e3, 0.0, -0.05)), 0.0);
  EXPECT_DOUBLE_EQ(this->amps(this->decide(80e3, -200e3, 0.0, -0.05)), 0.0);
  // F_d = 0 exactly: nothing to produce.
  EXPECT_DOUBLE_EQ(this->amps(this->decide(0.0, 10e3, 0.0, 0.05)), 0.0);
}

TYPED_TEST(OdbdcoTest, HoldsThePresentCurrentInsideTheForceDeadband) {
  // e = 100 − 99 = 1 kN ≤ 2 kN; e = −1.5 kN ≥ −2 kN.
  const auto d = this->decide(100e3, 99e3, 3.2, 0.05);
  EXPECT_EQ(d.branch, OdbdcoBranch::kHold);
  EXPECT_NEAR(this->amps(d), 3.2, 1e-6);
  EXPECT_NEAR(this->amps(this->decide(100e3, 101.5e3, 1.7, 0.05)), 1.7, 1e-6);
  // Hold never commands more than I_ceil nor a negative current.
  EXPECT_DOUBLE_EQ(this->amps(this->decide(100e3, 99e3, 12.0, 0.05)), 10.0);
  EXPECT_DOUBLE_EQ(this->amps(this->decide(100e3, 99e3, -0.5, 0.05)), 0.0);
}

TYPED_TEST(OdbdcoTest, HoldsWhenTheDirectionOfMotionIsUnknown) {
  // |v| = 0.5 mm/s < v_db = 1 mm/s: no decision about feasibility; keep 1.1 A.
  const auto d = this->decide(150e3, 10e3, 1.1, 0.0005);
  EXPECT_EQ(d.branch, OdbdcoBranch::kHold);
  EXPECT_NEAR(this->amps(d), 1.1, 1e-6);
  EXPECT_NEAR(this->amps(this->decide(-150e3, 10e3, 1.1, -0.0005)), 1.1, 1e-6);
  // Just outside the deadband the law decides again.
  EXPECT_DOUBLE_EQ(this->amps(this->decide(150e3, 10e3, 1.1, 0.0011)), 10.0);
}

TYPED_TEST(OdbdcoTest, CommandStaysWithinBackDriveAndOverDriveLevels) {
  // A grid over forces (±500 kN), coil currents (±30 A) and velocities.
  int n = 0;
  for (double fd = -500e3; fd <= 500e3; fd += 25e3) {
    for (double fm = -500e3; fm <= 500e3; fm += 50e3) {
      for (double i = -30.0; i <= 30.0; i += 2.5) {
        for (double v : {-0.3, -0.0005, 0.0, 0.0005, 0.3}) {
          const auto d = this->decide(fd, fm, i, v);
          const double a = this->amps(d);
          ASSERT_GE(a, -10.0);
          ASSERT_LE(a, 10.0);
          // Negative current only to back-drive, and only while the coil is above I_rel.
          if (a < 0.0) {
            ASSERT_EQ(d.branch, OdbdcoBranch::kBackDrive);
            ASSERT_GT(i, 0.05);
          }
          ++n;
        }
      }
    }
  }
  EXPECT_EQ(n, 41 * 21 * 25 * 5);
}

TEST(OdbdcoConfig, DefaultsBoundOverDriveByTheDrive) {
  const ControllerConfig c;
  EXPECT_EQ(validate_config<num::Float32Policy>(c), ConfigError::kNone);
  EXPECT_EQ(validate_config<num::Fixed32Policy>(c), ConfigError::kNone);
  // I_od = the ±10 A command range (10 V at 1 V/A), inside 15 A continuous.
  EXPECT_DOUBLE_EQ(c.overdrive_current_a, c.command_limit_a);
  EXPECT_LT(c.command_limit_a, c.drive_continuous_limit_a);
  EXPECT_DOUBLE_EQ(c.backdrive_current_a, -c.command_limit_a);
}

TEST(OdbdcoConfig, RejectsLevelsOutsideTheDrivesLimits) {
  auto bad = [](auto edit) {
    ControllerConfig c;
    edit(c);
    return validate_config<num::Float32Policy>(c);
  };
  EXPECT_EQ(bad([](ControllerConfig& c) { c.overdrive_current_a = 12.0; }), ConfigError::kCurrentLevels);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.overdrive_current_a = 2.0; }), ConfigError::kCurrentLevels);  // < I_nom
  EXPECT_EQ(bad([](ControllerConfig& c) {
              c.command_limit_a = 20.0;
              c.overdrive_current_a = 20.0;
            }),
            ConfigError::kCurrentLevels);  // 20 A > 15 A continuous
  EXPECT_EQ(bad([](ControllerConfig& c) { c.backdrive_current_a = 1.0; }), ConfigError::kCurrentLevels);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.backdrive_current_a = -11.0; }), ConfigError::kCurrentLevels);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.coil_current_ceiling_a = 10.5; }), ConfigError::kCurrentLevels);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.release_current_a = 2.5; }), ConfigError::kCurrentLevels);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.fallback_current_a = -1.0; }), ConfigError::kCurrentLevels);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.force_deadband_n = -1.0; }), ConfigError::kDeadband);
}

}  // namespace
}  // namespace mrd::fw
