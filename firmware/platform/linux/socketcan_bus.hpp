#pragma once
/// hal::CanBus on a Linux SocketCAN interface (can0, vcan0, …): a raw
/// socket, non-blocking, with CAN_RAW_FILTER set to the ids the node listens
/// to and CAN_RAW_ERR_FILTER subscribed to controller and bus-off errors,
/// which update state(). The only file that includes <linux/can.h>.

#include <cstdint>
#include <span>
#include <string>

#include "mrd/hal/can_bus.hpp"

namespace mrd::posix {

/// Fault-confinement state after an error frame with class bits `err_class`
/// (can_id & CAN_ERR_MASK) and controller detail `crtl` (data[1]), starting
/// from `now`. Pure, so the mapping is tested without a CAN interface.
hal::BusState bus_state_after_error(std::uint32_t err_class, std::uint8_t crtl, hal::BusState now) noexcept;

class SocketCanBus final : public hal::CanBus {
 public:
  /// Opens `interface` and applies `filters` (exact 11-bit ids when mask is
  /// 0x7FF). Throws std::runtime_error naming the interface and the failing
  /// call (no such interface, no CAN support in the kernel, …).
  SocketCanBus(const std::string& interface, std::span<const hal::CanFilter> filters);
  ~SocketCanBus() override;
  SocketCanBus(const SocketCanBus&) = delete;
  SocketCanBus& operator=(const SocketCanBus&) = delete;

  hal::CanResult send(const hal::CanFrame& frame) noexcept override;
  hal::CanResult receive(hal::CanFrame& frame) noexcept override;
  hal::BusState state() const noexcept override { return state_; }
  bool wait_readable(std::chrono::nanoseconds timeout) noexcept override;

  /// Error frames seen since opening.
  std::uint64_t error_frames() const noexcept { return error_frames_; }
  /// Frames the kernel dropped for this socket (SO_RXQ_OVFL is not used; read errors counted here).
  std::uint64_t read_errors() const noexcept { return read_errors_; }
  int fd() const noexcept { return fd_; }

 private:
  int fd_ = -1;
  hal::BusState state_ = hal::BusState::kActive;
  std::uint64_t error_frames_ = 0;
  std::uint64_t read_errors_ = 0;
};

}  // namespace mrd::posix
