#pragma once
/// Deadlines of a fixed-period loop on a monotonic clock, with overrun
/// counting. Deadlines stay on the grid start + k·T, so the loop does not
/// drift with its own run time; a tick that ends past its deadline counts
/// every period it missed and the loop skips to the next grid point instead
/// of running the missed ticks back to back.
///
/// <pre>
///   loop:  run tick;  deadline = schedule.after_tick(clock.now());  clock.sleep_until(deadline)
/// </pre>

#include <algorithm>
#include <cstdint>

namespace mrd::app {

class PeriodicSchedule {
 public:
  PeriodicSchedule(std::int64_t period_ns, std::int64_t start_ns) noexcept
      : period_ns_(period_ns), deadline_ns_(start_ns) {}

  /// The tick that started at the previous deadline ended at `now_ns`:
  /// returns the deadline to sleep until.
  std::int64_t after_tick(std::int64_t now_ns) noexcept {
    deadline_ns_ += period_ns_;
    if (now_ns > deadline_ns_) {
      const std::int64_t late = now_ns - deadline_ns_;
      worst_late_ns_ = std::max(worst_late_ns_, late);
      const std::int64_t missed = late / period_ns_ + 1;
      overruns_ += static_cast<std::uint32_t>(missed);
      deadline_ns_ += missed * period_ns_;
    }
    return deadline_ns_;
  }

  std::uint32_t overruns() const noexcept { return overruns_; }
  std::int64_t worst_late_ns() const noexcept { return worst_late_ns_; }
  std::int64_t deadline_ns() const noexcept { return deadline_ns_; }

 private:
  std::int64_t period_ns_;
  std::int64_t deadline_ns_;
  std::uint32_t overruns_ = 0;
  std::int64_t worst_late_ns_ = 0;
};

}  // namespace mrd::app
