#pragma once
/// Time as the firmware loop sees it: a monotonic clock in integer
/// nanoseconds and an absolute sleep. Implementations: CLOCK_MONOTONIC with
/// clock_nanosleep(TIMER_ABSTIME) (firmware/platform/linux/clock) and a manual
/// clock for tests and lockstep simulation (firmware/platform/sim/manual_clock).

#include <cstdint>

namespace mrd::hal {

class Clock {
 public:
  virtual ~Clock() = default;
  /// Monotonic time, ns, from an arbitrary origin; never goes backwards.
  virtual std::int64_t now_ns() const noexcept = 0;
  /// Sleeps until now_ns() >= `deadline_ns` (returns at once if it already is).
  virtual void sleep_until_ns(std::int64_t deadline_ns) noexcept = 0;
};

}  // namespace mrd::hal
