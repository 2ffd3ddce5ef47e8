#pragma once
/// What the board runtime reports: a summary line (periodically and at the
/// end of a run), one line per change of the drive-enable line, and why a
/// lockstep run ended. Lines are formatted into a fixed buffer (no heap) and
/// handed to a RuntimeLog, which the program provides (stdout on a Linux
/// board; none in the in-process board).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "firmware/app/control_task.hpp"
#include "firmware/app/mixing_task.hpp"
#include "mrd/units.hpp"

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
inline constexpr std::size_t kLogLineSize = 1024;

/// "<name>: summary ticks=… overruns=… … bus=…": the task's counters, the
/// loop's timing and the drive-enable changes, as key=value pairs.
void format_summary(char (&out)[kLogLineSize], const char* name, const ControlTaskStatus& status,
                    const LoopTiming& timing, std::uint64_t enable_changes) noexcept;

/// Appends the mixing task's part of the summary to `out`:
/// " idle_years=… sq=… pr=… capacity=… scheduler=… cycles=… saves=… save_failures=… idle_flags=0x…"
/// (equivalent idle time τ in Julian years, Eq. 5.5's SQ, PR of Eq. 5.9, the
/// capacity relative to fully mixed, confirmed mixing cycles since
/// commissioning, the estimator's IdleFlag bits).
template <class Policy>
void append_mixing_summary(char (&out)[kLogLineSize], const BasicMixingTask<Policy>& task, std::uint32_t saves,
                           std::uint32_t save_failures) noexcept {
  const auto& e = task.estimator().estimate();
  const std::size_t used = std::strlen(out);
  std::snprintf(out + used, kLogLineSize - used,
                " idle_years=%.6f sq=%.4f pr=%.4f capacity=%.4f scheduler=%s cycles=%u saves=%u save_failures=%u "
                "idle_flags=0x%x",
                static_cast<double>(e.equivalent_idle_s) / units::kSecondsPerYear, static_cast<double>(e.sq),
                static_cast<double>(e.participant_ratio), static_cast<double>(e.capacity_fraction),
                fw::scheduler_state_name(task.output().state), e.mixing_cycles, saves, save_failures,
                static_cast<unsigned>(e.flags));
}

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
