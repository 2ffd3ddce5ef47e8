#pragma once
/// What a fragility study will cost, said before it runs (`mrd fragility`
/// prints it and `--estimate` stops there): its runs, the wall time from a
/// short pilot measured on this machine, the disk its outputs and journal
/// take and the memory its records hold. A study whose disk exceeds the free
/// space of its file system, or whose memory exceeds the machine's, is
/// refused before any work.
///
/// Disk (upper bounds, bytes):
/// <pre>
///   runs.csv     header + per run: index, record, control, idle, PGA as written
///                and 5 peaks of at most 15 characters each ("%.9g": 9 digits,
///                a point and e±NNN), 9 commas and a newline
///   journal      64 per run (run_journal.hpp)
///   curves       fragility.csv (a row of at most 15 characters per number) and
///                fragility_curves.csv (41 rows per curve), curves = controls x
///                idle times x limit states
///   plots        kPlotBytesBound per control and limit state
///   summary.json kSummaryBaseBytes + each record's name and source + 200 per curve
/// </pre>
/// Wall time: the closed-loop steps of every run (records' samples at the
/// runs' step) over the steps per second one worker reached in the pilot
/// (per control mode), shared by the workers (ranks x threads, at most the
/// cores and the chunks of runs), plus the stochastic records' generation
/// at the pilot's rate.

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "host_sim/risk/fragility_fit.hpp"
#include "host_sim/risk/fragility_plan.hpp"
#include "host_sim/risk/stochastic_motion.hpp"

namespace mrd::risk {

/// Largest plot of a study, bytes (a gnuplot PNG with six idle times and two
/// bands is about 40 kB).
inline constexpr std::uintmax_t kPlotBytesBound = 100'000;
/// summary.json without its records and curves, bytes.
inline constexpr std::uintmax_t kSummaryBaseBytes = 4'000;
/// Longest number as fragility.csv and runs.csv write it ("%.9g").
inline constexpr std::uintmax_t kNumberBytesBound = 15;

/// A study's size, without its records' samples.
struct StudyShape {
  std::vector<std::string> record_names;
  std::vector<std::size_t> record_samples;  ///< at the runs' step
  std::uintmax_t record_source_bytes = 0;   ///< the records' source texts together (summary.json)
  std::vector<double> pga_g, idle_years;
  std::vector<control::ControlMode> modes;
  std::vector<LimitState> limit_states;
  double step_s = 1e-3;

  std::size_t run_count() const noexcept {
    return record_names.size() * pga_g.size() * idle_years.size() * modes.size();
  }
  /// Closed-loop steps of every run.
  double steps() const noexcept;
};

/// The shape of a plan whose records are loaded.
StudyShape study_shape(const FragilityPlan& plan, const std::vector<LimitState>& limit_states);

/// The shape of a plan whose `count` records will be stochastic motions of
/// `ranges` (their names and lengths are known before they are made).
StudyShape synthetic_study_shape(const FragilityPlan& plan, const std::vector<LimitState>& limit_states,
                                 const StochasticMotionRanges& ranges, unsigned count);

struct DiskEstimate {
  std::uintmax_t runs_csv = 0, journal = 0, curves = 0, plots = 0, summary = 0;
  std::uintmax_t outputs() const noexcept { return runs_csv + curves + plots + summary; }
  std::uintmax_t total() const noexcept { return outputs() + journal; }
};

/// The bounds above.
DiskEstimate estimate_disk(const StudyShape& shape);

/// Memory of one process, bytes: its records (8 bytes a sample; every rank
/// holds all), the runs' peaks (twice: the rank's share and the gathered
/// study) and runs.csv, built in memory before it is written.
std::uintmax_t estimate_memory(const StudyShape& shape);

/// Steps per second of one worker running `mode`'s closed loop on this
/// machine: a short stochastic record (at most 5000 steps of `base.step_s`)
/// at `pga_g` and `idle_years`, run again until at least `min_s` of wall time
/// has passed.
double pilot_steps_per_s(const plant::PlantSpec& base, control::ControlMode mode, double pga_g, double idle_years,
                         double min_s = 0.03);

/// Wall seconds to generate one stochastic motion of `ranges` and resample
/// it to `step_s` on this machine (one record, timed).
double pilot_generation_s(const StochasticMotionRanges& ranges, double step_s);

/// Wall time of a study, s: Σ over the modes of (steps / modes) /
/// steps_per_s[mode], over `workers`, plus `generation_s`.
double estimate_wall_s(const StudyShape& shape, const std::vector<double>& steps_per_s, unsigned workers,
                       double generation_s);

/// The workers a study keeps busy: ranks x threads, the threads at most the
/// cores, and at most the study's chunks of runs (study_runner.hpp).
unsigned study_workers(std::size_t run_count, int ranks, unsigned threads, unsigned cores);

/// A file system's free space for an unprivileged user (statvfs: f_bavail x
/// f_frsize) and its device, for `path` or, when it does not exist yet, its
/// nearest existing ancestor; nullopt when neither can be examined.
struct FileSystemSpace {
  dev_t device = 0;
  std::uintmax_t free_bytes = 0;
  std::filesystem::path examined;  ///< the existing path statvfs was given
};
std::optional<FileSystemSpace> file_system_space(const std::filesystem::path& path);

/// "12.3 kB", "4.56 GB" (SI prefixes, 3 significant digits).
std::string format_bytes(std::uintmax_t bytes);
/// "0.4 s", "12 min", "3.5 h", "2.1 days".
std::string format_duration(double seconds);

}  // namespace mrd::risk
