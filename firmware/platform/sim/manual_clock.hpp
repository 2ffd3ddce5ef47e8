#pragma once
/// A clock that moves only when told: sleeping until a deadline jumps there.
/// For tests and lockstep runs, where time is the plant's tick count.

#include <cstdint>

#include "mrd/hal/clock.hpp"

namespace mrd::sim {

class ManualClock final : public hal::Clock {
 public:
  std::int64_t now_ns() const noexcept override { return now_ns_; }
  void sleep_until_ns(std::int64_t deadline_ns) noexcept override {
    if (deadline_ns > now_ns_) now_ns_ = deadline_ns;
  }
  void advance_ns(std::int64_t dt_ns) noexcept { now_ns_ += dt_ns; }

 private:
  std::int64_t now_ns_ = 0;
};

}  // namespace mrd::sim
