#include "firmware/platform/linux/background_state_store.hpp"

#include <utility>

namespace mrd::posix {

BackgroundStateStore::BackgroundStateStore(hal::StateStore& medium, WriteListener listener)
    : medium_(medium), listener_(std::move(listener)), thread_([this] { run(); }) {}

BackgroundStateStore::~BackgroundStateStore() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

hal::StoreStatus BackgroundStateStore::load(hal::StateRecord& out) noexcept { return medium_.load(out); }

hal::StoreStatus BackgroundStateStore::save(const hal::StateRecord& record) noexcept {
  hal::StoreStatus last;
  {
    std::lock_guard lock(mutex_);
    if (has_pending_) ++superseded_;
    pending_ = record;
    has_pending_ = true;
    last = last_;
  }
  wake_.notify_one();
  return last;
}

void BackgroundStateStore::flush() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return !has_pending_ && !writing_; });
}

std::uint64_t BackgroundStateStore::writes() const {
  std::lock_guard lock(mutex_);
  return writes_;
}

std::uint64_t BackgroundStateStore::failed_writes() const {
  std::lock_guard lock(mutex_);
  return failed_;
}

std::uint64_t BackgroundStateStore::superseded() const {
  std::lock_guard lock(mutex_);
  return superseded_;
}

void BackgroundStateStore::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return has_pending_ || stop_; });
    if (!has_pending_) break;  // stopping, and everything is written
    const hal::StateRecord record = pending_;
    has_pending_ = false;
    writing_ = true;
    lock.unlock();
    const hal::StoreStatus status = medium_.save(record);
    if (listener_) listener_(status, record);
    lock.lock();
    writing_ = false;
    last_ = status;
    ++writes_;
    if (status != hal::StoreStatus::kOk) ++failed_;
    idle_.notify_all();
  }
  idle_.notify_all();
}

}  // namespace mrd::posix
