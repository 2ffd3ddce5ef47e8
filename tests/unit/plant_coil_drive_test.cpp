// The hardware plant's coil (R–L(i)) and PWM drive (PI current loop,
// ±72 V bus, 30 A peak / 15 A continuous, ±10 V command at 1 V/A).
#include <gtest/gtest.h>

#include <cmath>

#include "host_sim/plant/coil.hpp"
#include "host_sim/plant/pwm_drive.hpp"

namespace mrd::plant {
namespace {

constexpr double kR_ohm = 4.8;
constexpr double kBus_v = 72.0;

// Hand calculation of L(i) = L_0 exp(−|i|/I_s) through L(1) = 5 H, L(2) = 3 H:
// exp(−1/I_s) = 3/5 → I_s = 1/ln(5/3) = 1.95762 A; L_0 = 5 · 5/3 = 8.33333 H;
// L(2.5) = 5 · (3/5)^1.5 = 2.32379 H.
TEST(Coil, InductanceThroughTheThesisPoints) {
  const Coil c{CoilParams{}};
  EXPECT_NEAR(c.inductance_h(1.0), 5.0, 1e-12);
  EXPECT_NEAR(c.inductance_h(-2.0), 3.0, 1e-12);
  EXPECT_NEAR(c.inductance_h(0.0), 25.0 / 3.0, 1e-12);
  EXPECT_NEAR(c.inductance_h(2.5), 5.0 * std::pow(0.6, 1.5), 1e-12);
  EXPECT_NEAR(c.saturation_a(), 1.0 / std::log(5.0 / 3.0), 1e-12);
}

// DC: di/dt = 0 → i = V/R. 12 V / 4.8 Ω = 2.5 A; 30 s is more than 17 time
// constants L(0)/R = 1.74 s.
TEST(Coil, DcCurrentIsVoltageOverResistance) {
  Coil c{CoilParams{}};
  for (int k = 0; k < 300000; ++k) c.step(12.0, 1e-4);
  EXPECT_NEAR(c.current_a(), 12.0 / kR_ohm, 1e-6);
  for (int k = 0; k < 300000; ++k) c.step(-36.0, 1e-4);
  EXPECT_NEAR(c.current_a(), -36.0 / kR_ohm, 1e-6);
}

// Slew bound: the fastest the current can rise is with the full bus across
// the coil, di/dt = (72 − R i)/L(i), so reaching I takes at least
// t_min(I) = ∫_0^I L(i)/(72 − R i) di, here by the midpoint rule (≈ 0.1754 s for
// 2.5 A, 0.1313 s for 63 % and 0.1652 s for 90 %: 14–19 A/s).
double slew_bound_s(double to_a) {
  const Coil c{CoilParams{}};
  const int n = 20000;
  const double h = to_a / n;
  double t = 0.0;
  for (int k = 0; k < n; ++k) {
    const double i = (k + 0.5) * h;
    t += c.inductance_h(i) / (kBus_v - kR_ohm * i) * h;
  }
  return t;
}

double time_to_reach_s(double level_a) {
  PwmDrive d{PwmDriveParams{}, CoilParams{}};
  for (int k = 1; k <= 2000; ++k) {
    d.step({2.5, true}, 1e-3);
    if (d.current_a() >= level_a) return k * 1e-3;
  }
  return 1e9;
}

TEST(PwmDrive, StepTo2p5AWithinTheSlewBound) {
  EXPECT_NEAR(slew_bound_s(2.5), 0.1754, 5e-4);
  // Bridge saturated until close to the target: the loop cannot beat the
  // bound, and it reaches 63 % and 90 % within one tick (1 ms) of it.
  for (double frac : {0.63, 0.9}) {
    const double t = time_to_reach_s(frac * 2.5);
    EXPECT_GE(t, slew_bound_s(frac * 2.5)) << frac;
    EXPECT_LE(t, slew_bound_s(frac * 2.5) + 1e-3) << frac;
  }
  // Within 1 % of the target no later than the bound to 2.5 A plus 5 time
  // constants of the linear loop (5 ms each).
  EXPECT_LE(time_to_reach_s(0.99 * 2.5), slew_bound_s(2.5) + 0.025);
  // Settled: the integrator, held during the saturated rise, takes over the
  // 12 V the coil needs from the proportional term; the remaining error
  // 12 V / K_p = 12 mA closes with K_p/K_i = L(1 A)/R = 1.04 s: after 12 s,
  // 12 mA · exp(−11.8/1.04) ≈ 1.4e-7 A.
  PwmDrive d{PwmDriveParams{}, CoilParams{}};
  for (int k = 0; k < 12000; ++k) d.step({2.5, true}, 1e-3);
  EXPECT_NEAR(d.current_a(), 2.5, 1e-6);
  EXPECT_NEAR(d.voltage_v(), 2.5 * kR_ohm, 1e-3);  // 12 V
}

TEST(PwmDrive, GainsFromResistanceAndInductance) {
  const PwmDrive d{PwmDriveParams{}, CoilParams{}};
  EXPECT_DOUBLE_EQ(d.kp_v_a(), 5.0 * 200.0);       // L(1 A) ω_c
  EXPECT_DOUBLE_EQ(d.ki_v_as(), kR_ohm * 200.0);   // R ω_c
}

TEST(PwmDrive, VoltageSaturatesAtTheBus) {
  PwmDrive d{PwmDriveParams{}, CoilParams{}};
  d.step({10.0, true}, 1e-3);
  EXPECT_DOUBLE_EQ(d.voltage_v(), kBus_v);
  // 10 A needs 48 V: reached, below the bus (error 48 V / K_p = 48 mA closing
  // with 1.04 s: 48 mA · exp(−14/1.04) ≈ 7e-8 A after 15 s).
  for (int k = 0; k < 15000; ++k) d.step({10.0, true}, 1e-3);
  EXPECT_NEAR(d.current_a(), 10.0, 1e-6);
  d.step({-10.0, true}, 1e-3);
  EXPECT_DOUBLE_EQ(d.voltage_v(), -kBus_v);
}

TEST(PwmDrive, CommandClampedAtTenVolts) {
  const PwmDrive d{PwmDriveParams{}, CoilParams{}};
  EXPECT_DOUBLE_EQ(d.reference_a(2.5), 2.5);
  EXPECT_DOUBLE_EQ(d.reference_a(12.0), 10.0);   // 12 V → 10 V → 10 A
  EXPECT_DOUBLE_EQ(d.reference_a(-40.0), -10.0);
}

// The current limit: with a 0.25 V/A command a 10 V command asks 40 A, and the
// reference stops at 30 A. A 1 Ω coil can carry it (30 V < 72 V). The I²t
// budget (30² − 15²) · 2 s = 1350 A²s is spent at 675 A²/s at 30 A: after
// about 2 s (plus the rise) the limit folds back to 15 A and the current follows.
TEST(PwmDrive, CurrentLimitPeakThenContinuous) {
  PwmDriveParams p;
  p.volts_per_amp = 0.25;
  CoilParams c;
  c.resistance_ohm = 1.0;
  PwmDrive d{p, c};
  EXPECT_DOUBLE_EQ(d.reference_a(40.0), 30.0);
  double peak_a = 0.0;
  for (int k = 0; k < 1500; ++k) {
    d.step({40.0, true}, 1e-3);
    peak_a = std::max(peak_a, d.current_a());
  }
  EXPECT_NEAR(d.current_a(), 30.0, 0.05);
  EXPECT_DOUBLE_EQ(d.current_limit_a(), 30.0);
  for (int k = 0; k < 5000; ++k) {
    d.step({40.0, true}, 1e-3);
    peak_a = std::max(peak_a, d.current_a());
  }
  EXPECT_LE(peak_a, 30.0 + 0.05);
  EXPECT_NEAR(d.current_a(), 15.0, 0.1);
}

// Output off: the bridge opens and the current freewheels into the bus
// (−72 V) to zero: from 2.5 A no slower than 2.5 A · L(0)/(72 V) = 0.29 s.
TEST(PwmDrive, OutputOffDecaysToZero) {
  PwmDrive d{PwmDriveParams{}, CoilParams{}};
  for (int k = 0; k < 2000; ++k) d.step({2.5, true}, 1e-3);
  for (int k = 0; k < 290; ++k) d.step({2.5, false}, 1e-3);
  EXPECT_EQ(d.current_a(), 0.0);
  d.step({2.5, false}, 1e-3);
  EXPECT_EQ(d.current_a(), 0.0);
}

}  // namespace
}  // namespace mrd::plant
