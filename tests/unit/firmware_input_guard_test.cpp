// Bad input to the control core: NaN, infinite, out-of-range, flagged and
// stuck sensor values, stale samples and drive faults each lead to the
// documented safe output (damper_controller.hpp, SAFE-1 … SAFE-4) and are
// counted in status(), in both numeric builds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "firmware/core/damper_controller.hpp"
#include "firmware/core/input_guard.hpp"

namespace mrd::fw {
namespace {

using control::ControlMode;
using control::ControllerInput;
using control::ControllerOutput;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(InputGuardClassify, FindsNanAndInfinityFromTheBits) {
  EXPECT_EQ(classify_float(kNaN), InputFault::kNotANumber);
  EXPECT_EQ(classify_float(-kNaN), InputFault::kNotANumber);
  EXPECT_EQ(classify_float(std::numeric_limits<float>::signaling_NaN()), InputFault::kNotANumber);
  EXPECT_EQ(classify_float(kInf), InputFault::kInfinite);
  EXPECT_EQ(classify_float(-kInf), InputFault::kInfinite);
  EXPECT_EQ(classify_float(std::numeric_limits<float>::max()), InputFault::kNone);
  EXPECT_EQ(classify_float(std::numeric_limits<float>::denorm_min()), InputFault::kNone);
  EXPECT_EQ(classify_float(-0.0f), InputFault::kNone);
}

// The guard's range test, |v| ≤ limit, against its definition −limit ≤ v ≤
// limit with NaN and ±∞ named for what they are, at the limit's edges and
// with limits no float reaches.
TEST(InputGuardRange, EdgesOfTheLimitAndLimitsBeyondEveryFloat) {
  const auto disp_fault = [](float limit, float v) {
    InputGuardLimits l;
    l.disp_limit_m = limit;
    InputGuard g;
    g.init(l);
    ControllerInput in;
    in.damper_disp_m = v;
    return g.check(in)[InputGuard::idx(InputSignal::kDisp)];
  };
  const float above = std::nextafter(0.3f, 1.0f);
  EXPECT_EQ(disp_fault(0.3f, 0.3f), InputFault::kNone);
  EXPECT_EQ(disp_fault(0.3f, -0.3f), InputFault::kNone);
  EXPECT_EQ(disp_fault(0.3f, -0.0f), InputFault::kNone);
  EXPECT_EQ(disp_fault(0.3f, above), InputFault::kOutOfRange);
  EXPECT_EQ(disp_fault(0.3f, -above), InputFault::kOutOfRange);
  EXPECT_EQ(disp_fault(0.3f, kInf), InputFault::kInfinite);
  EXPECT_EQ(disp_fault(0.3f, -kInf), InputFault::kInfinite);
  EXPECT_EQ(disp_fault(0.3f, kNaN), InputFault::kNotANumber);
  // A limit of +∞ (a double limit beyond float's range, converted): every
  // finite stroke is inside, ±∞ are still infinite values, not strokes.
  const float big = std::numeric_limits<float>::max();
  EXPECT_EQ(disp_fault(kInf, big), InputFault::kNone);
  EXPECT_EQ(disp_fault(kInf, -big), InputFault::kNone);
  EXPECT_EQ(disp_fault(kInf, kInf), InputFault::kInfinite);
  EXPECT_EQ(disp_fault(kInf, -kInf), InputFault::kInfinite);
  EXPECT_EQ(disp_fault(kInf, kNaN), InputFault::kNotANumber);
  // A limit no value meets (−limit ≤ v ≤ limit is empty): everything finite
  // is out of range.
  EXPECT_EQ(disp_fault(-1.0f, 0.0f), InputFault::kOutOfRange);
  EXPECT_EQ(disp_fault(kNaN, 0.0f), InputFault::kOutOfRange);
}

template <class Policy>
class BadInputTest : public ::testing::Test {
 protected:
  DamperController<Policy> c_;
  std::uint64_t k_ = 0;

  void SetUp() override { ASSERT_EQ(c_.init(ControllerConfig{}), ConfigError::kNone); }

  /// A clean, moving sample: 40 mm at 0.25 Hz, force of a viscous damper,
  /// ground shaking at 0.5 m/s², coil at 1 A.
  ControllerInput good() const {
    const double t = static_cast<double>(k_) * 1e-3;
    const double w = 2.0 * 3.141592653589793 * 0.2508;
    ControllerInput in;
    in.tick = k_;
    in.damper_disp_m = static_cast<float>(0.04 * std::sin(w * t + 0.3));
    in.damper_force_n = static_cast<float>(1e5 * 0.04 * w * std::cos(w * t + 0.3));
    in.ground_accel_m_s2 = static_cast<float>(0.5 * std::cos(5.0 * t));
    in.base_accel_m_s2 = 0.1f;
    in.coil_current_a = 1.0f;
    return in;
  }
  ControllerOutput step(const ControllerInput& in) {
    const ControllerOutput out = c_.step(in);
    ++k_;
    return out;
  }
  /// Runs clean ticks (ODBDCO in charge), returns the last output.
  ControllerOutput run_good(int n) {
    ControllerOutput out;
    for (int i = 0; i < n; ++i) out = step(good());
    return out;
  }
  /// Checks SAFE-2 for a fault that lasts 20 ticks: 5 ticks repeating the
  /// last good command, then the 2.5 A fallback, F_d reported as 0; then
  /// recovery on the next good tick.
  template <class Corrupt>
  void expect_hold_then_fallback(Corrupt corrupt) {
    const ControllerOutput last_good = run_good(2000);
    const auto branches_before = c_.status().branch_ticks;
    for (int i = 0; i < 20; ++i) {
      ControllerInput in = good();
      corrupt(in);
      const ControllerOutput out = step(in);
      ASSERT_TRUE(out.drive_enable);
      ASSERT_EQ(out.desired_force_n, 0.0f);
      if (i < 5) {
        ASSERT_EQ(out.current_command_a, last_good.current_command_a) << "tick " << i;
      } else {
        ASSERT_EQ(out.current_command_a, 2.5f) << "tick " << i;
      }
    }
    EXPECT_EQ(c_.status().held_ticks, 5u);
    EXPECT_EQ(c_.status().fallback_ticks, 15u);
    // Recovery: the next good tick goes back to ODBDCO.
    (void)step(good());
    int decided = 0;
    for (int b = 0; b < kOdbdcoBranches; ++b) decided += static_cast<int>(c_.status().branch_ticks[b] - branches_before[b]);
    EXPECT_EQ(decided, 1);
  }
};
using Policies = ::testing::Types<num::Float32Policy, num::Fixed32Policy>;
TYPED_TEST_SUITE(BadInputTest, Policies);

TYPED_TEST(BadInputTest, CleanInputCountsNothing) {
  (void)this->run_good(20000);
  const DamperControllerStatus& s = this->c_.status();
  EXPECT_EQ(s.ticks, 20000u);
  for (int k = 1; k < kInputFaultKinds; ++k) EXPECT_EQ(s.invalid_by_kind[k], 0u) << k;
  EXPECT_EQ(s.stale_inputs, 0u);
  EXPECT_EQ(s.held_ticks + s.fallback_ticks, 0u);
  int decided = 0;
  for (auto b : s.branch_ticks) decided += static_cast<int>(b);
  EXPECT_EQ(decided, 20000);
}

TYPED_TEST(BadInputTest, NanStrokeHoldsThenFallsBack) {
  this->expect_hold_then_fallback([](ControllerInput& in) { in.damper_disp_m = kNaN; });
  EXPECT_EQ(this->c_.status().invalid(InputFault::kNotANumber), 20u);
  EXPECT_EQ(this->c_.status().invalid(InputSignal::kDisp), 20u);
}

TYPED_TEST(BadInputTest, InfiniteForceHoldsThenFallsBack) {
  this->expect_hold_then_fallback([](ControllerInput& in) { in.damper_force_n = -kInf; });
  EXPECT_EQ(this->c_.status().invalid(InputFault::kInfinite), 20u);
  EXPECT_EQ(this->c_.status().invalid(InputSignal::kForce), 20u);
}

TYPED_TEST(BadInputTest, OutOfRangeValuesHoldThenFallBack) {
  // 0.31 m is beyond the 0.30 m stroke limit (damper stroke ±292.1 mm).
  this->expect_hold_then_fallback([](ControllerInput& in) { in.damper_disp_m = 0.31f; });
  EXPECT_EQ(this->c_.status().invalid(InputFault::kOutOfRange), 20u);
}

TYPED_TEST(BadInputTest, ImpossibleCoilCurrentHoldsThenFallsBack) {
  // 31 A is more than the drive's 30 A peak.
  this->expect_hold_then_fallback([](ControllerInput& in) { in.coil_current_a = 31.0f; });
  EXPECT_EQ(this->c_.status().invalid(InputSignal::kCoilCurrent), 20u);
  EXPECT_EQ(this->c_.status().invalid(InputFault::kOutOfRange), 20u);
}

TYPED_TEST(BadInputTest, FlaggedInvalidHoldsThenFallsBack) {
  this->expect_hold_then_fallback([](ControllerInput& in) { in.flags.force_valid = false; });
  EXPECT_EQ(this->c_.status().invalid(InputFault::kFlagged), 20u);
}

TYPED_TEST(BadInputTest, RepeatedSampleIsStale) {
  // The runtime hands over the same sample again (its tick does not advance).
  std::uint64_t frozen = 0;
  bool first = true;
  this->expect_hold_then_fallback([&](ControllerInput& in) {
    if (first) frozen = in.tick - 1;
    first = false;
    in.tick = frozen;
  });
  EXPECT_EQ(this->c_.status().stale_inputs, 20u);
}

TYPED_TEST(BadInputTest, OldOrFutureSamplesAreStale) {
  (void)this->run_good(100);  // last accepted sample: tick 99
  auto sampled_at = [this](std::uint64_t tick) {
    ControllerInput in = this->good();
    in.tick = tick;
    (void)this->step(in);
    return this->c_.status().last_input_stale;
  };
  EXPECT_TRUE(sampled_at(99));    // now 100: the same sample again
  EXPECT_TRUE(sampled_at(99));    // now 101: and again
  EXPECT_FALSE(sampled_at(100));  // now 102: 2 ticks old, newer than 99: accepted
  EXPECT_TRUE(sampled_at(100));   // now 103: 3 ticks old > max_input_age_ticks = 2
  EXPECT_TRUE(sampled_at(105));   // now 104: from the future
  EXPECT_FALSE(sampled_at(105));  // now 105: on time
  EXPECT_EQ(this->c_.status().stale_inputs, 4u);
}

TYPED_TEST(BadInputTest, StuckStrokeDuringShakingIsDetected) {
  (void)this->run_good(1000);
  // The stroke freezes while the ground shakes (|a_g| up to 0.5 m/s²).
  const float frozen = this->good().damper_disp_m;
  ControllerOutput out;
  for (int i = 0; i < 600; ++i) {
    ControllerInput in = this->good();
    in.damper_disp_m = frozen;
    out = this->step(in);
  }
  // The 1st of the identical values is the last plausible one; the 500th
  // makes a run of 500 ticks: 101 ticks flagged stuck.
  EXPECT_EQ(this->c_.status().invalid(InputFault::kStuck), 101u);
  EXPECT_EQ(out.current_command_a, 2.5f);
}

// status().last_faults is the latest tick's verdict per signal: a fault is
// reported on its tick and gone on the next tick whose inputs are clean
// (the controller's path for clean ticks writes no faults), and a stuck run
// is reported while it lasts.
TYPED_TEST(BadInputTest, TheLatestTicksFaultsAreReportedAndGoneOnTheNextCleanTick) {
  const auto faults = [this] { return this->c_.status().last_faults; };
  const auto expect_only = [&](InputSignal signal, InputFault fault, const char* what) {
    for (int s = 0; s < kInputSignals; ++s) {
      EXPECT_EQ(faults()[s], s == static_cast<int>(signal) ? fault : InputFault::kNone) << what << ", signal " << s;
    }
  };
  const auto expect_none = [&](const char* what) {
    for (int s = 0; s < kInputSignals; ++s) EXPECT_EQ(faults()[s], InputFault::kNone) << what << ", signal " << s;
  };
  (void)this->run_good(100);
  expect_none("clean ticks");

  ControllerInput in = this->good();
  in.damper_disp_m = kNaN;
  in.damper_force_n = -kInf;
  (void)this->step(in);
  EXPECT_EQ(faults()[static_cast<int>(InputSignal::kDisp)], InputFault::kNotANumber);
  EXPECT_EQ(faults()[static_cast<int>(InputSignal::kForce)], InputFault::kInfinite);
  EXPECT_EQ(faults()[static_cast<int>(InputSignal::kGroundAccel)], InputFault::kNone);
  (void)this->run_good(1);
  expect_none("the clean tick after a NaN stroke and an infinite force");

  in = this->good();
  in.flags.ground_accel_valid = false;
  (void)this->step(in);
  expect_only(InputSignal::kGroundAccel, InputFault::kFlagged, "a flagged ground acceleration");
  (void)this->run_good(1);
  expect_none("the clean tick after a flagged ground acceleration");

  // 500 identical strokes while the ground shakes: the 500th is stuck.
  const float frozen = this->good().damper_disp_m;
  for (int i = 0; i < 499; ++i) {
    in = this->good();
    in.damper_disp_m = frozen;
    (void)this->step(in);
  }
  expect_none("499 identical strokes");
  in = this->good();
  in.damper_disp_m = frozen;
  (void)this->step(in);
  expect_only(InputSignal::kDisp, InputFault::kStuck, "the 500th identical stroke");
  (void)this->run_good(1);
  expect_none("a moving stroke again");
}

TYPED_TEST(BadInputTest, ConstantStrokeAtRestIsNotStuck) {
  // No shaking: a building at rest reports the same stroke forever.
  ControllerOutput out;
  for (int i = 0; i < 3000; ++i) {
    ControllerInput in = this->good();
    in.damper_disp_m = 0.001f;
    in.damper_force_n = 0.0f;
    in.ground_accel_m_s2 = 0.01f;
    in.coil_current_a = 0.0f;
    out = this->step(in);
  }
  EXPECT_EQ(this->c_.status().invalid(InputFault::kStuck), 0u);
  EXPECT_EQ(this->c_.status().fallback_ticks, 0u);
}

TYPED_TEST(BadInputTest, DriveFaultDisablesTheDriveAndDelaysReEnable) {
  (void)this->run_good(100);
  for (int i = 0; i < 10; ++i) {
    ControllerInput in = this->good();
    in.flags.drive_fault = true;
    const ControllerOutput out = this->step(in);
    ASSERT_FALSE(out.drive_enable);
    ASSERT_EQ(out.current_command_a, 0.0f);
  }
  // Cleared: still disabled for drive_reenable_delay_ticks = 1000.
  for (int i = 0; i < 1000; ++i) ASSERT_FALSE(this->step(this->good()).drive_enable) << i;
  EXPECT_TRUE(this->step(this->good()).drive_enable);
  EXPECT_EQ(this->c_.status().drive_fault_ticks, 10u);
  EXPECT_EQ(this->c_.status().drive_disabled_ticks, 1010u);
}

TYPED_TEST(BadInputTest, BadAccelerationIsCountedButDoesNotChangeTheOutput) {
  // SAFE-4: the law does not use accelerations. Compare with a twin fed clean input.
  DamperController<TypeParam> twin;
  ASSERT_EQ(twin.init(ControllerConfig{}), ConfigError::kNone);
  for (int i = 0; i < 3000; ++i) {
    const ControllerInput clean = this->good();
    ControllerInput in = clean;
    in.base_accel_m_s2 = kNaN;
    in.ground_accel_m_s2 = (i % 2) ? kInf : 1e6f;
    const ControllerOutput a = this->step(in);
    const ControllerOutput b = twin.step(clean);
    ASSERT_EQ(a.current_command_a, b.current_command_a);
    ASSERT_EQ(a.desired_force_n, b.desired_force_n);
  }
  const DamperControllerStatus& s = this->c_.status();
  EXPECT_EQ(s.invalid(InputSignal::kBaseAccel), 3000u);
  EXPECT_EQ(s.invalid(InputSignal::kGroundAccel), 3000u);
  EXPECT_EQ(s.invalid(InputFault::kNotANumber), 3000u);
  EXPECT_EQ(s.invalid(InputFault::kInfinite), 1500u);
  EXPECT_EQ(s.invalid(InputFault::kOutOfRange), 1500u);
  EXPECT_EQ(s.fallback_ticks, 0u);
}

TYPED_TEST(BadInputTest, PassiveModesIgnoreBadSensors) {
  // SAFE-3: passive-on keeps 2.5 A with every sensor NaN, and counts.
  ASSERT_TRUE(this->c_.set_mode(ControlMode::kPassiveOn));
  for (int i = 0; i < 50; ++i) {
    ControllerInput in = this->good();
    in.damper_disp_m = in.damper_force_n = in.coil_current_a = kNaN;
    EXPECT_EQ(this->step(in).current_command_a, 2.5f);
  }
  EXPECT_EQ(this->c_.status().invalid(InputFault::kNotANumber), 150u);
  EXPECT_EQ(this->c_.status().fallback_ticks, 0u);
}

}  // namespace
}  // namespace mrd::fw
