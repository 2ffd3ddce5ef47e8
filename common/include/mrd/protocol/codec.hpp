#pragma once
/// The only byte packing of the mrd CAN protocol (common/protocol/CAN_PROTOCOL.md).
/// Used by the firmware and by every simulated peer, so each simulation
/// exercises the real frames.
///
/// Every frame: 8 bytes, little-endian signals in bytes 0..5, byte 6 a rolling
/// counter, byte 7 a CRC-8 (SAE J1850: poly 0x1D, init 0xFF, final XOR 0xFF)
/// over the two identifier bytes (low byte first) and bytes 0..6.
///
/// encode() quantizes to the signal's resolution (round half away from zero)
/// and refuses values outside the documented range or not finite. decode()
/// accepts only the exact identifier (message and sender node), length 8, a
/// matching CRC, zero reserved bits and in-range values; otherwise it leaves
/// the output untouched and says why. Counters are checked separately
/// (CounterCheck), because only the receiver knows the stream's history.
/// Nothing here allocates, throws or blocks.

#include <cstdint>
#include <span>

#include "mrd/hal/can_bus.hpp"
#include "mrd/protocol/messages.hpp"

namespace mrd::protocol {

/// Why a frame was not accepted.
enum class DecodeError : std::uint8_t {
  kOk = 0,
  kWrongId,       ///< another message, another sender, extended or remote frame
  kWrongLength,   ///< DLC other than 8
  kBadChecksum,   ///< CRC-8 mismatch
  kBadField,      ///< reserved bits set or an enumeration value undefined
  kOutOfRange,    ///< a signal outside its documented range
};

const char* decode_error_name(DecodeError e) noexcept;

/// CRC-8 SAE J1850 of `bytes` (check value of "123456789": 0x4B).
std::uint8_t crc8_j1850(std::span<const std::uint8_t> bytes) noexcept;

/// CRC of a frame as byte 7 carries it: over id low, id high, bytes 0..6.
std::uint8_t frame_crc(std::uint32_t id, const std::array<std::uint8_t, 8>& data) noexcept;

// Encoders: fill `out` (id from the message and `sender`, DLC 8, counter,
// CRC). Return false, leaving `out` unspecified, when a value is out of range,
// not finite, or `sender` is not 1..15.
bool encode(const CurrentCommand& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const DriveStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const DaqMotion& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const DaqAccel& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const MixingCommand& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const MixingStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const ControllerStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const IdleStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const SimCoilState& m, std::uint8_t sender, hal::CanFrame& out) noexcept;
bool encode(const SimCoilDrive& m, std::uint8_t sender, hal::CanFrame& out) noexcept;

// Decoders: accept `f` only from node `sender` (see the file comment).
DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, CurrentCommand& out) noexcept;
DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, DriveStatus& out) noexcept;
DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, DaqMotion& out) noexcept;
DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, DaqAccel& out) noexcept;
DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, MixingCommand& out) noexcept;
DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, MixingStatus& out) noexcept;
DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, ControllerStatus& out) noexcept;
DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, IdleStatus& out) noexcept;
DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, SimCoilState& out) noexcept;
DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, SimCoilDrive& out) noexcept;

/// Largest counter step taken as "frames were lost" rather than "stale".
inline constexpr std::uint8_t kMaxCounterJump = 8;

/// Verdict on one frame's rolling counter.
enum class CounterVerdict : std::uint8_t {
  kAccepted = 0,  ///< next in sequence, or up to kMaxCounterJump − 1 frames lost
  kSynced,        ///< first frame of the stream (or after desync()): taken as is
  kRepeated,      ///< same counter as the last accepted frame
  kStale,         ///< behind the last accepted frame, or too far ahead: a replay
};

constexpr bool counter_ok(CounterVerdict v) noexcept {
  return v == CounterVerdict::kAccepted || v == CounterVerdict::kSynced;
}

/// Rolling-counter check of one stream (one message from one sender). A frame
/// whose counter is 1..kMaxCounterJump ahead (mod 256) of the last accepted
/// one is accepted; 0 ahead is a repeat; anything else is stale. The receiver
/// calls desync() when the stream's timeout expires, so the sender's next
/// frame starts a new sequence.
class CounterCheck {
 public:
  CounterVerdict check(std::uint8_t counter) noexcept;
  void desync() noexcept { synced_ = false; }
  bool synced() const noexcept { return synced_; }
  std::uint8_t last() const noexcept { return last_; }
  /// Frames skipped inside accepted jumps since construction.
  std::uint32_t lost_frames() const noexcept { return lost_; }

 private:
  bool synced_ = false;
  std::uint8_t last_ = 0;
  std::uint32_t lost_ = 0;
};

}  // namespace mrd::protocol
