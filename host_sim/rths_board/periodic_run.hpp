#pragma once
/// The free-running loop both RTHS runtimes share: a tick every period on
/// absolute deadlines (app::PeriodicSchedule), its timing recorded.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "firmware/app/periodic_schedule.hpp"
#include "host_sim/rths_board/board_loop.hpp"
#include "mrd/hal/clock.hpp"

namespace mrd::rths_board {

/// The step of a runtime's loop, 1/rate_hz, after the checks both runtimes
/// make: a record with samples, a rate in 100..65535 Hz (the status frame's
/// uint16).
inline double checked_loop_step_s(std::size_t record_samples, double rate_hz) {
  if (record_samples == 0) throw std::invalid_argument("RTHS runtime: empty record");
  if (!(rate_hz >= 100.0 && rate_hz <= 65535.0)) throw std::invalid_argument("RTHS runtime: rate outside 100..65535 Hz");
  return 1.0 / rate_hz;
}

/// Ticks on `clock` every `period_ns` while `end` stays kRunning; a set
/// `stop` ends it as kInterrupted. Each period: `before_tick()` (not timed:
/// waiting for the tick's input), then `tick()`, timed into `timing`
/// (longest tick, overruns, worst lateness) and appended to `tick_ns` while
/// it has reserved room (no allocation in the loop).
template <class BeforeTick, class Tick>
void run_ticks_periodic(hal::Clock& clock, std::int64_t period_ns, const std::atomic<bool>& stop, LoopEnd& end,
                        LoopTimingRecord& timing, std::vector<std::int64_t>& tick_ns, BeforeTick&& before_tick,
                        Tick&& tick) noexcept {
  timing.period_ns = period_ns;
  app::PeriodicSchedule schedule(period_ns, clock.now_ns());
  while (end == LoopEnd::kRunning) {
    if (stop.load()) {
      end = LoopEnd::kInterrupted;
      break;
    }
    before_tick();
    const std::int64_t start_ns = clock.now_ns();
    tick();
    const std::int64_t done_ns = clock.now_ns();
    timing.worst_tick_ns = std::max(timing.worst_tick_ns, done_ns - start_ns);
    if (tick_ns.size() < tick_ns.capacity()) tick_ns.push_back(done_ns - start_ns);
    const std::int64_t deadline_ns = schedule.after_tick(done_ns);
    timing.overruns = schedule.overruns();
    timing.worst_late_ns = schedule.worst_late_ns();
    if (end != LoopEnd::kRunning) break;
    clock.sleep_until_ns(deadline_ns);
  }
}

}  // namespace mrd::rths_board
