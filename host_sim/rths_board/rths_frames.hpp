#pragma once
/// The CAN frames between the RTHS runtime on the board (`mrd-rths`) and the
/// laboratory (`mrd-rths-lab`), in the framing of the mrd protocol
/// (common/protocol/CAN_PROTOCOL.md): 11-bit id = msg_id << 4 | sender node,
/// DLC 8, little-endian signals in bytes 0..5, byte 6 a rolling counter, byte 7
/// the protocol's CRC-8 over the identifier and bytes 0..6.
///
/// | msg id | name | sender → receiver | when |
/// |---|---|---|---|
/// | 0x10 | RthsCommand | runtime → lab | every loop tick |
/// | 0x11 | RthsMeasurement | lab → runtime | after each command (and with the start beacon) |
/// | 0x12 | RthsLabStatus | lab → runtime | 100 ms beacon before the run; every tick once stopped |
/// | 0x13 | RthsRunStatus | runtime → lab | at the end of the run (three times) |
///
/// Signals (value = raw × factor, int24 two's complement):
/// - RthsCommand: bytes 0–2 `command` 1e-8 m (±83.886 mm), bytes 3–5
///   `target` 1e-8 m; counter = the tick k mod 256.
/// - RthsMeasurement: bytes 0–2 `displacement` 1e-8 m, bytes 3–5 `force`
///   0.01 N (±83.886 kN); counter = the tick the sample is for (k + 1 after
///   command k) mod 256.
/// - RthsLabStatus: byte 0 `state` (0 waiting, 1 running, 2 stopped), byte 1
///   `stop` (0 none, 1 force limit, 2 tracking limit, 3 not finite, 4 command
///   timeout), bytes 2–3 `rate` uint16 Hz (the lab's step rate), bytes 4–5 0.
/// - RthsRunStatus: byte 0 `state` (1 finished, 2 ended by the lab's stop, 3
///   aborted), bytes 1–4 `ticks` uint32, byte 5 0.
///
/// The ids are protocol::MsgId::kRthsCommand … kRthsRunStatus; their rows,
/// signals, timeouts and example frames are in CAN_PROTOCOL.md and mrd.dbc.
/// The converters'
/// own steps (displacement 0.29 µm, force 0.068 N at ±3.8 V, 18 bit) are well
/// above the frames' 10 nm and 0.01 N.
///
/// Bus load: a tick is two frames of at most 135 bits; at 1 kHz that is 27 %
/// of a 1 Mbit/s bus, at 4096 Hz 111 %: 4096 Hz needs CAN FD (`--can-fd`,
/// rths_fd_frames.hpp: 53 % at 1 Mbit/s arbitration, 5 Mbit/s data) or a
/// faster link (vcan has no bit rate, so the emulated board runs either).

#include <cstdint>

#include "mrd/hal/can_bus.hpp"
#include "mrd/protocol/codec.hpp"

namespace mrd::rths_board {

/// Default node of the laboratory (the board file's controller node sends the commands).
inline constexpr std::uint8_t kDefaultLabNode = 5;

struct RthsCommand {
  double command_m = 0.0;
  double target_m = 0.0;
  std::uint8_t counter = 0;
};

struct RthsMeasurement {
  double displacement_m = 0.0;
  double force_n = 0.0;
  std::uint8_t counter = 0;
};

enum class LabState : std::uint8_t { kWaiting = 0, kRunning = 1, kStopped = 2 };
enum class LabStopReason : std::uint8_t {
  kNone = 0,
  kForceLimit = 1,
  kTrackingLimit = 2,
  kNotFinite = 3,
  kCommandTimeout = 4,
};
/// "none", "force_limit", "tracking_limit", "not_finite", "command_timeout".
const char* lab_stop_reason_name(LabStopReason r) noexcept;
const char* lab_state_name(LabState s) noexcept;

struct RthsLabStatus {
  LabState state = LabState::kWaiting;
  LabStopReason stop = LabStopReason::kNone;
  std::uint16_t rate_hz = 0;
  std::uint8_t counter = 0;
};

enum class RunState : std::uint8_t { kFinished = 1, kLabStopped = 2, kAborted = 3 };

struct RthsRunStatus {
  RunState state = RunState::kFinished;
  std::uint32_t ticks = 0;
  std::uint8_t counter = 0;
};

/// Fill `out`; false when a value is outside its signal's range, not finite,
/// or the sender is not 1..15.
bool encode(const RthsCommand& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const RthsMeasurement& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const RthsLabStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const RthsRunStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept;

/// Accept `f` only with the exact id from `sender`, DLC 8, a matching CRC,
/// defined enumerations and zero reserved bytes; `out` untouched otherwise.
protocol::DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, RthsCommand& out) noexcept;
protocol::DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, RthsMeasurement& out) noexcept;
protocol::DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, RthsLabStatus& out) noexcept;
protocol::DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, RthsRunStatus& out) noexcept;

}  // namespace mrd::rths_board
