// Faults seen from the whole sim board (firmware task + core, drive, plant
// over the in-memory bus, lockstep, 1 ms ticks): what reaches the coil.
// Documented reactions: common/protocol/CAN_PROTOCOL.md, "Timeouts and safe behaviour".
#include <gtest/gtest.h>

#include <cmath>

#include "firmware/app/board_config.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/peers/in_process_board.hpp"

namespace mrd {
namespace {

using protocol::MsgId;

constexpr int kFaultTick = 500;
constexpr double kSafeCurrentA = 2.5;

/// A gentle 1 Hz ground shake so the sensors move.
double ag(int k) { return 0.5 * std::sin(2.0 * 3.141592653589793 * 1e-3 * k); }

app::BoardConfig sim_board_file() {
  const std::string file = std::string(MRD_BOARDS_DIR) + "/sim/board.toml";
  return app::parse_board_config(io::read_regular_file(file, app::kMaxBoardFileBytes), file);
}

std::unique_ptr<peers::InProcessBoard> board(control::ControlMode mode) {
  app::BoardConfig b = sim_board_file();
  b.mode = mode;
  return std::make_unique<peers::InProcessBoard>(b, plant::PlantSpec{}, peers::drive_config(b));
}

bool is(const hal::CanFrame& f, MsgId m) { return protocol::msg_of(f.id) == static_cast<std::uint8_t>(m); }

/// Runs until the drive applies `current_a`; returns the ticks after kFaultTick, or −1.
int ticks_until_applied(peers::InProcessBoard& b, double current_a, int limit = 200) {
  for (int k = kFaultTick; k < kFaultTick + limit; ++k) {
    b.step(ag(k));
    if (b.applied_current_a() == current_a) return k - kFaultTick + 1;
  }
  return -1;
}

void run_to_fault(peers::InProcessBoard& b) {
  for (int k = 0; k < kFaultTick; ++k) b.step(ag(k));
}

TEST(BoardFaults, CommandStreamCutGivesTheSafeCurrentWithin21Ticks) {
  auto b = board(control::ControlMode::kPassiveOff);  // 0 A normally, so 2.5 A is visible
  run_to_fault(*b);
  ASSERT_EQ(b->applied_current_a(), 0.0);
  b->bus().set_tamper([](hal::CanFrame& f) { return !is(f, MsgId::kCurrentCommand); });
  const int n = ticks_until_applied(*b, kSafeCurrentA);
  EXPECT_EQ(n, 21) << "timeout 20 ms: the 21st tick without a command is the first past it";
  EXPECT_EQ(b->drive().counters().fallbacks, 1u);
}

// The drive's safe current is the board's passive-on current: a board
// configured for a 1 A damper falls back to 1 A, not the thesis's 2.5 A; its
// over-current fault sits at its drive's peak (the thesis rig's 30 A, §3.2,
// or its [drive]'s).
TEST(BoardFaults, TheSafeCurrentAndOverCurrentAreTheBoardsOwn) {
  const peers::DriveConfig thesis = peers::drive_config(sim_board_file());
  EXPECT_EQ(thesis.safe_current_a, 2.5f);  // §6.4's passive-on current
  EXPECT_EQ(thesis.peak_limit_a, 30.0f);   // §3.2: 30 A peak
  app::BoardConfig b = sim_board_file();
  b.mode = control::ControlMode::kPassiveOff;
  b.controller.nominal_current_a = b.controller.fallback_current_a = b.controller.rated_current_a = 1.0;
  app::BoardDrive d;
  d.name = "small";
  d.peak_current_a = 12.0;
  d.continuous_current_a = 12.0;
  b.controller.drive_peak_limit_a = b.controller.drive_continuous_limit_a = 12.0;
  b.drive = d;
  const peers::DriveConfig own = peers::drive_config(b);
  EXPECT_EQ(own.safe_current_a, 1.0f);
  EXPECT_EQ(own.peak_limit_a, 12.0f);
  peers::InProcessBoard board(b, plant::PlantSpec{}, own);
  run_to_fault(board);
  ASSERT_EQ(board.applied_current_a(), 0.0);
  board.bus().set_tamper([](hal::CanFrame& f) { return !is(f, MsgId::kCurrentCommand); });
  EXPECT_EQ(ticks_until_applied(board, 1.0), 21);
}

TEST(BoardFaults, CorruptedCommandsGiveTheSafeCurrentWithin21Ticks) {
  auto b = board(control::ControlMode::kPassiveOff);
  run_to_fault(*b);
  b->bus().set_tamper([](hal::CanFrame& f) {
    if (is(f, MsgId::kCurrentCommand)) f.data[2] ^= 0x04;  // a bit flipped in flight
    return true;
  });
  EXPECT_EQ(ticks_until_applied(*b, kSafeCurrentA), 21);
  EXPECT_GE(b->drive().counters().rejected, 20u);
}

TEST(BoardFaults, ReplayedCommandsDoNotHoldOffTheFallback) {
  auto b = board(control::ControlMode::kPassiveOff);
  // Record a genuine command early on.
  hal::CanFrame recorded{};
  bool have = false;
  b->bus().set_tamper([&](hal::CanFrame& f) {
    if (!have && is(f, MsgId::kCurrentCommand)) {
      recorded = f;
      have = true;
    }
    return true;
  });
  run_to_fault(*b);
  ASSERT_TRUE(have);
  // The controller's commands stop; an attacker replays the recording every tick.
  auto& rogue = b->bus().attach();
  b->bus().set_tamper([&](hal::CanFrame& f) { return !is(f, MsgId::kCurrentCommand) || f.data == recorded.data; });
  int n = -1;
  for (int k = kFaultTick; k < kFaultTick + 100 && n < 0; ++k) {
    rogue.send(recorded);
    b->step(ag(k));
    if (b->applied_current_a() == kSafeCurrentA) n = k - kFaultTick + 1;
  }
  EXPECT_EQ(n, 21);
  EXPECT_GE(b->drive().counters().stale + b->drive().counters().repeated, 20u);
}

TEST(BoardFaults, CommandsFromAnotherNodeAreNeverTaken) {
  auto b = board(control::ControlMode::kPassiveOff);
  run_to_fault(*b);
  auto& rogue = b->bus().attach();
  for (int k = kFaultTick; k < kFaultTick + 200; ++k) {
    hal::CanFrame f;
    ASSERT_TRUE(protocol::encode(
        protocol::CurrentCommand{9.0f, true, control::ControlMode::kSemiActive, static_cast<std::uint8_t>(k)}, 5, f));
    rogue.send(f);
    b->step(ag(k));
    ASSERT_EQ(b->applied_current_a(), 0.0) << "tick " << k;
  }
  EXPECT_EQ(b->drive().counters().foreign, 200u);
}

TEST(BoardFaults, BusOffAtTheControllerGivesTheSafeCurrentWithin21Ticks) {
  auto b = board(control::ControlMode::kPassiveOff);
  run_to_fault(*b);
  b->controller_endpoint().set_state(hal::BusState::kBusOff);
  EXPECT_EQ(ticks_until_applied(*b, kSafeCurrentA), 21);
  EXPECT_EQ(b->task_status().bus_state, hal::BusState::kBusOff);
}

TEST(BoardFaults, DriveFaultLineTurnsTheCoilOffInTheSameTick) {
  auto b = board(control::ControlMode::kPassiveOn);
  run_to_fault(*b);
  ASSERT_EQ(b->applied_current_a(), 2.5);
  b->io().set_input(hal::InputLine::kDriveFault, true);
  EXPECT_EQ(ticks_until_applied(*b, 0.0), 1);
  EXPECT_FALSE(b->io().output(hal::OutputLine::kDriveEnable));
}

TEST(BoardFaults, MissingSensorFramesGiveTheSafeCurrentWithinSixTicks) {
  auto b = board(control::ControlMode::kSemiActive);
  run_to_fault(*b);
  b->bus().set_tamper([](hal::CanFrame& f) { return !is(f, MsgId::kDaqMotion); });
  int n = -1;
  for (int k = kFaultTick; k < kFaultTick + 50 && n < 0; ++k) {
    b->step(ag(k));
    if (b->task_status().last_output.current_command_a == 2.5f && b->applied_current_a() == 2.5)
      n = k - kFaultTick + 1;
  }
  EXPECT_GE(n, 1);
  EXPECT_LE(n, 6) << "core SAFE-2: 5 ticks holding the last command, then 2.5 A";
}

}  // namespace
}  // namespace mrd
