// ODBDCO current logic (§6.3, Phillips & Spencer 2012) held to the coil's
// rating: every branch of the law in odbdco.hpp, its direction hysteresis,
// target dwell and rest release, its limits, and the validation of its
// parameters, for both numeric builds.
#include <gtest/gtest.h>

#include <utility>

#include "firmware/core/controller_config.hpp"
#include "firmware/core/odbdco.hpp"

namespace mrd::fw {
namespace {

template <class Policy>
class OdbdcoTest : public ::testing::Test {
 protected:
  using Force = typename Formats<Policy>::Force;
  using Current = typename Formats<Policy>::Current;
  using Velocity = typename Formats<Policy>::Velocity;

  // The defaults of ControllerConfig at T = 1 ms: I_od = 10 A, I_bd = −10 A,
  // I_band = 0.1 A, F_db = 2 kN, v_on = 6 mm/s, v_off = 3 mm/s, dwell 30
  // ticks, rest 1000 ticks.
  static OdbdcoParams<Policy> params() {
    OdbdcoParams<Policy> p;
    p.overdrive_a = num::from_double<Current>(10.0);
    p.backdrive_a = num::from_double<Current>(-10.0);
    p.band_a = num::from_double<Current>(0.1);
    p.deadband_n = num::from_double<Force>(2000.0);
    p.velocity_on = num::from_double<Velocity>(6e-3 * 1e-3);
    p.velocity_off = num::from_double<Velocity>(3e-3 * 1e-3);
    p.dwell_ticks = 30;
    p.rest_ticks = 1000;
    return p;
  }
  /// One tick of `law` with SI doubles; velocity in m/s at T = 1 ms; I_c = `ceiling_a`.
  static OdbdcoDecision<Policy> tick(Odbdco<Policy>& law, double fd_n, double fm_n, double coil_a, double v_m_s,
                                     double ceiling_a = 2.5) {
    return law.step(params(), num::from_double<Force>(fd_n), num::from_double<Force>(fm_n),
                    num::from_double<Current>(coil_a), num::from_double<Velocity>(v_m_s * 1e-3),
                    num::from_double<Current>(ceiling_a));
  }
  /// The first tick of a fresh law (target 0 A, free to change).
  static OdbdcoDecision<Policy> decide(double fd_n, double fm_n, double coil_a, double v_m_s, double ceiling_a = 2.5) {
    Odbdco<Policy> law;
    law.reset();
    return tick(law, fd_n, fm_n, coil_a, v_m_s, ceiling_a);
  }
  static double amps(const OdbdcoDecision<Policy>& d) { return num::to_double(d.command_a); }
};
using Policies = ::testing::Types<num::Float32Policy, num::Fixed32Policy>;
TYPED_TEST_SUITE(OdbdcoTest, Policies);

TYPED_TEST(OdbdcoTest, OverDrivesOnlyWhileTheCoilIsShortOfTheRatedCurrent) {
  // Moving up at 50 mm/s, F_d = 100 kN, F_m = 50 kN: e = 50 kN > 2 kN → target I_c = 2.5 A.
  // Coil at 0 A < 2.5 − 0.1: voltage forcing at I_od.
  const auto d = this->decide(100e3, 50e3, 0.0, 0.05);
  EXPECT_EQ(d.branch, OdbdcoBranch::kOverDrive);
  EXPECT_DOUBLE_EQ(this->amps(d), 10.0);
  // Mirror image: moving down, both forces negative.
  const auto m = this->decide(-100e3, -50e3, 0.0, -0.05);
  EXPECT_EQ(m.branch, OdbdcoBranch::kOverDrive);
  EXPECT_DOUBLE_EQ(this->amps(m), 10.0);
  // The next tick of a law whose target is I_c (set at tick 0 with the coil at 0 A).
  auto next = [&](double coil) {
    Odbdco<TypeParam> law;
    law.reset();
    EXPECT_EQ(this->tick(law, 100e3, 50e3, 0.0, 0.05).branch, OdbdcoBranch::kOverDrive);
    EXPECT_TRUE(law.target_on());
    const auto r = this->tick(law, 100e3, 50e3, coil, 0.05);
    return std::make_pair(r, this->tick(law, 100e3, 50e3, coil, 0.05));
  };
  // Coil at 2.39 A, still short of 2.4 A: forcing.
  EXPECT_DOUBLE_EQ(this->amps(next(2.39).first), 10.0);
  // Within ±0.1 A of 2.5 A: the target itself, never more.
  for (double coil : {2.41, 2.5, 2.59}) {
    const auto t = next(coil).first;
    EXPECT_EQ(t.branch, OdbdcoBranch::kTarget) << coil;
    EXPECT_NEAR(this->amps(t), 2.5, 1e-6) << coil;
  }
  // Above 2.6 A the coil is pulled down to the rating: straight after
  // over-drive one tick at the target (no +10 A → −10 A jump), then back-drive.
  const auto [b1, b2] = next(2.7);
  EXPECT_EQ(b1.branch, OdbdcoBranch::kTarget);
  EXPECT_NEAR(this->amps(b1), 2.5, 1e-6);
  EXPECT_EQ(b2.branch, OdbdcoBranch::kBackDrive);
  EXPECT_DOUBLE_EQ(this->amps(b2), -10.0);
}

TYPED_TEST(OdbdcoTest, FollowsADeratedCeiling) {
  // I_c = 1 A (the I²t ceiling), target I_c set at tick 0: forcing below 0.9 A,
  // 1 A within the band, back-drive above 1.1 A (after one tick at the target).
  Odbdco<TypeParam> law;
  law.reset();
  EXPECT_DOUBLE_EQ(this->amps(this->tick(law, 100e3, 50e3, 0.0, 0.05, 1.0)), 10.0);
  EXPECT_DOUBLE_EQ(this->amps(this->tick(law, 100e3, 50e3, 0.5, 0.05, 1.0)), 10.0);
  EXPECT_NEAR(this->amps(this->tick(law, 100e3, 50e3, 1.0, 0.05, 1.0)), 1.0, 1e-6);
  EXPECT_DOUBLE_EQ(this->amps(this->tick(law, 100e3, 50e3, 1.2, 0.05, 1.0)), -10.0);
  // The ceiling derates further to 0.8 A: the same target now asks for 0.8 A.
  EXPECT_NEAR(this->amps(this->tick(law, 100e3, 50e3, 0.8, 0.05, 0.8)), 0.8, 1e-6);
  // I_c = 0 A (the coil at its rating): the target is 0 A, no forcing up at all.
  const auto z = this->decide(100e3, 50e3, 0.0, 0.05, 0.0);
  EXPECT_EQ(z.branch, OdbdcoBranch::kOff);
  EXPECT_DOUBLE_EQ(this->amps(z), 0.0);
}

TYPED_TEST(OdbdcoTest, BackDrivesWhenTheForceMustShrinkUntilTheCoilIsWithinTheBand) {
  // F_d = 50 kN, F_m = 100 kN: e = −50 kN < −2 kN → target 0 A.
  const auto d = this->decide(50e3, 100e3, 2.0, 0.05);
  EXPECT_EQ(d.branch, OdbdcoBranch::kBackDrive);
  EXPECT_DOUBLE_EQ(this->amps(d), -10.0);
  // Coil at 0.11 A > I_band = 0.1 A: still back-driving.
  EXPECT_DOUBLE_EQ(this->amps(this->decide(50e3, 100e3, 0.11, 0.05)), -10.0);
  // Coil at 0.09 A: no current.
  const auto off = this->decide(50e3, 100e3, 0.09, 0.05);
  EXPECT_EQ(off.branch, OdbdcoBranch::kOff);
  EXPECT_DOUBLE_EQ(this->amps(off), 0.0);
  // Coil already negative (overshoot of the back-drive): no current, never
  // forcing either way (|i| magnetizes the fluid, and the target is 0 A).
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

TYPED_TEST(OdbdcoTest, AMoveThatCrossesTheDesiredForceEndsAtThePresentCurrent) {
  // Target 0 A (fresh law), moving up, F_m = 99 kN just short of F_d = 100 kN
  // (e = +1 kN): the force has crossed F_d on the way down, so the target
  // latches the present 1.7 A and the command is 1.7 A.
  const auto l = this->decide(100e3, 99e3, 1.7, 0.05);
  EXPECT_EQ(l.branch, OdbdcoBranch::kTarget);
  EXPECT_NEAR(this->amps(l), 1.7, 1e-6);
  // A coil at 3.2 A latches no more than I_c = 2.5 A: pulled down to it.
  EXPECT_DOUBLE_EQ(this->amps(this->decide(100e3, 99e3, 3.2, 0.05)), -10.0);
  // A coil reading 0.05 A (within I_band of 0 A) latches nothing: 0 A.
  const auto z = this->decide(100e3, 99e3, 0.05, 0.05);
  EXPECT_EQ(z.branch, OdbdcoBranch::kOff);
  EXPECT_DOUBLE_EQ(this->amps(z), 0.0);

  // Target I_c at tick 0 (coil 0 A); the force overshoots F_d (e = −1.5 kN)
  // with the coil at 1.7 A on tick 1: the move up ends there at once (the
  // dwell does not hold a move that has crossed), and 1.7 A is kept.
  Odbdco<TypeParam> law;
  law.reset();
  ASSERT_EQ(this->tick(law, 100e3, 50e3, 0.0, 0.05).branch, OdbdcoBranch::kOverDrive);
  const auto x = this->tick(law, 100e3, 101.5e3, 1.7, 0.05);
  EXPECT_EQ(x.branch, OdbdcoBranch::kTarget);
  EXPECT_NEAR(this->amps(x), 1.7, 1e-6);
  EXPECT_FALSE(law.target_on());
  // Inside the force deadband a ±20 mA bias on the reading never re-latches
  // (|i_m − I_t| ≤ I_band): 1.7 A for 10 s.
  for (int k = 0; k < 10000; ++k) {
    const double bias = (k % 2 == 0) ? 0.02 : -0.02;
    ASSERT_NEAR(this->amps(this->tick(law, 100e3, 101.5e3, 1.7 + bias, 0.05)), 1.7, 1e-6) << k;
  }
  // The coil falls to 1.2 A (a drive hiccup) with the force still inside the
  // deadband: more than I_band away, so the target latches 1.2 A.
  EXPECT_NEAR(this->amps(this->tick(law, 100e3, 101.5e3, 1.2, 0.05)), 1.2, 1e-6);
}

TYPED_TEST(OdbdcoTest, DirectionHasHysteresis) {
  Odbdco<TypeParam> law;
  law.reset();
  // 5 mm/s < v_on = 6 mm/s: direction unknown, the target stays 0 A even for F_d = 150 kN.
  EXPECT_DOUBLE_EQ(this->amps(this->tick(law, 150e3, 10e3, 0.0, 0.005)), 0.0);
  EXPECT_EQ(law.direction(), 0);
  // 6.5 mm/s: moving up; e = 140 kN → target 2.5 A, forcing.
  EXPECT_DOUBLE_EQ(this->amps(this->tick(law, 150e3, 10e3, 0.0, 0.0065)), 10.0);
  EXPECT_EQ(law.direction(), 1);
  // 4 mm/s > v_off = 3 mm/s: still moving up.
  (void)this->tick(law, 150e3, 10e3, 0.5, 0.004);
  EXPECT_EQ(law.direction(), 1);
  // 2.5 mm/s < v_off: unknown; the target 2.5 A is kept (no decision).
  EXPECT_NEAR(this->amps(this->tick(law, 150e3, 10e3, 2.5, 0.0025)), 2.5, 1e-6);
  EXPECT_EQ(law.direction(), 0);
  // −6.5 mm/s: moving down; F_d = +150 kN opposes → target 0 A (after the 30-tick dwell).
  for (int k = 0; k < 40; ++k) (void)this->tick(law, 150e3, 10e3, 0.0, -0.0065);
  EXPECT_EQ(law.direction(), -1);
  EXPECT_TRUE(law.target_off());
}

TYPED_TEST(OdbdcoTest, AtRestTheTargetDecaysToZeroAndASensorBiasIsNotIntegrated) {
  Odbdco<TypeParam> law;
  law.reset();
  ASSERT_EQ(this->tick(law, 150e3, 10e3, 2.5, 0.05).branch, OdbdcoBranch::kTarget);  // 2.5 A latched
  // At rest (v = 0), with F_d = −7.9 kN (RILD at 3 mm) and the coil reading 2.5 A:
  // the target is kept for rest_ticks = 1000 ticks, then released.
  for (int k = 1; k <= 1000; ++k) {
    ASSERT_NEAR(this->amps(this->tick(law, -7.9e3, 0.0, 2.5, 0.0)), 2.5, 1e-6) << k;
  }
  EXPECT_DOUBLE_EQ(this->amps(this->tick(law, -7.9e3, 0.0, 2.5, 0.0)), -10.0);  // target 0: pull down
  EXPECT_TRUE(law.target_off());
  // The coil reads +20 mA or −20 mA of bias for 600 s: the command stays 0 A
  // (a hold commanding u = i_m would close a loop that integrates the bias).
  for (int k = 0; k < 600000; ++k) {
    const double bias = (k % 2 == 0) ? 0.02 : -0.02;
    const auto d = this->tick(law, -7.9e3, 0.0, bias, 0.0);
    ASSERT_EQ(d.branch, OdbdcoBranch::kOff) << k;
    ASSERT_EQ(this->amps(d), 0.0) << k;
  }
}

TYPED_TEST(OdbdcoTest, TheTargetDwellsThirtyTicksBetweenChanges) {
  Odbdco<TypeParam> law;
  law.reset();
  // Tick 0: target 2.5 A (the coil at 2.5 A with the force short of F_d: latched).
  ASSERT_EQ(this->tick(law, 100e3, 50e3, 2.5, 0.05).branch, OdbdcoBranch::kTarget);
  // Ticks 1–29 ask for 0 A (e = −50 kN) but the target holds 2.5 A.
  for (int k = 1; k < 30; ++k) {
    const auto d = this->tick(law, 50e3, 100e3, 2.5, 0.05);
    ASSERT_EQ(d.branch, OdbdcoBranch::kTarget) << k;
    ASSERT_NEAR(this->amps(d), 2.5, 1e-6) << k;
  }
  // Tick 30: 30 ticks after the change, the target goes to 0 A.
  EXPECT_EQ(this->tick(law, 50e3, 100e3, 2.5, 0.05).branch, OdbdcoBranch::kBackDrive);
  // And back on only 30 ticks later: ticks 31–59 keep 0 A.
  for (int k = 31; k < 60; ++k) ASSERT_EQ(this->amps(this->tick(law, 100e3, 50e3, 0.0, 0.05)), 0.0) << k;
  EXPECT_EQ(this->tick(law, 100e3, 50e3, 0.0, 0.05).branch, OdbdcoBranch::kOverDrive);
}

TYPED_TEST(OdbdcoTest, NeverJumpsBetweenOverDriveAndBackDriveInOneTick) {
  Odbdco<TypeParam> law;
  law.reset();
  // Over-drive on the way to 2.5 A (coil at 0 A, then 1 A), held past the dwell.
  ASSERT_DOUBLE_EQ(this->amps(this->tick(law, 100e3, 50e3, 0.0, 0.05)), 10.0);
  for (int k = 1; k < 30; ++k) ASSERT_DOUBLE_EQ(this->amps(this->tick(law, 100e3, 50e3, 1.0, 0.05)), 10.0);
  // F_d turns against the motion (−50 kN moving up): target 0 A with the coil
  // at 1 A: one tick at the target (0 A), then back-drive.
  const auto via = this->tick(law, -50e3, 50e3, 1.0, 0.05);
  EXPECT_EQ(via.branch, OdbdcoBranch::kOff);
  EXPECT_DOUBLE_EQ(this->amps(via), 0.0);
  EXPECT_DOUBLE_EQ(this->amps(this->tick(law, -50e3, 50e3, 1.0, 0.05)), -10.0);
  // Still back-driving when, after the dwell, the target goes up again with
  // the coil read at 0 A: one tick at the target (2.5 A), then over-drive.
  for (int k = 0; k < 29; ++k) ASSERT_DOUBLE_EQ(this->amps(this->tick(law, -50e3, 50e3, 1.0, 0.05)), -10.0);
  const auto up = this->tick(law, 100e3, 50e3, 0.0, 0.05);
  EXPECT_EQ(up.branch, OdbdcoBranch::kTarget);
  EXPECT_NEAR(this->amps(up), 2.5, 1e-6);
  EXPECT_DOUBLE_EQ(this->amps(this->tick(law, 100e3, 50e3, 0.0, 0.05)), 10.0);
}

TYPED_TEST(OdbdcoTest, CommandStaysWithinBackDriveAndOverDriveLevels) {
  // A grid over forces (±500 kN), coil currents (±30 A) and velocities, each
  // from a fresh law and as the next tick of one running law.
  Odbdco<TypeParam> running;
  running.reset();
  int n = 0;
  for (double fd = -500e3; fd <= 500e3; fd += 25e3) {
    for (double fm = -500e3; fm <= 500e3; fm += 50e3) {
      for (double i = -30.0; i <= 30.0; i += 2.5) {
        for (double v : {-0.3, -0.0005, 0.0, 0.0005, 0.3}) {
          for (const auto& d : {this->decide(fd, fm, i, v), this->tick(running, fd, fm, i, v)}) {
            const double a = this->amps(d);
            ASSERT_GE(a, -10.0);
            ASSERT_LE(a, 10.0);
            // Negative current only to back-drive, and only while the coil is above the band.
            if (a < 0.0) {
              ASSERT_EQ(d.branch, OdbdcoBranch::kBackDrive);
              ASSERT_GT(i, 0.1);
            }
            // Beyond the rated 2.5 A only to over-drive, and only while the coil is short of it.
            if (a > 2.5) {
              ASSERT_EQ(d.branch, OdbdcoBranch::kOverDrive);
              ASSERT_LT(i, 2.4);
            }
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
  // The steady ceiling is the damper's rated current, the passive-on 2.5 A.
  EXPECT_DOUBLE_EQ(c.rated_current_a, kPassiveOnCurrent_a);
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
  EXPECT_EQ(bad([](ControllerConfig& c) { c.rated_current_a = 10.5; }), ConfigError::kCurrentLevels);  // > I_od
  EXPECT_EQ(bad([](ControllerConfig& c) { c.rated_current_a = 0.0; }), ConfigError::kCurrentLevels);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.current_band_a = 2.5; }), ConfigError::kCurrentLevels);  // ≥ I_r
  EXPECT_EQ(bad([](ControllerConfig& c) { c.current_band_a = 0.0; }), ConfigError::kCurrentLevels);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.fallback_current_a = -1.0; }), ConfigError::kCurrentLevels);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.force_deadband_n = -1.0; }), ConfigError::kDeadband);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.target_dwell_s = -0.01; }), ConfigError::kDeadband);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.rest_release_s = 100.0; }), ConfigError::kDeadband);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.velocity_off_m_s = 0.01; }), ConfigError::kVelocityFilter);  // > v_on
  EXPECT_EQ(bad([](ControllerConfig& c) { c.coil_derate_fraction = 1.0; }), ConfigError::kThermal);
  EXPECT_EQ(bad([](ControllerConfig& c) { c.coil_thermal_time_constant_s = 0.0; }), ConfigError::kThermal);
}

}  // namespace
}  // namespace mrd::fw
