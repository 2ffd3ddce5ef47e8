#pragma once
/// hal::CanBus on a Linux SocketCAN interface (can0, vcan0, …): a raw
/// socket, non-blocking, with CAN_RAW_FILTER set to the ids the node listens
/// to and CAN_RAW_ERR_FILTER subscribed to controller and bus-off errors,
/// which update state(). The only file that includes <linux/can.h>.
///
/// CAN FD (`can_fd` true): CAN_RAW_FD_FRAMES is set and the interface must
/// have the FD MTU (CANFD_MTU, 72: a CAN FD controller, or vcan, 72 by
/// default); a classic-only interface (MTU 16) is refused with an error
/// saying so. FD frames go out with CANFD_BRS when the frame asks for
/// it. The classic send()/receive() work as without FD; receive() skips FD
/// frames (counted in fd_frames_skipped()).

#include <cstdint>
#include <span>
#include <string>

#include "mrd/hal/can_bus.hpp"
#include "mrd/hal/can_fd_bus.hpp"

namespace mrd::posix {

/// Fault-confinement state after an error frame with class bits `err_class`
/// (can_id & CAN_ERR_MASK) and controller detail `crtl` (data[1]), starting
/// from `now`. Pure, so the mapping is tested without a CAN interface.
hal::BusState bus_state_after_error(std::uint32_t err_class, std::uint8_t crtl, hal::BusState now) noexcept;

class SocketCanBus final : public hal::CanFdBus {
 public:
  /// Opens `interface` and applies `filters` (exact 11-bit ids when mask is
  /// 0x7FF). Throws std::runtime_error naming the interface and the failing
  /// call (no such interface, no CAN support in the kernel, …).
  SocketCanBus(const std::string& interface, std::span<const hal::CanFilter> filters);
  /// As above; with `can_fd` also FD frames (throws when the interface's MTU is not CANFD_MTU).
  SocketCanBus(const std::string& interface, std::span<const hal::CanFilter> filters, bool can_fd);
  ~SocketCanBus() override;
  SocketCanBus(const SocketCanBus&) = delete;
  SocketCanBus& operator=(const SocketCanBus&) = delete;

  hal::CanResult send(const hal::CanFrame& frame) noexcept override;
  hal::CanResult receive(hal::CanFrame& frame) noexcept override;
  hal::CanResult send_fd(const hal::CanFdFrame& frame) noexcept override;
  hal::CanResult receive_fd(hal::CanFdFrame& frame) noexcept override;
  bool fd_enabled() const noexcept override { return fd_; }
  hal::BusState state() const noexcept override { return state_; }
  bool wait_readable(std::chrono::nanoseconds timeout) noexcept override;

  /// Error frames seen since opening.
  std::uint64_t error_frames() const noexcept { return error_frames_; }
  /// Frames the kernel dropped for this socket (SO_RXQ_OVFL is not used; read errors counted here).
  std::uint64_t read_errors() const noexcept { return read_errors_; }
  /// FD frames that a classic receive() passed over.
  std::uint64_t fd_frames_skipped() const noexcept { return fd_skipped_; }
  int fd() const noexcept { return sock_; }

 private:
  /// The next data frame of either kind into `out`; error frames handled here.
  hal::CanResult read_frame(hal::CanFdFrame& out) noexcept;

  int sock_ = -1;
  bool fd_ = false;
  std::uint64_t fd_skipped_ = 0;
  hal::BusState state_ = hal::BusState::kActive;
  std::uint64_t error_frames_ = 0;
  std::uint64_t read_errors_ = 0;
};

}  // namespace mrd::posix
