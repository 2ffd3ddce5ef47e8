// The control task on an in-memory bus and lines: frames in → the core's
// input, the core's output → command frame and lines, heartbeat, lockstep.
#include <gtest/gtest.h>

#include <vector>

#include "firmware/app/control_task.hpp"
#include "firmware/core/damper_controller.hpp"
#include "firmware/platform/sim/memory_bus.hpp"
#include "firmware/platform/sim/memory_io.hpp"

namespace mrd::app {
namespace {

using protocol::can_id;
using protocol::MsgId;

/// Records its inputs and returns a scripted output.
struct StandInCore {
  std::vector<control::ControllerInput> inputs;
  control::ControllerOutput next{1.25f, true, 0.0f};
  int resets = 0;
  void reset() { ++resets; }
  control::ControllerOutput step(const control::ControllerInput& in) {
    inputs.push_back(in);
    return next;
  }
};

class TaskFixture : public ::testing::Test {
 protected:
  TaskFixture() : ctrl_(bus_.attach()), peer_(bus_.attach()) {
    ctrl_.set_filters(control_task_filters(nodes_));
  }
  void send_motion(float x, float f, std::uint8_t c, std::uint8_t node = 3) {
    hal::CanFrame fr;
    ASSERT_TRUE(protocol::encode(protocol::DaqMotion{x, true, f, true, c}, node, fr));
    peer_.send(fr);
  }
  void send_accel(float g, float b, std::uint8_t c) {
    hal::CanFrame fr;
    ASSERT_TRUE(protocol::encode(protocol::DaqAccel{g, true, b, true, c}, 3, fr));
    peer_.send(fr);
  }
  void send_drive(float i, std::uint8_t c, protocol::DriveState s = protocol::DriveState::kFollowing,
                  std::uint8_t faults = 0) {
    hal::CanFrame fr;
    ASSERT_TRUE(protocol::encode(protocol::DriveStatus{i, i, faults, s, c}, 2, fr));
    peer_.send(fr);
  }
  /// The current commands the controller sent, decoded.
  std::vector<protocol::CurrentCommand> commands() {
    std::vector<protocol::CurrentCommand> out;
    hal::CanFrame fr;
    while (peer_.receive(fr) == hal::CanResult::kOk) {
      protocol::CurrentCommand c;
      if (protocol::decode(fr, 1, c) == protocol::DecodeError::kOk) out.push_back(c);
    }
    return out;
  }

  protocol::NodeIds nodes_{};
  sim::MemoryBus bus_;
  sim::MemoryCanEndpoint& ctrl_;
  sim::MemoryCanEndpoint& peer_;
  sim::MemoryIo io_;
};

TEST_F(TaskFixture, HandsTheDecodedSampleToTheCoreAndSendsItsCommand) {
  StandInCore core;
  ControlTask<StandInCore> task(core, ctrl_, io_, ControlTaskConfig{});
  task.reset();
  EXPECT_EQ(core.resets, 1);
  send_motion(0.0125f, -1500.5f, 7);
  send_accel(1.1f, -0.25f, 7);
  send_drive(2.345f, 7);
  const auto out = task.run_tick();
  ASSERT_EQ(core.inputs.size(), 1u);
  const auto& in = core.inputs[0];
  EXPECT_EQ(in.tick, 0u);
  EXPECT_FLOAT_EQ(in.damper_disp_m, 0.0125f);   // 125000 × 0.1 µm
  EXPECT_FLOAT_EQ(in.damper_force_n, -1500.5f);
  EXPECT_FLOAT_EQ(in.ground_accel_m_s2, 1.1f);
  EXPECT_FLOAT_EQ(in.base_accel_m_s2, -0.25f);
  EXPECT_FLOAT_EQ(in.coil_current_a, 2.345f);
  EXPECT_TRUE(in.flags.disp_valid && in.flags.force_valid && in.flags.ground_accel_valid && in.flags.base_accel_valid);
  EXPECT_FALSE(in.flags.drive_fault);
  EXPECT_FLOAT_EQ(out.current_command_a, 1.25f);
  const auto cmds = commands();
  ASSERT_EQ(cmds.size(), 1u) << "one command per tick (the heartbeat is another message)";
  EXPECT_FLOAT_EQ(cmds[0].current_a, 1.25f);
  EXPECT_TRUE(cmds[0].enable);
  EXPECT_TRUE(io_.output(hal::OutputLine::kDriveEnable));
}

TEST_F(TaskFixture, CommandCounterRollsAndLinesAreWrittenOnlyOnChange) {
  StandInCore core;
  ControlTask<StandInCore> task(core, ctrl_, io_, ControlTaskConfig{});
  task.reset();
  std::vector<std::uint8_t> counters;
  for (int k = 0; k < 300; ++k) {
    task.run_tick();
    for (const auto& c : commands()) counters.push_back(c.counter);
  }
  ASSERT_EQ(counters.size(), 300u);
  for (std::size_t i = 1; i < counters.size(); ++i)
    EXPECT_EQ(counters[i], static_cast<std::uint8_t>(counters[i - 1] + 1)) << i;
  EXPECT_EQ(io_.writes(hal::OutputLine::kDriveEnable), 1u) << "level unchanged after the first write";
  core.next.drive_enable = false;
  task.run_tick();
  EXPECT_EQ(io_.writes(hal::OutputLine::kDriveEnable), 2u);
  EXPECT_FALSE(io_.output(hal::OutputLine::kDriveEnable));
}

TEST_F(TaskFixture, SampleTickIsTheTickTheFrameArrived) {
  StandInCore core;
  ControlTask<StandInCore> task(core, ctrl_, io_, ControlTaskConfig{});
  task.reset();
  send_motion(0.01f, 0.0f, 1);
  task.run_tick();  // tick 0, sample from tick 0
  task.run_tick();  // tick 1, nothing new
  task.run_tick();  // tick 2, nothing new
  send_motion(0.02f, 0.0f, 2);
  task.run_tick();  // tick 3, new sample
  ASSERT_EQ(core.inputs.size(), 4u);
  EXPECT_EQ(core.inputs[0].tick, 0u);
  EXPECT_EQ(core.inputs[1].tick, 0u) << "an old sample keeps its tick so the core sees it is stale";
  EXPECT_EQ(core.inputs[2].tick, 0u);
  EXPECT_EQ(core.inputs[3].tick, 3u);
  EXPECT_FLOAT_EQ(core.inputs[3].damper_disp_m, 0.02f);
}

TEST_F(TaskFixture, NeverTakesDataFromAnotherNode) {
  StandInCore core;
  ControlTask<StandInCore> task(core, ctrl_, io_, ControlTaskConfig{});
  task.reset();
  ctrl_.set_filters({});  // let everything through to prove the task itself refuses it
  send_motion(0.3f, 1000.0f, 1, /*node=*/5);
  task.run_tick();
  EXPECT_EQ(task.status().unexpected_ids, 1u);
  EXPECT_FALSE(core.inputs[0].flags.disp_valid);
  EXPECT_EQ(core.inputs[0].damper_disp_m, 0.0f);
}

TEST_F(TaskFixture, LockstepNeedsAllThreeFramesOfOneTick) {
  StandInCore core;
  ControlTask<StandInCore> task(core, ctrl_, io_, ControlTaskConfig{});
  task.reset();
  send_motion(0.0f, 0.0f, 4);
  send_accel(0.0f, 0.0f, 4);
  task.poll_rx();
  EXPECT_FALSE(task.lockstep_ready()) << "no drive status yet";
  send_drive(0.0f, 3);
  task.poll_rx();
  EXPECT_FALSE(task.lockstep_ready()) << "drive status of another tick";
  send_drive(0.0f, 4);
  task.poll_rx();
  EXPECT_TRUE(task.lockstep_ready());
  task.step_tick();
  EXPECT_FALSE(task.lockstep_ready()) << "consumed";
}

TEST_F(TaskFixture, HeartbeatEveryHundredTicksWithFlags) {
  StandInCore core;
  ControlTask<StandInCore> task(core, ctrl_, io_, ControlTaskConfig{});
  task.reset();
  std::vector<protocol::ControllerStatus> beats;
  for (int k = 0; k < 250; ++k) {
    task.run_tick();
    hal::CanFrame fr;
    while (peer_.receive(fr) == hal::CanResult::kOk) {
      protocol::ControllerStatus s;
      if (protocol::decode(fr, 1, s) == protocol::DecodeError::kOk) beats.push_back(s);
    }
  }
  ASSERT_EQ(beats.size(), 3u);  // ticks 0, 100, 200
  EXPECT_EQ(beats[1].counter, 1);
  EXPECT_TRUE(beats[1].flags & protocol::controller_flag::kDriveEnabled);
  EXPECT_TRUE(beats[1].flags & protocol::controller_flag::kSensorTimeout) << "no DAQ frame was ever sent";
  EXPECT_TRUE(beats[1].flags & protocol::controller_flag::kDriveSilent);
}

TEST_F(TaskFixture, MixingRequestGoesOutWithEveryHeartbeatUntilStopped) {
  StandInCore core;
  ControlTask<StandInCore> task(core, ctrl_, io_, ControlTaskConfig{});
  task.reset();
  task.request_mixing({protocol::MixingAction::kStart, 0.0762f, 0.2f, 600.0f, 0});
  std::vector<protocol::MixingCommand> sent;
  auto collect = [&] {
    hal::CanFrame fr;
    while (peer_.receive(fr) == hal::CanResult::kOk) {
      protocol::MixingCommand m;
      if (protocol::decode(fr, 1, m) == protocol::DecodeError::kOk) sent.push_back(m);
    }
  };
  for (int k = 0; k < 250; ++k) {
    if (k == 150) {
      hal::CanFrame fr;  // the actuator answers: running
      ASSERT_TRUE(protocol::encode(protocol::MixingStatus{protocol::MixingState::kRunning, 1.0f, 0.0762f, 0, 0}, 4, fr));
      peer_.send(fr);
    }
    task.run_tick();
    collect();
  }
  ASSERT_EQ(sent.size(), 3u);  // ticks 0, 100, 200
  EXPECT_EQ(sent[0].action, protocol::MixingAction::kStart);
  EXPECT_EQ(sent[2].counter, 2);
  EXPECT_TRUE(task.status().actuator_present);
  EXPECT_EQ(task.status().last_mixing.state, protocol::MixingState::kRunning);
  task.request_mixing({protocol::MixingAction::kStop, 0.0f, 0.0f, 0.0f, 0});
  for (int k = 0; k < 250; ++k) {
    task.run_tick();
    collect();
  }
  ASSERT_EQ(sent.size(), 4u) << "one stop, then silence";
  EXPECT_EQ(sent[3].action, protocol::MixingAction::kStop);
}

TEST_F(TaskFixture, MaintenanceDueDrivesItsLine) {
  StandInCore core;
  ControlTask<StandInCore> task(core, ctrl_, io_, ControlTaskConfig{});
  task.reset();
  task.run_tick();
  EXPECT_FALSE(io_.output(hal::OutputLine::kMaintenanceDue));
  task.set_maintenance_due(true);
  task.run_tick();
  EXPECT_TRUE(io_.output(hal::OutputLine::kMaintenanceDue));
  EXPECT_EQ(io_.writes(hal::OutputLine::kMaintenanceDue), 2u);
}

TEST_F(TaskFixture, PassiveOnCoreCommandsTwoAndAHalfAmperes) {
  fw::DamperController<num::Float32Policy> core;
  fw::ControllerConfig cfg;
  cfg.mode = control::ControlMode::kPassiveOn;
  ASSERT_EQ(core.init(cfg), fw::ConfigError::kNone);
  ControlTask<fw::DamperController<num::Float32Policy>> task(core, ctrl_, io_, ControlTaskConfig{});
  task.reset();
  for (std::uint8_t k = 0; k < 20; ++k) {
    send_motion(0.001f * k, 100.0f * k, k);
    send_accel(0.0f, 0.0f, k);
    send_drive(2.5f, k);
    task.run_tick();
  }
  const auto cmds = commands();
  ASSERT_FALSE(cmds.empty());
  for (const auto& c : cmds) {
    EXPECT_EQ(c.current_a, 2.5f);  // §6.4 passive-on, 2500 mA exactly
    EXPECT_TRUE(c.enable);
  }
}

TEST_F(TaskFixture, AnOutputTheCodecCannotCarryGoesOutAsOff) {
  StandInCore core;
  core.next = {12.0f, true, 0.0f};  // beyond the ±10 A command range
  ControlTask<StandInCore> task(core, ctrl_, io_, ControlTaskConfig{});
  task.reset();
  const auto out = task.run_tick();
  EXPECT_EQ(task.status().encode_errors, 1u);
  EXPECT_FALSE(out.drive_enable);
  const auto cmds = commands();
  ASSERT_FALSE(cmds.empty());
  EXPECT_EQ(cmds[0].current_a, 0.0f);
  EXPECT_FALSE(cmds[0].enable);
  EXPECT_FALSE(io_.output(hal::OutputLine::kDriveEnable));
}

}  // namespace
}  // namespace mrd::app
