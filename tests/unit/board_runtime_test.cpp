// The board runtime on in-memory adapters and manual clocks: the fixed-period
// loop and the lockstep loop with their log lines, the mixing task's request
// reaching the bus as a MixingCommand and its maintenance output reaching
// its line, the state store served after the tick, and a board without GPIO.
#include "firmware/app/runtime.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "firmware/app/no_lines_fitted.hpp"
#include "firmware/core/damper_controller.hpp"
#include "firmware/platform/sim/manual_clock.hpp"
#include "firmware/platform/sim/memory_bus.hpp"
#include "firmware/platform/sim/memory_io.hpp"
#include "firmware/platform/sim/memory_state_store.hpp"
#include "mrd/units.hpp"

namespace mrd::app {
namespace {

using Core = fw::DamperController<num::Float32Policy>;

/// Keeps every line.
struct RecordingLog final : RuntimeLog {
  std::vector<std::string> lines;
  void line(const char* text) noexcept override { lines.emplace_back(text); }
};

class RuntimeFixture : public ::testing::Test {
 protected:
  RuntimeFixture() : ctrl_(bus_.attach(1024)), peer_(bus_.attach(1024)) {
    ctrl_.set_filters(control_task_filters(nodes_));
    EXPECT_EQ(core_.init(fw::default_controller_config(control::ControlMode::kPassiveOn, 1e-3)),
              fw::ConfigError::kNone);
  }
  RuntimePorts ports() {
    RuntimePorts p{clock_, ctrl_, io_};
    p.log = &log_;
    return p;
  }
  /// One plant tick's inputs (DAQ and drive), and the actuator's status when `actuator`.
  void send_inputs(std::uint8_t c, bool actuator = false) {
    hal::CanFrame f;
    ASSERT_TRUE(protocol::encode(protocol::DaqMotion{0.001f, true, 1000.0f, true, c}, nodes_.daq, f));
    peer_.send(f);
    ASSERT_TRUE(protocol::encode(protocol::DaqAccel{0.0f, true, 0.0f, true, c}, nodes_.daq, f));
    peer_.send(f);
    ASSERT_TRUE(protocol::encode(protocol::DriveStatus{2.5f, 2.5f, 0, protocol::DriveState::kFollowing, c},
                                 nodes_.drive, f));
    peer_.send(f);
    if (actuator) {
      ASSERT_TRUE(protocol::encode(protocol::MixingStatus{protocol::MixingState::kIdle, 0.0f, 0.0f, 0, c},
                                   nodes_.actuator, f));
      peer_.send(f);
    }
  }
  /// The MixingCommands the controller sent since the last call.
  std::vector<protocol::MixingCommand> mixing_commands() {
    std::vector<protocol::MixingCommand> out;
    hal::CanFrame f;
    while (peer_.receive(f) == hal::CanResult::kOk) {
      protocol::MixingCommand m;
      if (protocol::decode(f, nodes_.controller, m) == protocol::DecodeError::kOk) out.push_back(m);
    }
    return out;
  }
  int lines_containing(const std::string& text) const {
    int n = 0;
    for (const auto& l : log_.lines) n += l.find(text) != std::string::npos ? 1 : 0;
    return n;
  }

  protocol::NodeIds nodes_{};
  sim::MemoryBus bus_;
  sim::MemoryCanEndpoint& ctrl_;
  sim::MemoryCanEndpoint& peer_;
  sim::MemoryIo io_;
  sim::ManualClock clock_;
  RecordingLog log_;
  Core core_;
  std::atomic<bool> stop_{false};
};

TEST_F(RuntimeFixture, FixedPeriodLoopRunsOnTheClockAndEndsWithTheSummary) {
  RuntimeConfig rc;
  rc.max_ticks = 250;
  rc.report_every_ns = 100'000'000;  // every 100 ticks
  BoardRuntime<Core> rt(core_, ports(), ControlTaskConfig{}, rc);
  const std::int64_t t0 = clock_.now_ns();
  rt.run_periodic(stop_);
  EXPECT_EQ(rt.task().tick(), 250u);
  EXPECT_EQ(clock_.now_ns() - t0, 250 * rc.period_ns) << "slept to each deadline, no drift";
  EXPECT_EQ(rt.timing().overruns, 0u);
  EXPECT_EQ(lines_containing("mrd-firmware: summary ticks="), 3) << "ticks 100 and 200, and at the end";
  EXPECT_EQ(log_.lines.back().rfind("mrd-firmware: summary ticks=250 overruns=0 worst_late_us=0.0 ", 0), 0u)
      << log_.lines.back();
  // No sensors: passive-on still enables the drive from the first tick on.
  EXPECT_EQ(lines_containing("mrd-firmware: tick 0: drive-enable line active"), 1);
  EXPECT_TRUE(io_.output(hal::OutputLine::kDriveEnable));
}

/// The controller's bus in lockstep with a scripted plant: each wait for the
/// bus lets the plant send its next tick's inputs, until it has none left;
/// then the wait sleeps its whole timeout on the manual clock, as a socket would.
class LockstepBus final : public hal::CanBus {
 public:
  LockstepBus(hal::CanBus& bus, sim::ManualClock& clock, std::function<bool()> next_plant_tick)
      : bus_(bus), clock_(clock), next_(std::move(next_plant_tick)) {}
  hal::CanResult send(const hal::CanFrame& f) noexcept override { return bus_.send(f); }
  hal::CanResult receive(hal::CanFrame& f) noexcept override { return bus_.receive(f); }
  hal::BusState state() const noexcept override { return bus_.state(); }
  bool wait_readable(std::chrono::nanoseconds timeout) noexcept override {
    if (bus_.wait_readable(timeout) || next_()) return true;
    clock_.advance_ns(timeout.count());
    return false;
  }

 private:
  hal::CanBus& bus_;
  sim::ManualClock& clock_;
  std::function<bool()> next_;
};

class LockstepFixture : public RuntimeFixture {
 protected:
  /// A runtime whose plant sends `plant_ticks` complete input sets, one per wait.
  BoardRuntime<Core> runtime(int plant_ticks, const RuntimeConfig& rc) {
    plant_ticks_ = plant_ticks;
    RuntimePorts p{clock_, lockstep_bus_, io_};
    p.log = &log_;
    return BoardRuntime<Core>(core_, p, ControlTaskConfig{}, rc);
  }
  bool next_plant_tick() {
    if (sent_ >= plant_ticks_) return false;
    send_inputs(static_cast<std::uint8_t>(sent_++));
    return true;
  }
  int plant_ticks_ = 0;
  int sent_ = 0;
  LockstepBus lockstep_bus_{ctrl_, clock_, [this] { return next_plant_tick(); }};
};

TEST_F(LockstepFixture, StepsOncePerCompleteInputSet) {
  RuntimeConfig rc;
  rc.max_ticks = 3;
  BoardRuntime<Core> rt = runtime(5, rc);
  rt.run_lockstep(stop_);
  EXPECT_EQ(rt.task().tick(), 3u);
  EXPECT_EQ(rt.task().status().frames_accepted, 9u);
  EXPECT_EQ(rt.task().status().last_input.damper_disp_m, 0.001f);
  EXPECT_EQ(log_.lines.back().rfind("mrd-firmware: summary ticks=3 ", 0), 0u) << log_.lines.back();
}

TEST_F(LockstepFixture, EndsWhenThePlantFallsSilent) {
  RuntimeConfig rc;
  rc.lockstep_idle_exit_ns = 2'000'000'000;
  BoardRuntime<Core> rt = runtime(2, rc);
  rt.run_lockstep(stop_);
  EXPECT_EQ(rt.task().tick(), 2u);
  EXPECT_EQ(lines_containing("mrd-firmware: lockstep: no complete tick for 2.1 s after tick 2: the plant has finished"),
            1)
      << log_.lines.front();
}

TEST_F(RuntimeFixture, StopsWhenAskedTo) {
  stop_ = true;
  BoardRuntime<Core> rt(core_, ports(), ControlTaskConfig{}, RuntimeConfig{});
  rt.run_periodic(stop_);
  EXPECT_EQ(rt.task().tick(), 0u);
  EXPECT_EQ(lines_containing("summary ticks=0 "), 1);
}

/// A mixing task on a fully settled fluid: due at once.
MixingTask settled_mixing_task(bool actuator_fitted) {
  MixingTaskConfig mc;
  mc.scheduler.actuator_fitted = actuator_fitted;
  MixingTask m;
  EXPECT_TRUE(m.init(mc));
  m.boot_with(m.estimator().model().max_settling_time_s(), 0, 1.7e9);
  return m;
}

TEST_F(RuntimeFixture, ADueMixingRequestReachesTheBusAsAMixingCommand) {
  BoardRuntime<Core> rt(core_, ports(), ControlTaskConfig{}, RuntimeConfig{});
  MixingTask mixing = settled_mixing_task(true);
  rt.attach_mixing(&mixing);
  std::vector<protocol::MixingCommand> sent;
  for (std::uint8_t k = 0; k <= 100; ++k) {
    send_inputs(k, true);
    rt.run_tick();
    for (const auto& m : mixing_commands()) sent.push_back(m);
  }
  ASSERT_EQ(mixing.output().state, fw::SchedulerState::kRequested);
  ASSERT_EQ(sent.size(), 1u) << "requested on tick 0, sent with the heartbeat of tick 100";
  EXPECT_EQ(sent[0].action, protocol::MixingAction::kStart);
  const fw::MixingPlan& plan = mixing.output().plan;
  EXPECT_NEAR(sent[0].amplitude_m, plan.amplitude_m, 1e-5);
  EXPECT_NEAR(sent[0].frequency_hz, plan.frequency_hz, 0.01);
  EXPECT_GE(sent[0].duration_s, plan.duration_s);
  EXPECT_FALSE(io_.output(hal::OutputLine::kMaintenanceDue));
}

TEST_F(RuntimeFixture, MaintenanceDueReachesItsLineAndTheHeartbeat) {
  BoardRuntime<Core> rt(core_, ports(), ControlTaskConfig{}, RuntimeConfig{});
  MixingTask mixing = settled_mixing_task(false);
  rt.attach_mixing(&mixing);
  send_inputs(0);
  rt.run_tick();
  EXPECT_TRUE(mixing.output().maintenance_required);
  EXPECT_FALSE(io_.output(hal::OutputLine::kMaintenanceDue)) << "driven from the next tick on";
  send_inputs(1);
  rt.run_tick();
  EXPECT_TRUE(io_.output(hal::OutputLine::kMaintenanceDue));
  for (std::uint8_t k = 2; k <= 100; ++k) {
    send_inputs(k);
    rt.run_tick();
  }
  bool flagged = false;
  hal::CanFrame f;
  while (peer_.receive(f) == hal::CanResult::kOk) {
    protocol::ControllerStatus hb;
    if (protocol::decode(f, nodes_.controller, hb) == protocol::DecodeError::kOk && hb.counter == 1)
      flagged = (hb.flags & protocol::controller_flag::kMaintenanceDue) != 0;
  }
  EXPECT_TRUE(flagged) << "the heartbeat of tick 100 says maintenance is due";
  EXPECT_TRUE(mixing_commands().empty()) << "no actuator: no command";
}

TEST_F(RuntimeFixture, WithoutAMixingTaskNothingIsRequestedAndTheLineStaysLow) {
  BoardRuntime<Core> rt(core_, ports(), ControlTaskConfig{}, RuntimeConfig{});
  std::vector<protocol::MixingCommand> sent;
  for (std::uint8_t k = 0; k <= 200; ++k) {
    send_inputs(k, true);
    rt.run_tick();
    for (const auto& m : mixing_commands()) sent.push_back(m);
  }
  EXPECT_TRUE(sent.empty());
  EXPECT_FALSE(io_.output(hal::OutputLine::kMaintenanceDue));
}

TEST_F(RuntimeFixture, TheStateStoreIsServedAfterTheTickWhenTheWallClockIsValid) {
  sim::MemoryStateStore store;
  sim::ManualWallClock rtc;
  RuntimePorts p = ports();
  p.store = &store;
  p.rtc = &rtc;
  BoardRuntime<Core> rt(core_, p, ControlTaskConfig{}, RuntimeConfig{});
  MixingTaskConfig mc;
  MixingTask mixing;
  ASSERT_TRUE(mixing.init(mc));
  (void)mixing.boot(store, 0, 0.0, false);  // nothing stored, no wall clock: fully settled, save due
  rt.attach_mixing(&mixing);
  ASSERT_TRUE(mixing.save_due());
  send_inputs(0);
  rt.run_tick();
  EXPECT_EQ(store.saves(), 0u) << "no valid wall clock yet: the stored record (if any) is the safer one";
  rtc.set(1.7e9);
  send_inputs(1);
  rt.run_tick();
  EXPECT_EQ(store.saves(), 1u);
  EXPECT_FALSE(mixing.save_due());
}

/// The board's fixed-point build of the mixing task, booted half a year idle.
using FixedMixing = BasicMixingTask<num::Fixed32Policy>;

TEST_F(RuntimeFixture, TheFixedPointMixingTaskRunsOnTheBoardAndItsEstimateGoesOutAsIdleStatus) {
  BoardRuntime<Core, FixedMixing> rt(core_, ports(), ControlTaskConfig{}, RuntimeConfig{});
  FixedMixing mixing;
  ASSERT_TRUE(mixing.init(MixingTaskConfig{}));
  constexpr double kHalfYear_s = 0.5 * units::kSecondsPerYear;
  mixing.boot_with(kHalfYear_s, 0, std::int64_t{1'700'000'000'000});
  rt.attach_mixing(&mixing);
  std::vector<protocol::IdleStatus> frames;
  for (std::uint8_t k = 0; k <= 100; ++k) {
    send_inputs(k, true);
    rt.run_tick();
    hal::CanFrame f;
    while (peer_.receive(f) == hal::CanResult::kOk) {
      protocol::IdleStatus s;
      if (protocol::decode(f, nodes_.controller, s) == protocol::DecodeError::kOk) frames.push_back(s);
    }
  }
  // Heartbeats at ticks 0 and 100; the first goes out before the mixing task's
  // first step (nothing to send yet), so one IdleStatus.
  ASSERT_EQ(frames.size(), 1u);
  // Half a Julian year is 0.5 · 365.25 · 24 = 4383 h (plus 0.1 s of ticks).
  EXPECT_EQ(frames[0].equivalent_idle_h, 4383u);
  const auto& e = mixing.estimator().estimate();
  EXPECT_NEAR(frames[0].participant_ratio, static_cast<double>(e.participant_ratio), 0.002) << "0.004 steps";
  EXPECT_NEAR(frames[0].capacity_fraction, static_cast<double>(e.capacity_fraction), 0.002);
  EXPECT_EQ(frames[0].scheduler, static_cast<std::uint8_t>(mixing.output().state));
  EXPECT_EQ(frames[0].flags, 0u) << "booted from a known state with a clock";
  rt.log_summary();
  EXPECT_NE(log_.lines.back().find(" idle_years=0.500"), std::string::npos) << log_.lines.back();
  EXPECT_NE(log_.lines.back().find(" cycles=0 saves=0 "), std::string::npos) << log_.lines.back();
}

TEST_F(RuntimeFixture, SchedulerTransitionsAndRequestsAreLogged) {
  BoardRuntime<Core> rt(core_, ports(), ControlTaskConfig{}, RuntimeConfig{});
  MixingTask mixing = settled_mixing_task(true);
  rt.attach_mixing(&mixing);
  send_inputs(0, true);
  rt.run_tick();
  ASSERT_EQ(mixing.output().state, fw::SchedulerState::kRequested);
  // A fully settled fluid passes idle → due → requested in one step (the
  // diagram in mixing_scheduler.hpp): one line for the change and one for the request.
  EXPECT_EQ(lines_containing("mrd-firmware: tick 0: scheduler idle -> requested"), 1);
  EXPECT_EQ(lines_containing("mrd-firmware: tick 0: mixing requested: cycles="), 1);
}

TEST(NoLinesFitted, AcceptsWritesAndReadsTheFaultInputInactive) {
  NoLinesFitted io;
  EXPECT_TRUE(io.write(hal::OutputLine::kDriveEnable, true));
  EXPECT_TRUE(io.write(hal::OutputLine::kMaintenanceDue, true));
  bool fault = true;
  EXPECT_TRUE(io.read(hal::InputLine::kDriveFault, fault));
  EXPECT_FALSE(fault);
}

}  // namespace
}  // namespace mrd::app
