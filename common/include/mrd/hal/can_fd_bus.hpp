#pragma once
/// CAN FD beside the classic bus (ISO 11898-1:2015 FD frames, up to 64 data
/// bytes, the data phase optionally at a higher bit rate): a frame struct and
/// an extension of hal::CanBus. A bus that carries FD still carries classic
/// frames through send()/receive() exactly as before; receive() skips FD
/// frames, receive_fd() returns both kinds (classic ones with `fd` false).

#include <array>
#include <cstdint>

#include "mrd/hal/can_bus.hpp"

namespace mrd::hal {

/// The lengths an FD frame can carry (the DLC codes 0..15).
constexpr bool valid_fd_length(std::uint8_t len) noexcept {
  return len <= 8 || len == 12 || len == 16 || len == 20 || len == 24 || len == 32 || len == 48 || len == 64;
}

/// One CAN FD data frame, or a classic one when `fd` is false (len 0..8).
struct CanFdFrame {
  std::uint32_t id = 0;       ///< identifier without flag bits
  bool extended = false;      ///< 29-bit identifier
  bool remote = false;        ///< remote request (classic only; never used by our protocol)
  bool fd = true;             ///< an FD frame (FDF); false: a classic data frame
  bool brs = true;            ///< bit-rate switch for the data phase (FD only)
  std::uint8_t len = 0;       ///< data bytes: valid_fd_length (FD), 0..8 (classic)
  std::array<std::uint8_t, 64> data{};
};

/// Classic frame → the FD struct (fd false) and back; the DLC and all 8 data
/// bytes are kept as they are, so the round trip is exact.
inline CanFdFrame as_fd_struct(const CanFrame& f) noexcept {
  CanFdFrame g;
  g.id = f.id;
  g.extended = f.extended;
  g.remote = f.remote;
  g.fd = false;
  g.brs = false;
  g.len = f.dlc;
  for (std::size_t i = 0; i < f.data.size(); ++i) g.data[i] = f.data[i];
  return g;
}
inline CanFrame as_classic(const CanFdFrame& f) noexcept {
  CanFrame g;
  g.id = f.id;
  g.extended = f.extended;
  g.remote = f.remote;
  g.dlc = f.len;
  for (std::size_t i = 0; i < g.data.size(); ++i) g.data[i] = f.data[i];
  return g;
}

/// A CanBus that also carries FD frames. Non-blocking, never allocating.
class CanFdBus : public CanBus {
 public:
  /// Queues an FD frame (or a classic one, fd false). kError for a length
  /// the frame kind cannot carry or when FD is not enabled.
  virtual CanResult send_fd(const CanFdFrame& frame) noexcept = 0;
  /// Takes the oldest received frame of either kind.
  virtual CanResult receive_fd(CanFdFrame& frame) noexcept = 0;
  /// True when FD frames are sent and received (SocketCAN: CAN_RAW_FD_FRAMES on a CANFD_MTU interface).
  virtual bool fd_enabled() const noexcept = 0;
};

}  // namespace mrd::hal
