#include "memory_bus.hpp"

namespace mrd::sim {

hal::CanResult MemoryCanEndpoint::send(const hal::CanFrame& frame) noexcept {
  if (state_ == hal::BusState::kBusOff) return hal::CanResult::kError;
  bus_->broadcast(*this, frame);
  return hal::CanResult::kOk;
}

hal::CanResult MemoryCanEndpoint::receive(hal::CanFrame& frame) noexcept {
  if (state_ == hal::BusState::kBusOff) {
    head_ = count_ = 0;  // a controller in bus-off takes no part in traffic
    return hal::CanResult::kError;
  }
  while (count_ > 0) {
    const hal::CanFdFrame& f = ring_[head_];
    head_ = (head_ + 1) % ring_.size();
    --count_;
    if (f.fd) continue;  // an FD frame: not for a classic read
    frame = hal::as_classic(f);
    return hal::CanResult::kOk;
  }
  return hal::CanResult::kWouldBlock;
}

hal::CanResult MemoryCanEndpoint::send_fd(const hal::CanFdFrame& frame) noexcept {
  if (!frame.fd) {
    if (frame.len > 8) return hal::CanResult::kError;
    return send(hal::as_classic(frame));
  }
  if (!fd_ || !hal::valid_fd_length(frame.len)) return hal::CanResult::kError;
  if (state_ == hal::BusState::kBusOff) return hal::CanResult::kError;
  bus_->broadcast_fd(*this, frame);
  return hal::CanResult::kOk;
}

hal::CanResult MemoryCanEndpoint::receive_fd(hal::CanFdFrame& frame) noexcept {
  if (state_ == hal::BusState::kBusOff) {
    head_ = count_ = 0;
    return hal::CanResult::kError;
  }
  if (count_ == 0) return hal::CanResult::kWouldBlock;
  frame = ring_[head_];
  head_ = (head_ + 1) % ring_.size();
  --count_;
  return hal::CanResult::kOk;
}

bool MemoryCanEndpoint::accepts(const hal::CanFdFrame& f) const noexcept {
  if (state_ == hal::BusState::kBusOff) return false;
  if (f.fd && !fd_) return false;
  if (filters_.empty()) return true;
  for (const auto& flt : filters_) {
    if ((f.id & flt.mask) == (flt.id & flt.mask)) return true;
  }
  return false;
}

void MemoryCanEndpoint::deliver(const hal::CanFdFrame& f) noexcept {
  if (!accepts(f)) return;
  if (count_ == ring_.size()) {
    ++overflows_;
    return;
  }
  ring_[(head_ + count_) % ring_.size()] = f;
  ++count_;
}

MemoryCanEndpoint& MemoryBus::attach(std::size_t capacity) {
  endpoints_.push_back(std::unique_ptr<MemoryCanEndpoint>(new MemoryCanEndpoint(*this, capacity)));
  return *endpoints_.back();
}

void MemoryBus::broadcast(const MemoryCanEndpoint& from, const hal::CanFrame& f) noexcept {
  ++sent_;
  hal::CanFrame g = f;
  if (tamper_ && !tamper_(g)) return;
  const hal::CanFdFrame h = hal::as_fd_struct(g);
  for (auto& e : endpoints_) {
    if (e.get() != &from) e->deliver(h);
  }
}

void MemoryBus::broadcast_fd(const MemoryCanEndpoint& from, const hal::CanFdFrame& f) noexcept {
  ++sent_;
  for (auto& e : endpoints_) {
    if (e.get() != &from) e->deliver(f);
  }
}

}  // namespace mrd::sim
