#pragma once
/// hal::Clock on CLOCK_MONOTONIC; sleep_until_ns() is clock_nanosleep with
/// TIMER_ABSTIME, so a fixed-period loop does not drift with its own run time.

#include <string>

#include "mrd/hal/clock.hpp"

namespace mrd::posix {

class PosixClock final : public hal::Clock {
 public:
  std::int64_t now_ns() const noexcept override;
  void sleep_until_ns(std::int64_t deadline_ns) noexcept override;
};

/// hal::WallClock on CLOCK_REALTIME (on a board, set from its RTC at boot:
/// CONFIG_RTC_HCTOSYS). A clock before kEarliestValidUnixS counts as unset:
/// a board whose RTC lost its battery boots at the epoch (1970), and a time
/// off measured from there would be decades.
class PosixWallClock final : public hal::WallClock {
 public:
  /// 2020-01-01T00:00:00Z.
  static constexpr double kEarliestValidUnixS = 1577836800.0;
  bool now_s(double& unix_s) const noexcept override;
};

/// Linux real-time practice for the control thread, each step optional.
struct RealtimeRequest {
  int sched_fifo_priority = 0;  ///< 1..99: SCHED_FIFO at this priority
  bool lock_memory = false;     ///< mlockall(MCL_CURRENT | MCL_FUTURE)
  int cpu = -1;                 ///< pin to this CPU
};

/// Applies what it can and says, one line per step, what it did or why it
/// could not (e.g. "SCHED_FIFO 80 not permitted (EPERM): run as root or give
/// CAP_SYS_NICE / LimitRTPRIO"). Never fails: the loop runs without it.
std::string apply_realtime(const RealtimeRequest& r);

}  // namespace mrd::posix
