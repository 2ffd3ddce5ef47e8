#pragma once
/// Time as the firmware loop sees it: a monotonic clock in integer
/// nanoseconds and an absolute sleep, and the wall clock (RTC) that measures
/// time across power cycles. Implementations: CLOCK_MONOTONIC with
/// clock_nanosleep(TIMER_ABSTIME) (firmware/platform/linux/posix_clock), and
/// manual clocks for tests and lockstep simulation
/// (firmware/platform/sim/manual_clock).

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

/// Calendar time from the board's real-time clock. It may be unset at boot
/// and may jump; the idle-time estimator checks it (it only measures the
/// time the board was off and watches for backward jumps).
class WallClock {
 public:
  virtual ~WallClock() = default;
  /// Seconds since the Unix epoch into `unix_s`; false when the clock has
  /// no valid time (then `unix_s` is left unchanged).
  virtual bool now_s(double& unix_s) const noexcept = 0;
};

}  // namespace mrd::hal
