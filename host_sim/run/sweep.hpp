#pragma once
/// Idle-time sweeps (thesis §6.5, Fig. 6.12–6.20): every motion × control
/// mode × idle time, run in parallel on all cores.

#include <cstddef>
#include <functional>
#include <vector>

#include "mrd/control/io.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/motions.hpp"

namespace mrd::run {

struct SweepSpec {
  std::vector<StudyMotion> motions;
  std::vector<control::ControlMode> modes;
  std::vector<double> idle_years;  ///< the idle-time axis of the reports, years
  plant::PlantSpec base{};         ///< step, building, damper, settling (idle_time_s is set per run)
  unsigned threads = 0;            ///< 0: all hardware threads
};

struct SweepRow {
  std::size_t motion_index = 0;
  control::ControlMode mode = control::ControlMode::kPassiveOff;
  double idle_years = 0.0;  ///< the run's idle time, years
  plant::PlantSummary summary;
};

/// 0 to `to_years` every `step_years`, inclusive of the end (within rounding).
std::vector<double> idle_grid(double from_years, double to_years, double step_years);

/// Runs every combination; rows are ordered motion-major, then mode, then
/// idle time. `progress(done, total)` is called from worker threads (under a
/// lock) after each run. Throws what a run throws (e.g. a mode that cannot
/// be built) before starting any work.
std::vector<SweepRow> run_sweep(const SweepSpec& spec,
                                const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace mrd::run
