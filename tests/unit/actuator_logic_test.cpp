// The simulated mixing actuator: runs the thesis cycle, refuses what it
// cannot drive, aborts when the controller stops asking.
#include <gtest/gtest.h>

#include <cmath>

#include "host_sim/peers/actuator_logic.hpp"

namespace mrd::peers {
namespace {

constexpr std::int64_t kS = 1'000'000'000;

hal::CanFrame mixing(protocol::MixingAction a, float amp, float f_hz, float dur_s, std::uint8_t counter) {
  hal::CanFrame f;
  EXPECT_TRUE(protocol::encode(protocol::MixingCommand{a, amp, f_hz, dur_s, counter}, 1, f));
  return f;
}

TEST(ActuatorLogic, RunsTheThesisCycleToTheEnd) {
  // ±76.2 mm at 0.2 Hz for 10 s: peak velocity 2π·0.2·0.0762 = 0.0957 m/s < 0.2 m/s.
  ActuatorLogic a;
  std::uint8_t c = 0;
  ASSERT_TRUE(a.on_frame(mixing(protocol::MixingAction::kStart, 0.0762f, 0.2f, 10.0f, c++), 0));
  EXPECT_EQ(a.tick(0).state, protocol::MixingState::kRunning);
  // x(1.25 s) = A sin(2π·0.2·1.25) = A sin(π/2) = A.
  EXPECT_NEAR(a.position_m(kS + kS / 4), 0.0762, 1e-6);
  for (std::int64_t t = kS / 10; t < 10 * kS; t += kS / 10) {
    a.on_frame(mixing(protocol::MixingAction::kStart, 0.0762f, 0.2f, 10.0f, c++), t);
    ASSERT_EQ(a.tick(t).state, protocol::MixingState::kRunning) << t;
  }
  EXPECT_EQ(a.tick(10 * kS).state, protocol::MixingState::kDone);
}

TEST(ActuatorLogic, RefusesBeyondStrokeOrVelocity) {
  ActuatorLogic a;  // stroke 0.1 m, velocity 0.2 m/s
  ASSERT_TRUE(a.on_frame(mixing(protocol::MixingAction::kStart, 0.15f, 0.1f, 10.0f, 0), 0));
  EXPECT_EQ(a.tick(0).faults, protocol::mixing_fault::kStrokeLimit);
  ActuatorLogic b;
  // 2π·1.0·0.05 = 0.314 m/s > 0.2 m/s.
  ASSERT_TRUE(b.on_frame(mixing(protocol::MixingAction::kStart, 0.05f, 1.0f, 10.0f, 0), 0));
  const auto s = b.tick(0);
  EXPECT_EQ(s.state, protocol::MixingState::kFault);
  EXPECT_EQ(s.faults, protocol::mixing_fault::kVelocityLimit);
}

TEST(ActuatorLogic, AbortsWhenCommandsStopOrOnStop) {
  ActuatorLogic a;
  ASSERT_TRUE(a.on_frame(mixing(protocol::MixingAction::kStart, 0.05f, 0.2f, 600.0f, 0), 0));
  EXPECT_EQ(a.tick(kS / 2).state, protocol::MixingState::kRunning) << "500 ms: not yet";
  const auto s = a.tick(kS / 2 + 1);
  EXPECT_EQ(s.state, protocol::MixingState::kAborted);
  EXPECT_TRUE(s.faults & protocol::mixing_fault::kCommandTimeout);
  ActuatorLogic b;
  ASSERT_TRUE(b.on_frame(mixing(protocol::MixingAction::kStart, 0.05f, 0.2f, 600.0f, 0), 0));
  ASSERT_TRUE(b.on_frame(mixing(protocol::MixingAction::kStop, 0.0f, 0.0f, 0.0f, 1), kS / 10));
  EXPECT_EQ(b.tick(kS / 10).state, protocol::MixingState::kAborted);
  EXPECT_EQ(b.position_m(kS / 5), 0.0);
}

TEST(ActuatorLogic, IgnoresCommandsFromAnotherNode) {
  ActuatorLogic a;
  hal::CanFrame f;
  ASSERT_TRUE(protocol::encode(protocol::MixingCommand{protocol::MixingAction::kStart, 0.05f, 0.2f, 60.0f, 0}, 7, f));
  EXPECT_FALSE(a.on_frame(f, 0));
  EXPECT_EQ(a.tick(0).state, protocol::MixingState::kIdle);
}

}  // namespace
}  // namespace mrd::peers
