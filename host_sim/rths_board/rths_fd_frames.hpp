#pragma once
/// The RTHS loop's two per-tick messages as CAN FD frames (`--can-fd`), for
/// 4096 Hz on one bus: the same identifiers as the classic RthsCommand and
/// RthsMeasurement (msg id 0x10 / 0x11 << 4 | sender), told apart from them
/// by the FD format and the length, 12 bytes, sent with the bit-rate switch.
/// The beacon and the run status stay classic frames.
///
/// | bytes | RthsCommand (FD) | RthsMeasurement (FD) |
/// |---|---|---|
/// | 0–3 | `command` int32 × 1e-9 m (±2.147 m) | `displacement` int32 × 1e-9 m |
/// | 4–7 | `target` int32 × 1e-9 m | `force` int32 × 1e-3 N (±2147.48 kN) |
/// | 8–9 | counter uint16: the tick mod 65536 | counter uint16: the tick the sample is for |
/// | 10 | 0 (reserved) | 0 (reserved) |
/// | 11 | CRC-8 (the protocol's J1850) over id low, id high, bytes 0–10 | same |
///
/// Little-endian, int32 two's complement (−2³¹ never sent). Layout, a
/// worked example and the bus load: common/protocol/CAN_PROTOCOL.md,
/// "CAN FD frames of the RTHS link".

#include <cstdint>

#include "mrd/hal/can_fd_bus.hpp"
#include "mrd/protocol/codec.hpp"

namespace mrd::rths_board {

inline constexpr std::uint8_t kRthsFdLength = 12;

struct RthsFdCommand {
  double command_m = 0.0;
  double target_m = 0.0;
  std::uint16_t counter = 0;
};

struct RthsFdMeasurement {
  double displacement_m = 0.0;
  double force_n = 0.0;
  std::uint16_t counter = 0;
};

/// CRC-8 of an RTHS FD frame as byte 11 carries it.
std::uint8_t rths_fd_crc(std::uint32_t id, const hal::CanFdFrame& f) noexcept;

/// Fill `out` (FD, BRS, 12 bytes); false when a value is outside its signal's
/// range, not finite, or the sender is not 1..15.
bool encode_fd(const RthsFdCommand& m, std::uint8_t sender, hal::CanFdFrame& out) noexcept;
bool encode_fd(const RthsFdMeasurement& m, std::uint8_t sender, hal::CanFdFrame& out) noexcept;

/// Accept only an FD frame with the exact id from `sender`, 12 bytes, a
/// matching CRC and a zero reserved byte; `out` untouched otherwise.
protocol::DecodeError decode_fd(const hal::CanFdFrame& f, std::uint8_t sender, RthsFdCommand& out) noexcept;
protocol::DecodeError decode_fd(const hal::CanFdFrame& f, std::uint8_t sender, RthsFdMeasurement& out) noexcept;

}  // namespace mrd::rths_board
