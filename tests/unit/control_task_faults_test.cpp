// Faults at the controller, with the real control core: drive fault line,
// drive-reported faults, unreadable lines, bus-off, corrupted, replayed and
// missing sensor frames. Times are in control ticks (1 ms); the documented
// reactions are in common/protocol/CAN_PROTOCOL.md, "Timeouts and safe behaviour".
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "firmware/app/control_task.hpp"
#include "firmware/core/damper_controller.hpp"
#include "firmware/platform/sim/memory_bus.hpp"
#include "firmware/platform/sim/memory_io.hpp"

namespace mrd::app {
namespace {

using Core = fw::DamperController<num::Float32Policy>;

class Faults : public ::testing::Test {
 protected:
  Faults() : ctrl_(bus_.attach()), daq_(bus_.attach()) { ctrl_.set_filters(control_task_filters({})); }

  void init(control::ControlMode mode) {
    fw::ControllerConfig cfg;
    cfg.mode = mode;
    ASSERT_EQ(core_.init(cfg), fw::ConfigError::kNone);
    task_ = std::make_unique<ControlTask<Core>>(core_, ctrl_, io_, ControlTaskConfig{});
    task_->reset();
  }
  /// One tick with fresh, plausible sensor frames (a slow sine stroke, so the
  /// core's stuck-sensor test stays quiet).
  control::ControllerOutput good_tick() {
    const auto c = static_cast<std::uint8_t>(k_ & 0xFF);
    const float x = 0.01f * static_cast<float>(std::sin(0.01 * static_cast<double>(k_)));
    hal::CanFrame f;
    protocol::encode(protocol::DaqMotion{x, true, 1000.0f * x / 0.01f, true, c}, 3, f);
    send(f);
    protocol::encode(protocol::DaqAccel{0.5f, true, 0.1f, true, c}, 3, f);
    send(f);
    protocol::encode(protocol::DriveStatus{2.5f, 2.5f, 0, protocol::DriveState::kFollowing, c}, 2, f);
    send(f);
    ++k_;
    return task_->run_tick();
  }
  void send(hal::CanFrame f) {
    if (corrupt_next_) {
      f.data[0] ^= 0x01;
      corrupt_next_ = false;
    }
    daq_.send(f);
  }
  control::ControllerOutput silent_tick() {
    ++k_;
    return task_->run_tick();
  }

  sim::MemoryBus bus_;
  sim::MemoryCanEndpoint& ctrl_;
  sim::MemoryCanEndpoint& daq_;
  sim::MemoryIo io_;
  Core core_;
  std::unique_ptr<ControlTask<Core>> task_;
  std::uint64_t k_ = 0;
  bool corrupt_next_ = false;
};

TEST_F(Faults, DriveFaultLineDisablesTheDriveInTheSameTick) {
  init(control::ControlMode::kPassiveOn);
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(good_tick().drive_enable);
  io_.set_input(hal::InputLine::kDriveFault, true);
  const auto out = good_tick();  // the first tick that reads the asserted line
  EXPECT_FALSE(out.drive_enable);
  EXPECT_EQ(out.current_command_a, 0.0f);
  EXPECT_FALSE(io_.output(hal::OutputLine::kDriveEnable)) << "the enable line is low in that tick";
  EXPECT_TRUE(task_->status().drive_fault);
}

TEST_F(Faults, UnreadableFaultLineCountsAsAFault) {
  init(control::ControlMode::kPassiveOn);
  good_tick();
  io_.set_failing(true);
  const auto out = good_tick();
  EXPECT_FALSE(out.drive_enable);
  EXPECT_GE(task_->status().gpio_errors, 1u);
}

TEST_F(Faults, FaultReportedByTheDriveDisablesIt) {
  init(control::ControlMode::kPassiveOn);
  for (int i = 0; i < 10; ++i) good_tick();
  hal::CanFrame f;
  protocol::encode(protocol::DriveStatus{0.0f, 0.0f, protocol::drive_fault::kOverTemperature,
                                         protocol::DriveState::kFault, static_cast<std::uint8_t>(k_)},
                   2, f);
  daq_.send(f);
  const auto out = task_->run_tick();
  EXPECT_FALSE(out.drive_enable);
  EXPECT_EQ(out.current_command_a, 0.0f);
}

TEST_F(Faults, MissingSensorFramesFallBackToTheSafeCurrentWithinSixTicks) {
  // Semi-active, sensor frames stop: the core holds the last command for
  // fault_hold_ticks = 5 ticks, then commands the fallback 2.5 A (SAFE-2).
  init(control::ControlMode::kSemiActive);
  for (int i = 0; i < 200; ++i) good_tick();
  int ticks_to_safe = 0;
  control::ControllerOutput out;
  do {
    out = silent_tick();
    ++ticks_to_safe;
  } while (out.current_command_a != 2.5f && ticks_to_safe < 100);
  EXPECT_LE(ticks_to_safe, 6);
  EXPECT_TRUE(out.drive_enable);
  // After the task's own timeout (10 ticks) the stream counts as timed out.
  for (int i = 0; i < 10; ++i) silent_tick();
  EXPECT_TRUE(task_->status().sensor_timeout);
  // Sensors return with any counter (re-synchronised) and control resumes.
  k_ += 77;
  for (int i = 0; i < 3; ++i) good_tick();
  EXPECT_FALSE(task_->status().sensor_timeout);
  EXPECT_TRUE(task_->status().last_input.flags.disp_valid);
}

TEST_F(Faults, CorruptedSensorFrameIsDroppedAndCounted) {
  init(control::ControlMode::kPassiveOff);
  good_tick();
  corrupt_next_ = true;  // the DaqMotion of the next tick
  good_tick();
  EXPECT_EQ(task_->status().rejected(protocol::DecodeError::kBadChecksum), 1u);
  EXPECT_EQ(task_->status().last_input.tick, 0u) << "the core got the old sample's tick, i.e. a stale sample";
}

TEST_F(Faults, ReplayedSensorFrameIsRejected) {
  init(control::ControlMode::kPassiveOff);
  hal::CanFrame old;
  protocol::encode(protocol::DaqMotion{0.2f, true, 5000.0f, true, 0}, 3, old);
  for (int i = 0; i < 20; ++i) good_tick();
  daq_.send(old);  // counter 0, recorded at tick 0
  task_->run_tick();
  EXPECT_EQ(task_->status().stale_counters, 1u);
  EXPECT_NE(task_->status().last_input.damper_disp_m, 0.2f);
}

TEST_F(Faults, BusOffIsReportedAndCommandsAreStillAttempted) {
  init(control::ControlMode::kPassiveOn);
  for (int i = 0; i < 10; ++i) good_tick();
  ctrl_.set_state(hal::BusState::kBusOff);
  for (int i = 0; i < 20; ++i) silent_tick();
  EXPECT_EQ(task_->status().bus_state, hal::BusState::kBusOff);
  EXPECT_EQ(task_->status().bus_error_ticks, 20u);
  EXPECT_GE(task_->status().tx_errors, 20u);
  EXPECT_TRUE(task_->status().sensor_timeout) << "nothing arrives in bus-off";
  ctrl_.set_state(hal::BusState::kActive);
  for (int i = 0; i < 100; ++i) good_tick();  // a heartbeat goes out with the bus-error flag
  hal::CanFrame f;
  bool flagged = false;
  while (daq_.receive(f) == hal::CanResult::kOk) {
    protocol::ControllerStatus s;
    if (protocol::decode(f, 1, s) == protocol::DecodeError::kOk)
      flagged |= (s.flags & protocol::controller_flag::kBusError) != 0;
  }
  EXPECT_TRUE(flagged);
}

}  // namespace
}  // namespace mrd::app
