// The writer thread behind the board's state store: every record handed over
// reaches the medium, the newest one last; a failing medium is reported by
// the next save; flush() waits for the writes; the listener sees each write.
#include "firmware/platform/linux/background_state_store.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace mrd::posix {
namespace {

/// A medium that keeps every record written, can be slowed and made to fail.
class SlowMedium final : public hal::StateStore {
 public:
  hal::StoreStatus load(hal::StateRecord& out) noexcept override {
    std::lock_guard lock(m_);
    if (written_.empty()) return hal::StoreStatus::kMissing;
    out = written_.back();
    return hal::StoreStatus::kOk;
  }
  hal::StoreStatus save(const hal::StateRecord& r) noexcept override {
    {
      std::unique_lock lock(m_);
      writing_ = true;
      cv_.notify_all();
      cv_.wait(lock, [this] { return !gate_closed_; });
    }
    std::this_thread::sleep_for(delay_);
    if (fail_.load()) return hal::StoreStatus::kIoError;
    std::lock_guard lock(m_);
    written_.push_back(r);
    return hal::StoreStatus::kOk;
  }
  void wait_until_writing() {
    std::unique_lock lock(m_);
    cv_.wait(lock, [this] { return writing_; });
  }
  void open_gate() {
    std::lock_guard lock(m_);
    gate_closed_ = false;
    cv_.notify_all();
  }
  std::vector<hal::StateRecord> written() {
    std::lock_guard lock(m_);
    return written_;
  }
  std::chrono::milliseconds delay_{0};
  std::atomic<bool> fail_{false};
  bool gate_closed_ = false;  ///< set before the first save

 private:
  std::mutex m_;
  std::condition_variable cv_;
  bool writing_ = false;
  std::vector<hal::StateRecord> written_;
};

hal::StateRecord record(std::uint8_t tag) {
  hal::StateRecord r{};
  r[0] = tag;
  return r;
}

TEST(BackgroundStateStore, WritesEveryRecordWhenTheMediumKeepsUp) {
  SlowMedium medium;
  BackgroundStateStore store(medium);
  for (std::uint8_t k = 1; k <= 5; ++k) {
    EXPECT_EQ(store.save(record(k)), hal::StoreStatus::kOk);
    store.flush();
  }
  const auto w = medium.written();
  ASSERT_EQ(w.size(), 5u);
  for (std::uint8_t k = 1; k <= 5; ++k) EXPECT_EQ(w[k - 1][0], k);
  EXPECT_EQ(store.writes(), 5u);
}

TEST(BackgroundStateStore, SaveNeverWaitsForTheMediumAndTheNewestRecordIsWrittenLast) {
  SlowMedium medium;
  medium.gate_closed_ = true;  // the medium's first write blocks until the test opens the gate
  BackgroundStateStore store(medium);
  store.save(record(1));
  medium.wait_until_writing();
  // The writer is stuck inside the medium: if save() waited for it, the test would hang here.
  for (std::uint8_t k = 2; k <= 10; ++k) EXPECT_EQ(store.save(record(k)), hal::StoreStatus::kOk);
  medium.open_gate();
  store.flush();
  const auto w = medium.written();
  ASSERT_EQ(w.size(), 2u) << "the record being written, then only the newest of those that waited";
  EXPECT_EQ(w[0][0], 1);
  EXPECT_EQ(w[1][0], 10);
  EXPECT_EQ(store.superseded(), 8u);
}

TEST(BackgroundStateStore, AFailingMediumIsReportedByTheNextSave) {
  SlowMedium medium;
  medium.fail_ = true;
  std::vector<hal::StoreStatus> heard;
  std::mutex m;
  BackgroundStateStore store(medium, [&](hal::StoreStatus s, const hal::StateRecord&) {
    std::lock_guard lock(m);
    heard.push_back(s);
  });
  EXPECT_EQ(store.save(record(1)), hal::StoreStatus::kOk) << "nothing has failed yet";
  store.flush();
  EXPECT_EQ(store.save(record(2)), hal::StoreStatus::kIoError);
  store.flush();
  EXPECT_EQ(store.failed_writes(), 2u);
  medium.fail_ = false;
  EXPECT_EQ(store.save(record(3)), hal::StoreStatus::kIoError) << "still the last write's outcome";
  store.flush();
  EXPECT_EQ(store.save(record(4)), hal::StoreStatus::kOk);
  store.flush();
  std::lock_guard lock(m);
  ASSERT_EQ(heard.size(), 4u);
  EXPECT_EQ(heard[0], hal::StoreStatus::kIoError);
  EXPECT_EQ(heard[3], hal::StoreStatus::kOk);
}

TEST(BackgroundStateStore, TheDestructorWritesWhatIsStillWaiting) {
  SlowMedium medium;
  medium.delay_ = std::chrono::milliseconds(20);
  {
    BackgroundStateStore store(medium);
    store.save(record(1));
    store.save(record(2));
  }
  const auto w = medium.written();
  ASSERT_FALSE(w.empty());
  EXPECT_EQ(w.back()[0], 2);
}

TEST(BackgroundStateStore, LoadReadsTheMedium) {
  SlowMedium medium;
  BackgroundStateStore store(medium);
  hal::StateRecord r{};
  EXPECT_EQ(store.load(r), hal::StoreStatus::kMissing);
  store.save(record(7));
  store.flush();
  EXPECT_EQ(store.load(r), hal::StoreStatus::kOk);
  EXPECT_EQ(r[0], 7);
}

}  // namespace
}  // namespace mrd::posix
