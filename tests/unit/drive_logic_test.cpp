// The simulated drive's rules (CAN_PROTOCOL.md, "Timeouts and safe behaviour"):
// follows valid commands from the controller only, falls back to the safe
// current 20 ms after the last valid one, refuses corrupted, replayed and
// foreign commands.
#include <gtest/gtest.h>

#include "host_sim/peers/drive_logic.hpp"

namespace mrd::peers {
namespace {

constexpr std::int64_t kMs = 1'000'000;

hal::CanFrame command(float a, std::uint8_t counter, std::uint8_t node = 1, bool enable = true) {
  hal::CanFrame f;
  EXPECT_TRUE(protocol::encode(protocol::CurrentCommand{a, enable, control::ControlMode::kSemiActive, counter}, node, f));
  return f;
}

TEST(DriveLogic, StartsInTheSafeStateUntilTheFirstCommand) {
  DriveLogic d;
  const DriveOutput o = d.tick(0, false, 0.0f);
  EXPECT_EQ(o.state, protocol::DriveState::kSafe);
  EXPECT_EQ(o.applied_current_a, 2.5f);
  EXPECT_TRUE(o.faults & protocol::drive_fault::kCommandTimeout);
}

TEST(DriveLogic, FollowsValidCommands) {
  DriveLogic d;
  ASSERT_TRUE(d.on_frame(command(-3.25f, 0), 0));
  const DriveOutput o = d.tick(0, false, 0.0f);
  EXPECT_EQ(o.state, protocol::DriveState::kFollowing);
  EXPECT_EQ(o.applied_current_a, -3.25f);
  EXPECT_TRUE(o.output_on);
  ASSERT_TRUE(d.on_frame(command(1.0f, 1, 1, /*enable=*/false), kMs));
  EXPECT_EQ(d.tick(kMs, false, 0.0f).state, protocol::DriveState::kDisabled);
  EXPECT_FALSE(d.output().output_on);
}

TEST(DriveLogic, FallsBackTwentyMillisecondsAfterTheLastValidCommand) {
  // Commands every 1 ms until t = 100 ms, then none. Drive ticks every 1 ms:
  // at t = 120 ms the age is exactly the 20 ms timeout (still following);
  // at t = 121 ms it exceeds it: safe current, latency 21 ms ≤ 20 ms + one period.
  DriveLogic d;
  std::uint8_t c = 0;
  for (std::int64_t t = 0; t <= 100 * kMs; t += kMs) {
    ASSERT_TRUE(d.on_frame(command(0.5f, c++), t));
    ASSERT_EQ(d.tick(t, false, 0.5f).state, protocol::DriveState::kFollowing);
  }
  for (std::int64_t t = 101 * kMs; t <= 120 * kMs; t += kMs) EXPECT_EQ(d.tick(t, false, 0.5f).state, protocol::DriveState::kFollowing) << t;
  const DriveOutput o = d.tick(121 * kMs, false, 0.5f);
  EXPECT_EQ(o.state, protocol::DriveState::kSafe);
  EXPECT_EQ(o.applied_current_a, 2.5f);
  EXPECT_EQ(d.counters().last_fallback_latency_ns, 21 * kMs);
  EXPECT_EQ(d.counters().fallbacks, 1u);
  // Commands resume with a fresh counter (the drive re-synchronised): followed again.
  ASSERT_TRUE(d.on_frame(command(0.75f, 200), 130 * kMs));
  EXPECT_EQ(d.tick(130 * kMs, false, 0.5f).applied_current_a, 0.75f);
}

TEST(DriveLogic, CorruptedCommandsDoNotKeepItAlive) {
  DriveLogic d;
  ASSERT_TRUE(d.on_frame(command(1.0f, 0), 0));
  std::uint8_t c = 1;
  for (std::int64_t t = kMs; t <= 30 * kMs; t += kMs) {
    hal::CanFrame f = command(9.0f, c++);
    f.data[1] ^= 0x10;  // one bit flipped on the wire
    EXPECT_FALSE(d.on_frame(f, t));
    d.tick(t, false, 1.0f);
  }
  EXPECT_EQ(d.output().state, protocol::DriveState::kSafe);
  EXPECT_EQ(d.counters().rejected, 30u);
  EXPECT_TRUE(d.output().faults & protocol::drive_fault::kCommandRejected);
}

TEST(DriveLogic, ReplayedAndRepeatedCommandsAreRefused) {
  DriveLogic d;
  const hal::CanFrame recorded = command(8.0f, 5);
  ASSERT_TRUE(d.on_frame(recorded, 0));
  EXPECT_FALSE(d.on_frame(recorded, kMs)) << "repeated";
  for (std::uint8_t c = 6; c < 30; ++c) ASSERT_TRUE(d.on_frame(command(0.0f, c), kMs * c));
  EXPECT_FALSE(d.on_frame(recorded, 31 * kMs)) << "replayed later: stale";
  EXPECT_EQ(d.counters().repeated, 1u);
  EXPECT_EQ(d.counters().stale, 1u);
  EXPECT_EQ(d.tick(31 * kMs, false, 0.0f).applied_current_a, 0.0f);
}

TEST(DriveLogic, NeverTakesACommandFromAnotherNode) {
  DriveLogic d;
  for (std::uint8_t node = 2; node <= 15; ++node) EXPECT_FALSE(d.on_frame(command(9.5f, node, node), 0)) << int(node);
  EXPECT_EQ(d.counters().foreign, 14u);
  EXPECT_EQ(d.counters().accepted, 0u);
  EXPECT_NE(d.tick(0, false, 0.0f).applied_current_a, 9.5f);
}

TEST(DriveLogic, FaultTurnsTheOutputOff) {
  DriveLogic d;
  ASSERT_TRUE(d.on_frame(command(5.0f, 0), 0));
  const DriveOutput o = d.tick(0, /*fault=*/true, 5.0f);
  EXPECT_EQ(o.state, protocol::DriveState::kFault);
  EXPECT_FALSE(o.output_on);
  EXPECT_EQ(o.applied_current_a, 0.0f);
  EXPECT_TRUE(d.tick(kMs, false, 30.5f).faults & protocol::drive_fault::kOverCurrent) << "above the 30 A peak";
}

}  // namespace
}  // namespace mrd::peers
