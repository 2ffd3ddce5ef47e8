#pragma once
/// hal::StateStore in RAM, for tests and the simulator. A stored record can
/// be damaged on purpose (`bytes()`, `truncate()`) and the next save made to
/// fail (`fail_next_save()`).

#include <cstddef>
#include <cstdint>

#include "mrd/hal/state_store.hpp"

namespace mrd::sim {

class MemoryStateStore final : public hal::StateStore {
 public:
  hal::StoreStatus load(hal::StateRecord& out) noexcept override {
    ++loads_;
    if (!has_record_) return hal::StoreStatus::kMissing;
    if (size_ != hal::kStateRecordSize) return hal::StoreStatus::kWrongSize;
    out = record_;
    return hal::StoreStatus::kOk;
  }
  hal::StoreStatus save(const hal::StateRecord& record) noexcept override {
    if (fail_next_save_) {
      fail_next_save_ = false;
      return hal::StoreStatus::kIoError;
    }
    record_ = record;
    size_ = hal::kStateRecordSize;
    has_record_ = true;
    ++saves_;
    return hal::StoreStatus::kOk;
  }

  bool has_record() const noexcept { return has_record_; }
  void clear() noexcept { has_record_ = false; }
  hal::StateRecord& bytes() noexcept { return record_; }
  const hal::StateRecord& bytes() const noexcept { return record_; }
  /// Pretends only the first `size` bytes survived.
  void truncate(std::size_t size) noexcept { size_ = size < hal::kStateRecordSize ? size : hal::kStateRecordSize; }
  void fail_next_save() noexcept { fail_next_save_ = true; }
  std::uint32_t saves() const noexcept { return saves_; }
  std::uint32_t loads() const noexcept { return loads_; }

 private:
  hal::StateRecord record_{};
  std::size_t size_ = 0;
  bool has_record_ = false;
  bool fail_next_save_ = false;
  std::uint32_t saves_ = 0;
  std::uint32_t loads_ = 0;
};

}  // namespace mrd::sim
