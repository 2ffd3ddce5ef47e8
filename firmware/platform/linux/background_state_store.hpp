#pragma once
/// hal::StateStore that writes on a thread of its own, so that a save never
/// holds up the control loop: save() copies the 64-byte record into a
/// mailbox and returns; the writer thread saves the newest record waiting
/// through the medium (e.g. FileStateStore, which fsyncs). A record that
/// arrives while another is being written replaces any older one still
/// waiting: the medium always ends with the newest state.
///
/// save() reports the outcome of the last write that finished (kOk until
/// one fails), so a failing medium shows in the estimator's kIdleSaveFailed
/// one save late. load() reads the medium directly (boot, before the loop).
/// flush() waits until everything handed over is written; the destructor
/// flushes and joins. The writer runs at the caller's default scheduling
/// (SCHED_OTHER), below the SCHED_FIFO control thread; the control thread
/// holds the mailbox's lock only for a copy of 64 bytes.

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>

#include "mrd/hal/state_store.hpp"

namespace mrd::posix {

class BackgroundStateStore final : public hal::StateStore {
 public:
  /// Called on the writer thread after each write, with its status and the
  /// record written (e.g. to log it).
  using WriteListener = std::function<void(hal::StoreStatus, const hal::StateRecord&)>;

  explicit BackgroundStateStore(hal::StateStore& medium, WriteListener listener = {});
  ~BackgroundStateStore();
  BackgroundStateStore(const BackgroundStateStore&) = delete;
  BackgroundStateStore& operator=(const BackgroundStateStore&) = delete;

  hal::StoreStatus load(hal::StateRecord& out) noexcept override;
  hal::StoreStatus save(const hal::StateRecord& record) noexcept override;

  /// Blocks until every record handed to save() is written.
  void flush();

  /// Writes finished, and of those failed.
  std::uint64_t writes() const;
  std::uint64_t failed_writes() const;
  /// Records replaced in the mailbox before they were written.
  std::uint64_t superseded() const;

 private:
  void run();

  hal::StateStore& medium_;
  WriteListener listener_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable idle_;
  hal::StateRecord pending_{};
  bool has_pending_ = false;
  bool writing_ = false;
  bool stop_ = false;
  hal::StoreStatus last_ = hal::StoreStatus::kOk;
  std::uint64_t writes_ = 0, failed_ = 0, superseded_ = 0;
  std::thread thread_;  ///< last: starts after every member above is built
};

}  // namespace mrd::posix
