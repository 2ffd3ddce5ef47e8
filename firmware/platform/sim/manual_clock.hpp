#pragma once
/// Clocks that move only when told, for tests and lockstep runs, where time
/// is the plant's tick count. Sleeping on ManualClock until a deadline jumps
/// there.

#include <cstdint>

#include "mrd/hal/clock.hpp"

namespace mrd::sim {

/// Monotonic time that advances only by advance_ns() and sleep_until_ns().
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

/// A wall clock with no valid time until set().
class ManualWallClock final : public hal::WallClock {
 public:
  bool now_s(double& unix_s) const noexcept override {
    if (valid_) unix_s = now_s_;
    return valid_;
  }
  void set(double unix_s, bool valid = true) noexcept {
    now_s_ = unix_s;
    valid_ = valid;
  }
  void advance_s(double dt_s) noexcept { now_s_ += dt_s; }

 private:
  double now_s_ = 0.0;
  bool valid_ = false;
};

}  // namespace mrd::sim
