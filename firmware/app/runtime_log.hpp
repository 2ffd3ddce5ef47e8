#pragma once
/// What the board runtime reports: a summary line (periodically and at the
/// end of a run), one line per change of the drive-enable line, and why a
/// lockstep run ended. Lines are formatted into a fixed buffer (no heap) and
/// handed to a RuntimeLog, which the program provides (stdout on a Linux
/// board; none in the in-process board).

#include <cstddef>
#include <cstdint>

#include "firmware/app/control_task.hpp"

namespace mrd::app {

/// Where the runtime's lines go.
class RuntimeLog {
 public:
  virtual ~RuntimeLog() = default;
  /// One complete line, without its newline.
  virtual void line(const char* text) noexcept = 0;
};

/// Timing of the fixed-period loop (zero in lockstep).
struct LoopTiming {
  std::uint32_t overruns = 0;      ///< periods missed
  std::int64_t worst_late_ns = 0;  ///< latest end of a tick past its deadline, ns
};

/// Longest line the runtime writes, with its terminating zero.
inline constexpr std::size_t kLogLineSize = 512;

/// "<name>: summary ticks=… overruns=… … bus=…": the task's counters, the
/// loop's timing and the drive-enable changes, as key=value pairs.
void format_summary(char (&out)[kLogLineSize], const char* name, const ControlTaskStatus& status,
                    const LoopTiming& timing, std::uint64_t enable_changes) noexcept;

/// Watches the drive-enable output tick by tick: its first level and every
/// change are worth a line.
class DriveEnableWatch {
 public:
  /// The tick that just ran (0 for the first) commanded `enable`; true when
  /// that is the first tick or a change.
  bool note(std::uint64_t tick, bool enable) noexcept {
    const bool first = tick == 0;
    const bool changed = !first && enable != level_;
    if (changed) ++changes_;
    level_ = enable;
    return first || changed;
  }
  /// Changes after the first tick.
  std::uint64_t changes() const noexcept { return changes_; }

 private:
  bool level_ = false;
  std::uint64_t changes_ = 0;
};

}  // namespace mrd::app
