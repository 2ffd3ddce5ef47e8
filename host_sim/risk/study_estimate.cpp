#include "host_sim/risk/study_estimate.hpp"

#include <sys/stat.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <span>

#include "host_sim/excitation/ground_motion.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/risk/fragility_report.hpp"
#include "host_sim/risk/run_journal.hpp"
#include "host_sim/risk/study_runner.hpp"

namespace mrd::risk {
namespace {

/// Steps of the pilot record, at most.
constexpr std::size_t kPilotSteps = 5000;
/// Length of the stochastic motion the pilot record is cut from, s.
constexpr double kPilotRecord_s = 5.0;
/// Samples the generation pilot resamples, at most.
constexpr double kPilotResampled = 1e5;

std::uintmax_t text_bytes(double v) { return io::format_number("%.9g", v).size(); }

/// Σ over i in [0, n) of the decimal digits of i.
std::uintmax_t index_digits(std::uintmax_t n) {
  std::uintmax_t sum = 0, lo = 0, hi = 10, digits = 1;
  while (lo < n) {
    sum += (std::min(n, hi) - lo) * digits;
    lo = hi;
    if (hi > UINTMAX_MAX / 10) break;
    hi *= 10;
    ++digits;
  }
  return sum;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

StudyShape shape_without_records(const FragilityPlan& plan, const std::vector<LimitState>& limit_states) {
  StudyShape s;
  s.pga_g = plan.pga_g;
  s.idle_years = plan.idle_years;
  s.modes = plan.modes;
  s.limit_states = limit_states;
  s.step_s = plan.base.step_s;
  return s;
}

}  // namespace

double StudyShape::steps() const noexcept {
  double samples = 0.0;
  for (std::size_t n : record_samples) samples += static_cast<double>(n);
  return samples * static_cast<double>(pga_g.size() * idle_years.size() * modes.size());
}

StudyShape study_shape(const FragilityPlan& plan, const std::vector<LimitState>& limit_states) {
  StudyShape s = shape_without_records(plan, limit_states);
  for (const auto& r : plan.records) {
    s.record_names.push_back(r.name);
    s.record_samples.push_back(r.accel_1g_m_s2.size());
    s.record_source_bytes += r.source.size();
  }
  return s;
}

StudyShape synthetic_study_shape(const FragilityPlan& plan, const std::vector<LimitState>& limit_states,
                                 const StochasticMotionRanges& ranges, unsigned count) {
  StudyShape s = shape_without_records(plan, limit_states);
  // The record lasts floor(duration / dt)·dt; resampled to the step, as
  // excitation::resample_linear counts its samples.
  const double kept_s = std::floor(ranges.duration_s / ranges.dt_s + 1e-9) * ranges.dt_s;
  const auto samples = static_cast<std::size_t>(std::floor(kept_s / plan.base.step_s + 1e-9)) + 1;
  for (unsigned i = 0; i < count; ++i) {
    const StochasticLabel label = stochastic_motion_label(ranges, record_seed(plan.seed, i), i);
    s.record_names.push_back(label.name);
    s.record_samples.push_back(samples);
    s.record_source_bytes += label.source.size();
  }
  return s;
}

DiskEstimate estimate_disk(const StudyShape& s) {
  DiskEstimate d;
  const std::uintmax_t runs = s.run_count();
  if (runs == 0) return d;
  const std::uintmax_t per_record = runs / s.record_names.size(), per_pga = runs / s.pga_g.size(),
                       per_idle = runs / s.idle_years.size(), per_mode = runs / s.modes.size();
  d.runs_csv = runs_csv(FragilityPlan{}, {}).size() + index_digits(runs) +
               runs * (9 + 1 + kRunMetricCount * kNumberBytesBound);
  for (const auto& n : s.record_names) d.runs_csv += per_record * n.size();
  for (double v : s.pga_g) d.runs_csv += per_pga * text_bytes(v);
  for (double v : s.idle_years) d.runs_csv += per_idle * text_bytes(v);
  std::uintmax_t mode_names = 0;
  for (auto m : s.modes) mode_names += std::char_traits<char>::length(control::mode_name(m));
  d.runs_csv += per_mode * mode_names;

  d.journal = runs * kJournalRecordBytes;

  // Curves: every mode x idle time x limit state.
  std::uintmax_t state_names = 0;
  for (const auto& l : s.limit_states) state_names += l.name.size();
  const std::uintmax_t idle = s.idle_years.size(), modes = s.modes.size(), states = s.limit_states.size();
  const std::uintmax_t curves = modes * idle * states;
  const std::uintmax_t name_bytes = idle * (mode_names * states + state_names * modes);  // Σ over the curves
  // fragility.csv: 10 numbers, the status (at most 13 characters), 2 counts
  // (at most 20 digits), 14 commas and a newline.
  d.curves = std::char_traits<char>::length(kFragilityCsvHeader) +
             std::char_traits<char>::length(kFragilityCsvRangeColumns) + 2 + name_bytes +
             curves * (10 * kNumberBytesBound + 13 + 40 + 15);
  // fragility_curves.csv: per point 5 numbers, 6 commas and a newline.
  const auto points = static_cast<std::uintmax_t>(BootstrapOptions{}.eval_points);
  d.curves += 100 + points * (name_bytes + curves * (5 * kNumberBytesBound + 7));

  d.plots = modes * states * kPlotBytesBound;
  std::uintmax_t record_text = s.record_source_bytes;
  for (const auto& n : s.record_names) record_text += n.size() + 40;
  d.summary = kSummaryBaseBytes + record_text + 200 * curves;
  return d;
}

std::uintmax_t estimate_memory(const StudyShape& s) {
  double samples = 0.0;
  for (std::size_t n : s.record_samples) samples += static_cast<double>(n);
  return static_cast<std::uintmax_t>(samples * sizeof(double)) + s.run_count() * 2 * sizeof(RunMetrics) +
         estimate_disk(s).runs_csv;
}

double pilot_steps_per_s(const plant::PlantSpec& base, control::ControlMode mode, double pga_g, double idle_years,
                         double min_s) {
  StochasticMotionRanges ranges;
  ranges.duration_s = kPilotRecord_s;
  const auto motion = stochastic_motion(ranges, record_seed(1, 0), 0);
  std::vector<double> accel = excitation::resample_linear(motion, base.step_s);
  if (accel.size() > kPilotSteps) accel.resize(kPilotSteps);
  FragilityPlan plan;
  plan.base = base;
  plan.records = {{motion.name, motion.source, std::move(accel)}};
  plan.pga_g = {pga_g};
  plan.idle_years = {idle_years};
  plan.modes = {mode};
  // A whole chunk, as the study steps it (its runs side by side in lanes).
  const std::vector<std::size_t> run(kChunkRuns, 0);
  std::vector<RunMetrics> out(kChunkRuns);
  const auto t0 = std::chrono::steady_clock::now();
  double steps = 0.0, elapsed_s = 0.0;
  do {
    simulate_runs(plan, run, out);
    steps += static_cast<double>(plan.records[0].accel_1g_m_s2.size() * run.size());
    elapsed_s = seconds_since(t0);
  } while (elapsed_s < min_s);
  return steps / std::max(elapsed_s, 1e-9);
}

double pilot_generation_s(const StochasticMotionRanges& ranges, double step_s) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto motion = stochastic_motion(ranges, record_seed(1, 0), 0);
  const double generation_s = seconds_since(t0);
  // Resampling costs the same per sample: timed on at most kPilotResampled
  // samples (the record at a fine step would take gigabytes), then scaled.
  const double samples = std::floor(motion.duration_s() / step_s + 1e-9) + 1.0;
  const double part = std::min(samples, kPilotResampled);
  const auto t1 = std::chrono::steady_clock::now();
  (void)excitation::resample_linear(motion, step_s, (part - 1.0) * step_s);
  return generation_s + seconds_since(t1) * samples / part;
}

double estimate_wall_s(const StudyShape& shape, const std::vector<double>& steps_per_s, unsigned workers,
                       double generation_s) {
  const double steps_per_mode = shape.steps() / static_cast<double>(std::max<std::size_t>(1, shape.modes.size()));
  double cpu_s = 0.0;
  for (double rate : steps_per_s) cpu_s += steps_per_mode / rate;
  return cpu_s / std::max(1u, workers) + generation_s;
}

unsigned study_workers(std::size_t run_count, int ranks, unsigned threads, unsigned cores) {
  const std::size_t chunks = (run_count + 7) / 8;
  const std::size_t per_rank = std::max(1u, std::min(threads, std::max(1u, cores)));
  const std::size_t workers = std::min(static_cast<std::size_t>(std::max(1, ranks)) * per_rank, chunks);
  return static_cast<unsigned>(std::max<std::size_t>(1, workers));
}

std::optional<FileSystemSpace> file_system_space(const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::path p = std::filesystem::absolute(path, ec).lexically_normal();
  if (ec) return std::nullopt;
  while (!std::filesystem::exists(p, ec)) {
    if (!p.has_relative_path()) return std::nullopt;
    p = p.parent_path();
  }
  struct statvfs v {};
  struct stat st {};
  if (::statvfs(p.c_str(), &v) != 0 || ::stat(p.c_str(), &st) != 0) return std::nullopt;
  return FileSystemSpace{st.st_dev, static_cast<std::uintmax_t>(v.f_bavail) * v.f_frsize, p};
}

std::string format_bytes(std::uintmax_t bytes) {
  if (bytes < 1000) return std::to_string(bytes) + " B";
  static const char* const kUnits[] = {"kB", "MB", "GB", "TB", "PB", "EB"};
  double v = static_cast<double>(bytes) / 1000.0;
  std::size_t u = 0;
  while (v >= 999.5 && u + 1 < std::size(kUnits)) {
    v /= 1000.0;
    ++u;
  }
  return io::format_number("%.3g", v) + " " + kUnits[u];
}

std::string format_duration(double seconds) {
  if (!(seconds < 60.0)) {
    if (seconds < 3600.0) return io::format_number("%.3g", seconds / 60.0) + " min";
    if (seconds < 86400.0) return io::format_number("%.3g", seconds / 3600.0) + " h";
    return io::format_number("%.3g", seconds / 86400.0) + " days";
  }
  return io::format_number("%.2g", seconds) + " s";
}

}  // namespace mrd::risk
