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
  if (count_ == 0) return hal::CanResult::kWouldBlock;
  frame = ring_[head_];
  head_ = (head_ + 1) % ring_.size();
  --count_;
  return hal::CanResult::kOk;
}

bool MemoryCanEndpoint::accepts(const hal::CanFrame& f) const noexcept {
  if (state_ == hal::BusState::kBusOff) return false;
  if (filters_.empty()) return true;
  for (const auto& flt : filters_) {
    if ((f.id & flt.mask) == (flt.id & flt.mask)) return true;
  }
  return false;
}

void MemoryCanEndpoint::deliver(const hal::CanFrame& f) noexcept {
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
  for (auto& e : endpoints_) {
    if (e.get() != &from) e->deliver(g);
  }
}

}  // namespace mrd::sim
