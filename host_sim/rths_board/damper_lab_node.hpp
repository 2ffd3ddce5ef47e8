#pragma once
/// The emulated laboratory of the thesis's RTHS set-up as a node on the CAN
/// bus (`mrd-rths-lab --specimen damper`): the servo-hydraulic actuator
/// (rths::LookaheadServo: a whole-step delay, a first-order lag) stroking
/// the MR damper specimen (physics::MrDamper with its idle effects), the
/// damper's PWM drive (peers::DriveLogic, the `sim` board's drive) and the
/// DAQ of stroke and force. It speaks the damper controller's own frames, so
/// the board's firmware control task drives it as it drives a damper in the
/// closed loop:
///
/// <pre>
///   before the run:  DaqMotion(0) + DriveStatus(0) + RthsLabStatus "waiting" (the beacon, every 100 ms)
///   CurrentCommand k (controller → drive):  the drive takes it
///   RthsCommand k (runtime → lab):  drive decides u[k]; damper steps at the actuator's x, ẋ with u[k];
///                                   the actuator takes the command → DaqMotion(k+1) + DriveStatus(k+1)
///   a stop:          the actuator holds its last command, RthsLabStatus "stopped" after every command
///   RthsRunStatus:   the runtime's end of run: the node is finished
/// </pre>
///
/// The stop: |force| above force_limit_n, |stroke − the command's target|
/// above tracking_limit_m, a value that is not finite, or (called by the
/// program) no command for too long once running. The DAQ's stroke and force
/// go out in DaqMotion (0.1 µm, 0.1 N, ±800 kN); the drive reports the
/// coil's current in DriveStatus. Nothing in serve() allocates.

#include <cstdint>

#include "host_sim/peers/drive_logic.hpp"
#include "host_sim/rths/thesis_actuator.hpp"
#include "host_sim/rths_board/rths_frames.hpp"
#include "mrd/hal/can_bus.hpp"
#include "mrd/physics/mr_damper.hpp"

namespace mrd::rths_board {

struct DamperLabConfig {
  protocol::NodeIds nodes{};  ///< controller (the runtime's and the control task's node), drive, daq
  std::uint8_t lab_node = kDefaultLabNode;
  double rate_hz = 1000.0;          ///< one step per command
  double delay_s = 0.015;           ///< the actuator's pure delay (whole steps, ≥ 1)
  double lag_s = 0.002;             ///< its first-order servo lag
  physics::MrDamperParams damper{}; ///< the specimen
  double settling_quotient = 1.0;   ///< its idle state (physics::settling_quotient_after_idle)
  peers::DriveConfig drive{};       ///< nodes are taken from `nodes`
  double force_limit_n = 250e3;     ///< the actuator's force capacity
  double tracking_limit_m = 0.010;
  /// false: one step per command (the runtime's tick is the lab's); true:
  /// serve() only keeps the latest command and step_on_clock(), called on the
  /// laboratory's own clock every period, steps with it, holding the last
  /// one when none arrived.
  bool own_clock = false;
};

class DamperLabNode {
 public:
  /// Throws std::invalid_argument for a rate outside 100..65535 Hz or a
  /// delay under one step.
  DamperLabNode(hal::CanBus& bus, const DamperLabConfig& config);

  /// DaqMotion and DriveStatus of the present sample and the status.
  void send_beacon() noexcept;
  /// Every frame received (see the file comment). Returns the commands taken.
  int serve() noexcept;
  /// Own clock: one step with the latest command received (none since the
  /// last step: the last one held, counted in held_steps()). Does nothing
  /// before the first command or once finished.
  void step_on_clock() noexcept;
  /// Own clock: a command has arrived (the clock may start).
  bool has_command() const noexcept { return have_latest_; }
  /// Own clock: steps taken without a new command.
  std::uint32_t held_steps() const noexcept { return held_steps_; }
  /// No command for too long while running: hold and report the stop.
  void stop_for_command_timeout() noexcept;

  bool finished() const noexcept { return finished_; }
  RunState run_state() const noexcept { return run_state_; }
  LabState state() const noexcept { return state_; }
  LabStopReason stop_reason() const noexcept { return stop_; }
  std::uint64_t steps() const noexcept { return steps_; }
  std::uint64_t stop_step() const noexcept { return stop_step_; }
  std::uint32_t rejected() const noexcept { return rejected_; }
  std::uint32_t sequence_gaps() const noexcept { return sequence_gaps_; }
  /// Commands stepped on without the same tick's current command (the drive held its last).
  std::uint32_t current_late() const noexcept { return current_late_; }
  std::uint32_t tx_errors() const noexcept { return tx_errors_; }
  double peak_force_n() const noexcept { return peak_force_n_; }
  double stroke_m() const noexcept { return servo_.position_m(); }

 private:
  void take(const RthsCommand& c) noexcept;
  void send_sample() noexcept;
  void send_status() noexcept;
  void send(const hal::CanFrame& f) noexcept;

  hal::CanBus& bus_;
  DamperLabConfig config_;
  std::int64_t period_ns_;
  rths::LookaheadServo servo_;
  physics::MrDamper damper_;
  peers::DriveLogic drive_;
  double force_n_ = 0.0;
  double held_command_m_ = 0.0;
  RthsCommand latest_{};
  bool have_latest_ = false, latest_new_ = false;
  bool have_current_ = false;
  std::uint8_t current_counter_ = 0;
  LabState state_ = LabState::kWaiting;
  LabStopReason stop_ = LabStopReason::kNone;
  RunState run_state_ = RunState::kFinished;
  bool finished_ = false;
  std::uint64_t steps_ = 0, stop_step_ = 0;
  std::uint32_t rejected_ = 0, sequence_gaps_ = 0, current_late_ = 0, tx_errors_ = 0, held_steps_ = 0;
  std::uint8_t status_counter_ = 0;
  double peak_force_n_ = 0.0;
};

}  // namespace mrd::rths_board
