#pragma once
/// The PWM current drive's behaviour on the bus (a 30A8-class servo drive,
/// thesis §3.2: 15 A continuous, 30 A peak), without the coil: the coil's
/// current is the plant's physics (Eq. 4.5). Pure and clock-free: time comes
/// in as `now_ns` (the monotonic clock, or tick × period in lockstep).
///
/// Per drive period:
/// <pre>
///   fault asserted                          → output off, state fault
///   no valid command for > timeout          → safe current, state safe (fault bit 3)
///   last valid command has enable = 0       → output off, state disabled
///   otherwise                               → the commanded current, state following
/// </pre>
/// A command is valid when the codec accepts it from the controller's node
/// id and its rolling counter is in sequence (CAN_PROTOCOL.md). Frames from
/// any other node id are never taken as commands.

#include <cstdint>

#include "firmware/app/board_config.hpp"
#include "firmware/core/controller_config.hpp"
#include "mrd/hal/can_bus.hpp"
#include "mrd/protocol/codec.hpp"

namespace mrd::peers {

struct DriveConfig {
  protocol::NodeIds nodes{};
  /// Applied when commands stop: passive-on (§6.4), the damper keeps damping.
  float safe_current_a = static_cast<float>(fw::kPassiveOnCurrent_a);
  std::int64_t command_timeout_ns = 20'000'000;  ///< 20 ms (CAN_PROTOCOL.md)
  float peak_limit_a = 30.0f;                    ///< over-current fault above this measured current
};

/// The drive a board commands: its node ids, the safe current its damper's
/// passive-on current (the board's controller.nominal_current_a: 2.5 A for
/// the thesis's, §6.4) and the over-current fault above the drive's peak
/// (the board's [drive] peak_current_a, else controller.drive_peak_limit_a:
/// 30 A for the thesis rig's, §3.2).
DriveConfig drive_config(const app::BoardConfig& board) noexcept;

struct DriveOutput {
  float applied_current_a = 0.0f;  ///< set point driven into the coil over the next period
  bool output_on = false;
  protocol::DriveState state = protocol::DriveState::kDisabled;
  std::uint8_t faults = 0;  ///< protocol::drive_fault bits
};

struct DriveCounters {
  std::uint32_t accepted = 0;
  std::uint32_t rejected = 0;    ///< codec errors on a command from the controller's id
  std::uint32_t repeated = 0;
  std::uint32_t stale = 0;
  std::uint32_t foreign = 0;     ///< current commands from another node id
  std::uint32_t fallbacks = 0;   ///< entries into the safe state
  std::int64_t last_fallback_latency_ns = -1;  ///< last valid command → safe state, ns
  /// Time between the drive tick that fell back and the tick before it, ns:
  /// the fallback is on time when latency ≤ timeout + this gap.
  std::int64_t last_fallback_tick_gap_ns = -1;
};

class DriveLogic {
 public:
  explicit DriveLogic(const DriveConfig& c = {}) noexcept : c_(c) {}

  /// Offers one received frame; returns true when it was a valid command.
  bool on_frame(const hal::CanFrame& f, std::int64_t now_ns) noexcept;

  /// Decides the output for the period starting at `now_ns`.
  /// `fault` is the drive's own fault (over-temperature, injected, …).
  DriveOutput tick(std::int64_t now_ns, bool fault, float measured_current_a) noexcept;

  /// Status frame content for the period just decided.
  protocol::DriveStatus status(float measured_current_a, std::uint8_t counter) const noexcept;

  const DriveCounters& counters() const noexcept { return n_; }
  const DriveOutput& output() const noexcept { return out_; }
  bool has_command() const noexcept { return have_command_; }
  const protocol::CurrentCommand& last_command() const noexcept { return cmd_; }

 private:
  DriveConfig c_;
  protocol::CounterCheck counter_{};
  protocol::CurrentCommand cmd_{};
  bool have_command_ = false;
  std::int64_t last_valid_ns_ = 0;
  std::int64_t last_tick_ns_ = -1;
  bool rejected_since_status_ = false;
  DriveOutput out_{};
  DriveCounters n_{};
};

}  // namespace mrd::peers
