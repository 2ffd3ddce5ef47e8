#pragma once
/// The CAN bus as the firmware and the simulated peers see it: a plain frame
/// struct of our own and a small non-blocking interface. Implementations:
/// SocketCAN (firmware/platform/linux/socketcan_bus), an in-memory bus
/// (firmware/platform/sim/memory_bus) for unit tests and the in-process board.

#include <array>
#include <chrono>
#include <cstdint>

namespace mrd::hal {

/// One classic CAN 2.0 data frame (11-bit or 29-bit id, up to 8 bytes).
struct CanFrame {
  std::uint32_t id = 0;            ///< identifier without flag bits
  bool extended = false;           ///< 29-bit identifier
  bool remote = false;             ///< remote-transmission request (never used by our protocol)
  std::uint8_t dlc = 0;            ///< data length code, 0..8
  std::array<std::uint8_t, 8> data{};
};

/// What a send or receive did.
enum class CanResult : std::uint8_t {
  kOk = 0,          ///< one frame sent or received
  kWouldBlock = 1,  ///< nothing to receive, or the transmit queue is full
  kError = 2,       ///< the interface reported an error (see state())
};

/// Error state of the local CAN controller (ISO 11898-1 fault confinement).
enum class BusState : std::uint8_t {
  kActive = 0,   ///< error counters below 96
  kWarning = 1,  ///< an error counter reached 96
  kPassive = 2,  ///< an error counter reached 128: no active error flags
  kBusOff = 3,   ///< TEC above 255: the controller takes no part in traffic
};

constexpr const char* bus_state_name(BusState s) noexcept {
  switch (s) {
    case BusState::kActive: return "active";
    case BusState::kWarning: return "warning";
    case BusState::kPassive: return "passive";
    case BusState::kBusOff: return "bus-off";
  }
  return "unknown";
}

/// Acceptance filter entry: a frame passes when (frame.id & mask) == (id & mask).
struct CanFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0x7FF;
};

/// Non-blocking CAN interface. send() and receive() never block and never
/// allocate; wait_readable() is the only call that may sleep.
class CanBus {
 public:
  virtual ~CanBus() = default;
  /// Queues `frame` for transmission.
  virtual CanResult send(const CanFrame& frame) noexcept = 0;
  /// Takes the oldest received frame that passed the filters, if any.
  /// Error indications are consumed here too and update state().
  virtual CanResult receive(CanFrame& frame) noexcept = 0;
  /// Present fault-confinement state, from the last error indication seen.
  virtual BusState state() const noexcept = 0;
  /// Sleeps until a frame may be received or `timeout` has passed; returns
  /// true when something is ready. Lockstep simulation waits here.
  virtual bool wait_readable(std::chrono::nanoseconds timeout) noexcept = 0;
};

}  // namespace mrd::hal
