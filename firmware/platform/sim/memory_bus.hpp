#pragma once
/// An in-memory CAN bus: several endpoints on one wire, each with its own
/// receive queue and acceptance filters, like SocketCAN sockets on vcan
/// without loopback to the sender. For unit tests, the in-process `sim`
/// board and the lockstep host tests. Queues are fixed-size rings allocated
/// at construction; send() and receive() never allocate.
///
/// Faults can be injected per endpoint: a bus state (error frames), frames
/// dropped on transmit, and a hook to edit frames in flight.
///
/// CAN FD: an endpoint with set_fd(true) also sends and receives FD frames
/// (send_fd/receive_fd), like a SocketCAN socket with CAN_RAW_FD_FRAMES; FD
/// frames reach only such endpoints, and classic receive() skips them. The
/// tamper hook sees classic frames only.

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "mrd/hal/can_bus.hpp"
#include "mrd/hal/can_fd_bus.hpp"

namespace mrd::sim {

class MemoryBus;

/// One node's attachment to a MemoryBus.
class MemoryCanEndpoint final : public hal::CanFdBus {
 public:
  hal::CanResult send(const hal::CanFrame& frame) noexcept override;
  hal::CanResult receive(hal::CanFrame& frame) noexcept override;
  hal::CanResult send_fd(const hal::CanFdFrame& frame) noexcept override;
  hal::CanResult receive_fd(hal::CanFdFrame& frame) noexcept override;
  bool fd_enabled() const noexcept override { return fd_; }
  /// Carry FD frames on this endpoint (off by default, as a classic socket).
  void set_fd(bool on) noexcept { fd_ = on; }
  hal::BusState state() const noexcept override { return state_; }
  /// Returns at once: true when a frame is queued (there is nothing to wait for in memory).
  bool wait_readable(std::chrono::nanoseconds) noexcept override { return count_ > 0; }

  /// Only frames passing one of `filters` are queued; none set = all pass.
  void set_filters(std::vector<hal::CanFilter> filters) { filters_ = std::move(filters); }
  /// Injected fault-confinement state; in bus-off, send() fails and nothing is received.
  void set_state(hal::BusState s) noexcept { state_ = s; }
  std::size_t queued() const noexcept { return count_; }
  /// Frames lost because this endpoint's queue was full.
  std::size_t overflows() const noexcept { return overflows_; }

 private:
  friend class MemoryBus;
  MemoryCanEndpoint(MemoryBus& bus, std::size_t capacity) : bus_(&bus), ring_(capacity) {}
  bool accepts(const hal::CanFdFrame& f) const noexcept;
  void deliver(const hal::CanFdFrame& f) noexcept;

  MemoryBus* bus_;
  std::vector<hal::CanFdFrame> ring_;
  bool fd_ = false;
  std::size_t head_ = 0, count_ = 0, overflows_ = 0;
  std::vector<hal::CanFilter> filters_;
  hal::BusState state_ = hal::BusState::kActive;
};

class MemoryBus {
 public:
  /// Called for every frame sent; return false to drop it (lost on the
  /// wire), or edit it in place (corrupt it).
  using Tamper = std::function<bool(hal::CanFrame&)>;

  /// A new endpoint with a receive queue of `capacity` frames. The bus owns it.
  MemoryCanEndpoint& attach(std::size_t capacity = 256);
  void set_tamper(Tamper t) { tamper_ = std::move(t); }
  /// Frames sent on the bus since construction (before tampering).
  std::size_t frames_sent() const noexcept { return sent_; }

 private:
  friend class MemoryCanEndpoint;
  void broadcast(const MemoryCanEndpoint& from, const hal::CanFrame& f) noexcept;
  void broadcast_fd(const MemoryCanEndpoint& from, const hal::CanFdFrame& f) noexcept;
  std::vector<std::unique_ptr<MemoryCanEndpoint>> endpoints_;
  Tamper tamper_;
  std::size_t sent_ = 0;
};

}  // namespace mrd::sim
