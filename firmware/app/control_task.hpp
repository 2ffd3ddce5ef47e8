#pragma once
/// The control task around the control core: one call per control period,
/// made by the board runtime (firmware/app/runtime.hpp).
///
/// <pre>
///   poll_rx():   drain the bus → decode (codec) → counter check → latest sample per stream
///   step_tick(): stream timeouts → fault line → ControllerInput → core.step()
///                → CurrentCommand frame → drive-enable / maintenance lines → heartbeat
/// </pre>
///
/// The same task runs on the board (SocketCAN, libgpiod), in the in-process
/// `sim` board and in the tests (in-memory bus and lines); only the adapters
/// behind hal::CanBus and hal::DigitalIo change. Fail-safe decisions on the
/// values (stale or invalid sensors, drive fault) are the core's
/// (firmware/core/damper_controller.hpp, SAFE-1…4): the task hands it the
/// sample's tick and validity flags and the fault line, and applies what the
/// core returns. The task itself only refuses frames (codec, counters, node
/// ids), ages the streams, and fails safe where the core cannot see: a GPIO
/// read error counts as a drive fault; an output the codec cannot encode
/// (not finite, beyond ±10 A) is sent as 0 A with the drive disabled.
///
/// Nothing in poll_rx() or step_tick() allocates, throws or blocks.

#include <algorithm>
#include <array>
#include <concepts>
#include <cstdint>
#include <vector>

#include "mrd/control/io.hpp"
#include "mrd/hal/can_bus.hpp"
#include "mrd/hal/digital_io.hpp"
#include "mrd/protocol/codec.hpp"

namespace mrd::app {

/// What the task needs of a control core: fw::DamperController<Policy> or a stand-in.
template <class C>
concept ControlCore = requires(C c, const control::ControllerInput& in) {
  { c.step(in) } -> std::same_as<control::ControllerOutput>;
  c.reset();
};

struct ControlTaskConfig {
  protocol::NodeIds nodes{};
  control::ControlMode mode = control::ControlMode::kPassiveOff;  ///< reported in frames
  /// A DAQ stream older than this is invalid and its counter re-synchronises (10 ms at 1 kHz).
  std::uint32_t sensor_timeout_ticks = 10;
  /// No DriveStatus for this long: flag "drive silent" (10 ms).
  std::uint32_t drive_status_timeout_ticks = 10;
  /// No MixingStatus for this long: the actuator counts as absent (500 ms).
  std::uint32_t actuator_timeout_ticks = 500;
  /// ControllerStatus, IdleStatus and MixingCommand period (100 ms).
  std::uint32_t heartbeat_period_ticks = 100;
};

/// The CAN ids the task listens to (for CAN_RAW_FILTER or the in-memory bus).
inline std::vector<hal::CanFilter> control_task_filters(const protocol::NodeIds& n) {
  using protocol::MsgId;
  return {{protocol::can_id(MsgId::kDaqMotion, n.daq), 0x7FF},
          {protocol::can_id(MsgId::kDaqAccel, n.daq), 0x7FF},
          {protocol::can_id(MsgId::kDriveStatus, n.drive), 0x7FF},
          {protocol::can_id(MsgId::kMixingStatus, n.actuator), 0x7FF}};
}

inline constexpr int kDecodeErrorKinds = 6;

/// Counters and latest values; everything a heartbeat or a log line needs.
struct ControlTaskStatus {
  std::uint64_t ticks = 0;
  std::uint64_t frames_received = 0;
  std::uint64_t frames_accepted = 0;
  std::array<std::uint32_t, kDecodeErrorKinds> rejected_by_error{};  ///< index protocol::DecodeError
  std::uint32_t repeated_counters = 0;
  std::uint32_t stale_counters = 0;
  std::uint32_t unexpected_ids = 0;  ///< frames not meant for us (another node, another message)
  std::uint32_t encode_errors = 0;
  std::uint32_t tx_errors = 0;
  std::uint32_t tx_would_block = 0;
  std::uint32_t gpio_errors = 0;
  std::uint32_t sensor_timeout_ticks = 0;  ///< ticks with the DAQ stream timed out
  std::uint32_t drive_fault_ticks = 0;
  std::uint32_t bus_error_ticks = 0;       ///< ticks in error-passive or bus-off
  std::uint32_t overruns = 0;              ///< set by the loop that runs the task
  bool sensor_timeout = false;
  bool drive_silent = false;
  bool drive_fault = false;
  bool actuator_present = false;
  hal::BusState bus_state = hal::BusState::kActive;
  control::ControllerInput last_input{};
  control::ControllerOutput last_output{};
  protocol::DriveStatus last_drive{};
  protocol::MixingStatus last_mixing{};

  std::uint32_t rejected(protocol::DecodeError e) const noexcept { return rejected_by_error[static_cast<int>(e)]; }
  std::uint32_t rejected_total() const noexcept {
    std::uint32_t n = repeated_counters + stale_counters;
    for (int i = 1; i < kDecodeErrorKinds; ++i) n += rejected_by_error[i];
    return n;
  }
};

template <ControlCore Core>
class ControlTask {
 public:
  ControlTask(Core& core, hal::CanBus& bus, hal::DigitalIo& io, const ControlTaskConfig& config) noexcept
      : core_(core), bus_(bus), io_(io), config_(config) {}

  /// Back to the state after construction; resets the core too.
  void reset() noexcept {
    core_.reset();
    motion_ = {};
    accel_ = {};
    drive_ = {};
    mixing_ = {};
    status_ = {};
    tick_ = 0;
    command_counter_ = heartbeat_counter_ = mixing_counter_ = 0;
    enable_written_ = maintenance_written_ = false;
    bus_error_since_heartbeat_ = false;
    idle_ = {};
    idle_set_ = false;
    idle_counter_ = 0;
  }

  /// One control period: poll_rx() then step_tick().
  control::ControllerOutput run_tick() noexcept {
    poll_rx();
    return step_tick();
  }

  /// Drains every received frame into the latest sample of its stream.
  void poll_rx() noexcept {
    hal::CanFrame f;
    for (;;) {
      const hal::CanResult r = bus_.receive(f);
      if (r != hal::CanResult::kOk) break;
      ++status_.frames_received;
      dispatch(f);
    }
    status_.bus_state = bus_.state();
  }

  /// Lockstep: a DaqMotion, a DaqAccel and a DriveStatus with one common
  /// counter (the plant's tick) arrived since the last step_tick().
  bool lockstep_ready() const noexcept {
    return motion_.fresh && accel_.fresh && drive_.fresh && motion_.msg.counter == accel_.msg.counter &&
           motion_.msg.counter == drive_.msg.counter;
  }

  /// Steps the core on the latest samples and sends its command.
  control::ControllerOutput step_tick() noexcept {
    const std::uint64_t now = tick_;
    const StreamHealth health = age_streams();
    status_.drive_fault = read_fault_line() || reported_fault(health.drive_ok);
    if (status_.drive_fault) bump(status_.drive_fault_ticks);

    const control::ControllerInput in = core_input(health, now);
    control::ControllerOutput out = core_.step(in);
    send_command(out);

    // Lines: written when they change (and once at the start).
    write_line(hal::OutputLine::kDriveEnable, out.drive_enable, enable_written_, enable_level_);
    write_line(hal::OutputLine::kMaintenanceDue, maintenance_due_, maintenance_written_, maintenance_level_);

    watch_bus();
    if (now % config_.heartbeat_period_ticks == 0) {
      send_heartbeat(out);
      if (mixing_request_.action == protocol::MixingAction::kStart || mixing_stop_pending_) send_mixing();
    }

    motion_.fresh = accel_.fresh = drive_.fresh = false;
    status_.last_input = in;
    status_.last_output = out;
    status_.last_drive = drive_.msg;
    status_.last_mixing = mixing_.msg;
    ++tick_;
    status_.ticks = tick_;
    return out;
  }

  /// Asks the mixing actuator for a cycle (sent with every heartbeat until stopped).
  void request_mixing(const protocol::MixingCommand& cmd) noexcept {
    mixing_request_ = cmd;
    mixing_stop_pending_ = cmd.action == protocol::MixingAction::kStop;
  }
  /// Sends `s` as the IdleStatus frame with every heartbeat from now on
  /// (the counter is the task's).
  void set_idle_status(const protocol::IdleStatus& s) noexcept {
    idle_ = s;
    idle_set_ = true;
  }
  /// Drives the maintenance-due line from the next tick on.
  void set_maintenance_due(bool due) noexcept { maintenance_due_ = due; }
  /// The loop reports missed periods here; they go out in the heartbeat.
  void set_overruns(std::uint32_t n) noexcept { status_.overruns = n; }

  const ControlTaskStatus& status() const noexcept { return status_; }
  std::uint64_t tick() const noexcept { return tick_; }

 private:
  template <class M>
  struct Stream {
    M msg{};
    protocol::CounterCheck counter{};
    bool seen = false;
    bool fresh = false;
    std::uint64_t tick = 0;  ///< task tick of the latest accepted frame
  };

  /// Which streams arrived within their timeouts this tick.
  struct StreamHealth {
    bool motion_ok = false;
    bool accel_ok = false;
    bool drive_ok = false;
  };

  /// Stream ages: a stream past its timeout is invalid and its counter
  /// re-synchronises; the actuator counts as present while it reports.
  StreamHealth age_streams() noexcept {
    StreamHealth h;
    h.motion_ok = alive(motion_, config_.sensor_timeout_ticks);
    h.accel_ok = alive(accel_, config_.sensor_timeout_ticks);
    h.drive_ok = alive(drive_, config_.drive_status_timeout_ticks);
    status_.actuator_present = alive(mixing_, config_.actuator_timeout_ticks);
    if (!h.motion_ok && motion_.seen) motion_.counter.desync();
    if (!h.accel_ok && accel_.seen) accel_.counter.desync();
    if (!h.drive_ok && drive_.seen) drive_.counter.desync();
    status_.sensor_timeout = !h.motion_ok;
    if (!h.motion_ok) bump(status_.sensor_timeout_ticks);
    status_.drive_silent = !h.drive_ok;
    return h;
  }

  /// The drive's fault line; an unreadable line counts as a fault.
  bool read_fault_line() noexcept {
    bool line_fault = false;
    if (!io_.read(hal::InputLine::kDriveFault, line_fault)) {
      bump(status_.gpio_errors);
      line_fault = true;
    }
    return line_fault;
  }

  /// A hard fault in the drive's own status (when it is recent).
  bool reported_fault(bool drive_ok) const noexcept {
    constexpr std::uint8_t kHardFaults = protocol::drive_fault::kOverCurrent | protocol::drive_fault::kOverTemperature |
                                         protocol::drive_fault::kUnderVoltage | protocol::drive_fault::kFaultLine;
    return drive_ok && (drive_.msg.state == protocol::DriveState::kFault || (drive_.msg.faults & kHardFaults) != 0);
  }

  /// The core's input: the sample's own tick lets the core judge staleness.
  control::ControllerInput core_input(const StreamHealth& h, std::uint64_t now) const noexcept {
    control::ControllerInput in;
    in.tick = motion_.seen ? motion_.tick : now;
    in.damper_disp_m = motion_.msg.damper_disp_m;
    in.damper_force_n = motion_.msg.damper_force_n;
    in.flags.disp_valid = h.motion_ok && motion_.msg.disp_valid;
    in.flags.force_valid = h.motion_ok && motion_.msg.force_valid;
    in.ground_accel_m_s2 = accel_.msg.ground_accel_m_s2;
    in.base_accel_m_s2 = accel_.msg.base_accel_m_s2;
    in.flags.ground_accel_valid = h.accel_ok && accel_.msg.ground_valid;
    in.flags.base_accel_valid = h.accel_ok && accel_.msg.base_valid;
    in.coil_current_a = drive_.msg.measured_current_a;
    in.flags.drive_fault = status_.drive_fault;
    return in;
  }

  /// The command frame; what cannot be encoded goes out as "off" (and `out` says so).
  void send_command(control::ControllerOutput& out) noexcept {
    protocol::CurrentCommand cmd{out.current_command_a, out.drive_enable, config_.mode, command_counter_};
    hal::CanFrame f;
    if (!protocol::encode(cmd, config_.nodes.controller, f)) {
      bump(status_.encode_errors);
      out.current_command_a = 0.0f;
      out.drive_enable = false;
      cmd = protocol::CurrentCommand{0.0f, false, config_.mode, command_counter_};
      (void)protocol::encode(cmd, config_.nodes.controller, f);
    }
    ++command_counter_;
    transmit(f);
  }

  /// Bus state: error-passive and bus-off ticks are counted and flagged in the next heartbeat.
  void watch_bus() noexcept {
    status_.bus_state = bus_.state();
    if (status_.bus_state == hal::BusState::kPassive || status_.bus_state == hal::BusState::kBusOff) {
      bump(status_.bus_error_ticks);
      bus_error_since_heartbeat_ = true;
    }
  }

  static void bump(std::uint32_t& c) noexcept {
    if (c != 0xFFFFFFFFu) ++c;
  }

  template <class M>
  bool alive(const Stream<M>& s, std::uint32_t timeout) const noexcept {
    return s.seen && tick_ - s.tick <= timeout;
  }

  template <class M>
  void accept(Stream<M>& s, const hal::CanFrame& f, std::uint8_t sender) noexcept {
    M m;
    const protocol::DecodeError e = protocol::decode(f, sender, m);
    if (e != protocol::DecodeError::kOk) {
      bump(status_.rejected_by_error[static_cast<int>(e)]);
      return;
    }
    switch (s.counter.check(m.counter)) {
      case protocol::CounterVerdict::kRepeated: bump(status_.repeated_counters); return;
      case protocol::CounterVerdict::kStale: bump(status_.stale_counters); return;
      default: break;
    }
    s.msg = m;
    s.seen = true;
    s.fresh = true;
    s.tick = tick_;
    ++status_.frames_accepted;
  }

  void dispatch(const hal::CanFrame& f) noexcept {
    using protocol::can_id;
    using protocol::MsgId;
    const auto& n = config_.nodes;
    if (f.extended) {
      bump(status_.unexpected_ids);
    } else if (f.id == can_id(MsgId::kDaqMotion, n.daq)) {
      accept(motion_, f, n.daq);
    } else if (f.id == can_id(MsgId::kDaqAccel, n.daq)) {
      accept(accel_, f, n.daq);
    } else if (f.id == can_id(MsgId::kDriveStatus, n.drive)) {
      accept(drive_, f, n.drive);
    } else if (f.id == can_id(MsgId::kMixingStatus, n.actuator)) {
      accept(mixing_, f, n.actuator);
    } else {
      bump(status_.unexpected_ids);
    }
  }

  void transmit(const hal::CanFrame& f) noexcept {
    switch (bus_.send(f)) {
      case hal::CanResult::kOk: break;
      case hal::CanResult::kWouldBlock: bump(status_.tx_would_block); break;
      case hal::CanResult::kError: bump(status_.tx_errors); break;
    }
  }

  void write_line(hal::OutputLine line, bool level, bool& written, bool& last) noexcept {
    if (written && last == level) return;
    if (io_.write(line, level)) {
      written = true;
      last = level;
    } else {
      bump(status_.gpio_errors);
    }
  }

  void send_heartbeat(const control::ControllerOutput& out) noexcept {
    namespace cf = protocol::controller_flag;
    std::uint8_t flags = 0;
    if (out.drive_enable) flags |= cf::kDriveEnabled;
    if (status_.sensor_timeout) flags |= cf::kSensorTimeout;
    if (status_.drive_fault) flags |= cf::kDriveFault;
    if (status_.drive_silent) flags |= cf::kDriveSilent;
    if (bus_error_since_heartbeat_) flags |= cf::kBusError;
    if (maintenance_due_) flags |= cf::kMaintenanceDue;
    const protocol::ControllerStatus hb{config_.mode, flags,
                                        static_cast<std::uint16_t>(std::min<std::uint32_t>(status_.overruns, 0xFFFF)),
                                        static_cast<std::uint16_t>(std::min<std::uint32_t>(status_.rejected_total(), 0xFFFF)),
                                        heartbeat_counter_++};
    hal::CanFrame f;
    if (protocol::encode(hb, config_.nodes.controller, f)) transmit(f);
    bus_error_since_heartbeat_ = false;
    if (idle_set_) {
      protocol::IdleStatus idle = idle_;
      idle.counter = idle_counter_++;
      if (protocol::encode(idle, config_.nodes.controller, f)) {
        transmit(f);
      } else {
        bump(status_.encode_errors);
      }
    }
  }

  void send_mixing() noexcept {
    protocol::MixingCommand m = mixing_request_;
    m.counter = mixing_counter_++;
    hal::CanFrame f;
    if (protocol::encode(m, config_.nodes.controller, f)) {
      transmit(f);
    } else {
      bump(status_.encode_errors);
    }
    mixing_stop_pending_ = false;
  }

  Core& core_;
  hal::CanBus& bus_;
  hal::DigitalIo& io_;
  ControlTaskConfig config_;

  Stream<protocol::DaqMotion> motion_{};
  Stream<protocol::DaqAccel> accel_{};
  Stream<protocol::DriveStatus> drive_{};
  Stream<protocol::MixingStatus> mixing_{};
  ControlTaskStatus status_{};
  std::uint64_t tick_ = 0;
  std::uint8_t command_counter_ = 0, heartbeat_counter_ = 0, mixing_counter_ = 0;
  bool enable_written_ = false, enable_level_ = false;
  bool maintenance_written_ = false, maintenance_level_ = false, maintenance_due_ = false;
  bool bus_error_since_heartbeat_ = false;
  protocol::MixingCommand mixing_request_{};
  bool mixing_stop_pending_ = false;
  protocol::IdleStatus idle_{};
  bool idle_set_ = false;
  std::uint8_t idle_counter_ = 0;
};

}  // namespace mrd::app
