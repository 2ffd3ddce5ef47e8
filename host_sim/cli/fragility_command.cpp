#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "host_sim/cli/building_option.hpp"
#include "host_sim/cli/damper_option.hpp"
#include "host_sim/cli/fluid_option.hpp"
#include "host_sim/cli/command.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/excitation/record_folder.hpp"
#include "host_sim/excitation/scaled_motion.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/report/output_transaction.hpp"
#include "host_sim/report/path_ownership.hpp"
#include "host_sim/risk/cluster.hpp"
#include "host_sim/risk/fragility_fit.hpp"
#include "host_sim/risk/fragility_plan.hpp"
#include "host_sim/risk/fragility_report.hpp"
#include "host_sim/risk/run_journal.hpp"
#include "host_sim/risk/stochastic_motion.hpp"
#include "host_sim/risk/study_estimate.hpp"
#include "host_sim/risk/study_runner.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/structure/isolators.hpp"

namespace mrd::cli {
namespace fragility_command {
namespace {

constexpr CommandHelp kFragilityHelp{
    "fragility", "Fragility curves: records x PGA x idle time x control mode, on all cores or MPI ranks",
    R"(Runs every record x PGA level x idle time x control mode in closed loop and fits, for each
control mode, idle time and limit state, a lognormal fragility P(LS | PGA) = Phi(ln(PGA/theta)/beta)
by maximum likelihood over the PGA levels (Baker 2015, binomial likelihood), with 5-95 % bootstrap
bands over the records. Records: --records DIR (every .csv and .at2 in it, any case, by name;
names starting with '.' are skipped, and a .csv or .at2 name that is not a regular file, such as a
folder, FIFO or device, is an error), --record FILE, or --synthetic N stochastic motions with an
evolving spectrum (Rezaeian & Der Kiureghian 2008 model, seeded by --seed and the record's number;
host_sim/risk/stochastic_motion.hpp). Each record is scaled to each PGA.
Limit states (exceeded when the peak reaches the threshold):
  stroke          peak base displacement >= 0.2921 m, the damper's stroke (thesis 3.1)
  isolation_gap   peak base displacement >= --gap-m (default 0.20 m, an assumption)
  floor_accel     peak absolute floor acceleration (DOFs 1..N-1, thesis floors 1-5; fixed base: all)
                  >= --floor-accel-g (default 0.3 g)
  story_drift     only with --drift-m X: peak story drift (max |x_i - x_{i-1}| over the stories)
                  >= X m. No default: a drift limit depends on the story heights, which the
                  building file does not hold, so X is an absolute drift (e.g. 0.02 m is 0.5 % of
                  a 4 m story), not a drift ratio. Without --drift-m the limit states are the
                  thesis's three above. With it, story_drift's rows, curves and plots are added
                  and the other curves stay as they are, bootstrap bands included (their
                  resampling seeds do not depend on it).
  bearing_capacity  only for a building whose bearings state displacement_capacity_m: peak
                  base displacement >= the smallest capacity they state (building file); its
                  rows, curves and plots are added likewise, ahead of story_drift's.
Building: --building FILE (README "Your building"; default the thesis building of Table 6.1,
buildings/thesis-6dof.toml, whose files are the same bytes with or without it). For another
building, "base displacement" is DOF 0 relative to the ground and "floors" its superstructure
(every DOF of a fixed-base building).
Damper and fluid: --damper FILE and --fluid FILE (README "Your damper and fluid"; defaults
dampers/thesis-200kn.toml and fluids/thesis-model-fluid.toml, the same bytes with or without
them): the stroke limit state and the warnings then take the damper's [rating] (stroke, force),
and the idle times settle the fluid in the damper's cylinder.
Parallel: threads (--threads, default the cores over the ranks on the node) and, under mpirun or
srun, MPI ranks: the runs are numbered (control, idle, PGA, record; record fastest), cut in chunks
of 8 and chunk c goes to rank c mod N; rank 0 gathers and writes. runs.csv is the same bytes for
any number of ranks and threads. Progress and the time left on stderr (rank 0).
Resume: completed runs are appended to journal files in --journal (default DIR.journal beside
--out); a killed study run again with the same options skips them. The journal is a folder
of mrd's own (it holds .mrd-journal; an existing folder of other files is refused, and so is one
that is, holds or lies inside --out or an input); its own files are removed once the outputs are
in place.
Cost: before it starts, the command prints the runs, the estimated wall time (the closed-loop steps
of every run over the steps per second a short pilot reaches on this machine for each control mode,
shared by the workers, plus the time to make the stochastic records), the disk it will write (upper
bounds: runs.csv per run, the journal at 64 bytes a run, the curves, the plots, summary.json) beside
the free space of --out's file system, and the memory per process. --estimate prints that and stops
(exit 0, nothing written). A study whose disk exceeds the free space of the file system of --out (or
of the journal's, when elsewhere), or whose processes would hold more memory than the machine has,
is refused (exit 2) before any work.
Beyond the model: runs whose peak stroke exceeds the damper's +-0.2921 m or whose peak damper force
exceeds its 200 kN are counted; one warning per kind on stderr, with the count and the worst peak,
also in summary.json warnings (the runs do not record the damper's velocity or coil current).
Files: DIR/runs.csv (run, record, control, idle_years, pga_g, peak_base_displacement_m,
peak_damper_force_kn, peak_floor_accel_m_s2, peak_base_accel_m_s2, peak_story_drift_m),
DIR/fragility.csv (control, limit_state, threshold (m or m/s2), idle_years, status (fitted |
none_exceeded | all_exceeded), median_pga_g, beta, their 5 and 95 % bootstrap percentiles, runs,
exceedances, pga_g_min and pga_g_max: the PGA levels fitted over), DIR/fragility_curves.csv (each
curve and band at 41 PGAs), one plot per control mode and limit state
(fragility_<control>_<limit state>.png, a curve per idle time), DIR/summary.json (runs,
runs_computed, runs_resumed, records, pga_g, idle_years, controls, building, dofs, limit_states,
curves, warnings,
ranks, threads_per_rank, wall_s, runs_per_core_hour (wall time x ranks x threads), cpu_s_rank0,
runs_per_cpu_hour (rank 0's runs over its CPU time)).)"};

/// Most runs one study holds.
constexpr double kMaxRuns = 1.0e8;

struct FragilityOptions {
  std::string records_dir;
  std::vector<std::string> records;
  unsigned synthetic = 0;
  double duration_s = 30.0;
  std::vector<double> pga_g{0.05, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0};
  std::vector<double> idle_years{0.0, 0.01, 0.03, 0.1, 0.3, 0.86};
  std::vector<std::string> controls;
  std::uint64_t seed = 1;
  unsigned bootstrap = 200;
  double gap_m = risk::kDefaultIsolationGap_m;
  double floor_accel_g = risk::kDefaultFloorAccel_g;
  std::optional<double> drift_m;  ///< --drift-m: the opt-in story_drift limit state
  std::string building;
  std::string damper;
  std::string fluid;
  double step_s = 1.0e-3;
  unsigned threads = 0;
  std::string journal;
  std::string out_dir = "out/fragility";
  bool estimate = false;
};

std::vector<double> sorted_unique(const std::string& option, std::vector<double> v) {
  std::sort(v.begin(), v.end());
  if (std::adjacent_find(v.begin(), v.end()) != v.end()) throw io::UsageError(option + ": a value is given twice");
  return v;
}

/// The plan without its records; throws io::UsageError for a bad option.
risk::FragilityPlan plan_options(const FragilityOptions& o) {
  const int sources = !o.records_dir.empty() + !o.records.empty() + (o.synthetic > 0);
  if (sources > 1) throw io::UsageError("--records, --record and --synthetic: give one of them");
  if (o.pga_g.empty()) throw io::UsageError("--pga-g: expected at least one PGA");
  for (double p : o.pga_g) check_pga_g(p);
  for (double y : o.idle_years) check_idle_years(y);
  if (o.idle_years.empty()) throw io::UsageError("--idle-years: expected at least one idle time");
  require_positive("--duration-s", o.duration_s, "a duration");
  require_at_most("--duration-s", o.duration_s, 600.0, "600 s");
  require_positive("--gap-m", o.gap_m, "an isolation gap");
  require_positive("--floor-accel-g", o.floor_accel_g, "a floor acceleration");
  if (o.drift_m) require_positive("--drift-m", *o.drift_m, "a story drift");
  require_step_s(o.step_s, 0.02, "0.02 s");
  risk::FragilityPlan plan;
  plan.pga_g = sorted_unique("--pga-g", o.pga_g);
  plan.idle_years = sorted_unique("--idle-years", o.idle_years);
  plan.seed = o.seed;
  plan.base.step_s = o.step_s;
  plan.base.building = load_building(o.building);
  const DamperAndFluid d = load_damper_and_fluid("fragility", o.damper, o.fluid);
  plan.base.damper = d.params;
  plan.base.settling = d.settling;
  if (o.controls.empty()) {
    plan.modes = run::available_modes();
  } else {
    for (const auto& c : o.controls) plan.modes.push_back(run::parse_control_mode(c));
  }
  for (auto mode : plan.modes) (void)run::make_controller(mode, plan.base.step_s);
  return plan;
}

std::vector<std::filesystem::path> record_files(const FragilityOptions& o) {
  std::vector<std::filesystem::path> files;
  for (const auto& r : o.records) files.emplace_back(r);
  if (!o.records_dir.empty()) files = excitation::record_files_in_folder("--records", o.records_dir);
  return files;
}

/// The records files given, at the runs' step.
void load_record_files(const std::vector<std::filesystem::path>& files, risk::FragilityPlan& plan) {
  for (const auto& f : files) {
    const auto m = excitation::load_scaled_motion(f, 1.0, plan.base.step_s);
    plan.records.push_back({m.name, m.source, m.accel_m_s2});
  }
}

unsigned synthetic_count(const FragilityOptions& o) { return o.synthetic ? o.synthetic : 20; }

risk::StochasticMotionRanges synthetic_ranges(const FragilityOptions& o) {
  risk::StochasticMotionRanges ranges;
  ranges.duration_s = o.duration_s;
  return ranges;
}

/// The stochastic motions at the runs' step (each depends only on its seed:
/// rank r of N makes records r, r + N, ... on its threads and the ranks share
/// them).
void make_synthetic_records(const FragilityOptions& o, risk::FragilityPlan& plan, const risk::Cluster& cluster,
                            unsigned threads) {
  const unsigned n = synthetic_count(o);
  const risk::StochasticMotionRanges ranges = synthetic_ranges(o);
  const auto ranks = static_cast<unsigned>(cluster.size());
  std::vector<std::vector<double>> accel(n);
  std::atomic<unsigned> next{static_cast<unsigned>(cluster.rank())};
  const auto worker = [&] {
    for (unsigned i = next.fetch_add(ranks); i < n; i = next.fetch_add(ranks)) {
      const auto m = risk::stochastic_motion(ranges, risk::record_seed(o.seed, i), i);
      accel[i] = excitation::resample_linear(m, plan.base.step_s);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < std::min(threads, n); ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  cluster.share(accel);
  for (unsigned i = 0; i < n; ++i) {
    const auto label = risk::stochastic_motion_label(ranges, risk::record_seed(o.seed, i), i);
    plan.records.push_back({label.name, label.source, std::move(accel[i])});
  }
}

/// Progress of rank 0 on stderr with the time left at its rate: a counter on a
/// terminal, otherwise a line at most every 5 s and at the end.
class ProgressPrinter {
 public:
  ProgressPrinter(int ranks, std::size_t study_runs) : ranks_(ranks), study_runs_(study_runs) {}
  void operator()(const risk::StudyProgress& p) {
    const bool last = p.done == p.total;
    if (!tty_ && !last && p.elapsed_s < last_s_ + 5.0) return;
    last_s_ = p.elapsed_s;
    const double left_s =
        p.done ? p.elapsed_s / static_cast<double>(p.done) * static_cast<double>(p.total - p.done) : 0;
    std::fprintf(
        stderr, "%sfragility: %zu/%zu runs of rank 0 (%d rank(s), %zu runs in the study), %.0f s, about %.0f s left%s",
        tty_ ? "\r" : "", p.done, p.total, ranks_, study_runs_, p.elapsed_s, left_s, tty_ && !last ? "" : "\n");
  }

 private:
  bool tty_ = ::isatty(STDERR_FILENO) != 0;
  int ranks_;
  std::size_t study_runs_;
  double last_s_ = -1e9;
};

void add_options(CLI::App& app, FragilityOptions& o) {
  app.add_option("--records", o.records_dir, "Folder of records (.csv, .at2)");
  app.add_option("--record", o.records, "Record file(s) (.csv, .at2)");
  app.add_option("--synthetic", o.synthetic, "Number of stochastic motions (default 20 when no record is given)")
      ->check(CLI::Range(1u, 100000u));
  app.add_option("--duration-s", o.duration_s, "Length of each stochastic motion, s")->capture_default_str();
  app.add_option("--pga-g", o.pga_g, "PGA levels, g (comma-separated)")->delimiter(',')->capture_default_str();
  app.add_option("--idle-years", o.idle_years, "Idle times, years (comma-separated)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--control", o.controls, "Control mode(s), comma-separated (default: all this build has)")
      ->delimiter(',');
  add_seed_option(app, o.seed, "Study seed: stochastic motions and bootstrap");
  app.add_option("--bootstrap", o.bootstrap, "Bootstrap resamples per curve (0: no bands)")
      ->check(CLI::Range(0u, 100000u))
      ->capture_default_str();
  app.add_option("--gap-m", o.gap_m, "Isolation gap of the isolation_gap limit state, m")->capture_default_str();
  app.add_option("--floor-accel-g", o.floor_accel_g, "Threshold of the floor_accel limit state, g")
      ->capture_default_str();
  app.add_option("--drift-m", o.drift_m,
                 "Adds the story_drift limit state at this peak story drift, m (no default: a drift limit depends on "
                 "the story heights, which the building file does not hold)");
  add_building_option(app, o.building);
  add_damper_option(app, o.damper);
  add_fluid_option(app, o.fluid);
  add_step_s_option(app, o.step_s, "Simulation step, s");
  add_threads_option(app, o.threads, "Worker threads per rank (0: the node's cores over its ranks)");
  app.add_option("--journal", o.journal, "Resume journal folder (default: DIR.journal beside --out)");
  app.add_flag("--estimate", o.estimate, "Print the study's runs, estimated wall time, disk and memory, and stop");
  add_out_option(app, o.out_dir, "Output folder")->capture_default_str();
}

/// The resume journal's folder, resolved: --journal, or DIR.journal beside
/// the resolved --out DIR (so `--out D/` gives D.journal, never D/.journal).
std::filesystem::path journal_folder(const FragilityOptions& o) {
  if (!o.journal.empty()) return report::resolve_path("--journal", o.journal);
  std::filesystem::path j = report::output_target(o.out_dir);
  j += ".journal";
  return j;
}

/// A journal is used, and removed after the run, only when it is absent,
/// empty or a journal (report::kJournalMarker), and lies clear of --out and
/// of every input.
void check_journal_folder(const FragilityOptions& o, const std::filesystem::path& journal) {
  const std::string shown = o.journal.empty() ? journal.string() : o.journal;
  report::check_owned_or_new("--journal", shown, journal, report::kJournalMarker);
  report::check_clear_of_output("--journal", shown, journal, "--out", o.out_dir, report::output_target(o.out_dir));
  report::check_clear_of_inputs("--journal", shown, journal);
}

/// Refuses a study whose disk exceeds the free space of the file system it
/// writes to: the outputs (and the journal, when it lies on the same one) on
/// --out's, the journal on its own.
void check_disk_space(const FragilityOptions& o, const risk::DiskEstimate& disk,
                      const std::optional<risk::FileSystemSpace>& out_fs, const std::filesystem::path& journal) {
  const auto journal_fs = risk::file_system_space(journal);
  const bool shared = out_fs && journal_fs && out_fs->device == journal_fs->device;
  const auto refuse = [](const char* option, const std::string& path, std::uintmax_t need, std::uintmax_t free) {
    throw io::UsageError(std::string(option) + ": the study would write about " + risk::format_bytes(need) +
                         " to the file system of '" + path + "', which has " + risk::format_bytes(free) +
                         " free; give fewer runs or another folder (--estimate shows the cost)");
  };
  const std::uintmax_t out_need = disk.outputs() + (shared ? disk.journal : 0);
  if (out_fs && out_need > out_fs->free_bytes) refuse("--out", o.out_dir, out_need, out_fs->free_bytes);
  if (!shared && journal_fs && disk.journal > journal_fs->free_bytes) {
    refuse("--journal", journal.string(), disk.journal, journal_fs->free_bytes);
  }
}

/// Physical memory of this machine, bytes (0 when unknown).
std::uintmax_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<std::uintmax_t>(pages) * static_cast<std::uintmax_t>(page) : 0;
}

/// Says on rank 0, before any work, what the study will cost: its runs, the
/// wall time from a pilot on this machine, its disk and memory; then refuses
/// (io::UsageError, on every rank) a study whose disk exceeds the free space
/// of its file system or whose processes on this node would hold more memory
/// than the machine has. Returns true when --estimate asks to stop there.
bool announce_cost(const FragilityOptions& o, const risk::FragilityPlan& plan, bool synthetic,
                   const std::vector<risk::LimitState>& limit_states, const std::filesystem::path& journal,
                   const risk::Cluster& cluster, unsigned threads) {
  std::exception_ptr refusal;
  if (cluster.rank() == 0) {
    const risk::StudyShape shape =
        synthetic ? risk::synthetic_study_shape(plan, limit_states, synthetic_ranges(o), synthetic_count(o))
                  : risk::study_shape(plan, limit_states);
    const std::size_t runs = shape.run_count();
    std::printf(
        "fragility: %zu records x %zu PGA levels x %zu idle times x %zu control modes = %zu runs on %d rank(s) x %u "
        "thread(s)\n",
        shape.record_names.size(), plan.pga_g.size(), plan.idle_years.size(), plan.modes.size(), runs, cluster.size(),
        threads);
    std::fflush(stdout);
    std::vector<double> steps_per_s;
    for (auto mode : plan.modes) {
      steps_per_s.push_back(risk::pilot_steps_per_s(plan.base, mode, plan.pga_g[plan.pga_g.size() / 2],
                                                    plan.idle_years.front()));
    }
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const unsigned workers = risk::study_workers(runs, cluster.size(), threads, cores);
    double generation_s = 0.0;
    if (synthetic) {
      const double makers = std::min<double>(synthetic_count(o), static_cast<double>(cluster.size()) *
                                                                     std::min(threads, cores));
      generation_s = risk::pilot_generation_s(synthetic_ranges(o), plan.base.step_s) *
                     std::ceil(synthetic_count(o) / std::max(1.0, makers));
    }
    const double wall_s = risk::estimate_wall_s(shape, steps_per_s, workers, generation_s);
    double slowest = steps_per_s.front();
    for (double r : steps_per_s) slowest = std::min(slowest, r);
    std::printf(
        "fragility: estimate: %.3g closed-loop steps of %.3g s, at %.3g steps/s or more per worker (a pilot on this "
        "machine) on %u worker(s)%s: about %s of wall time\n",
        shape.steps(), plan.base.step_s, slowest, workers,
        synthetic ? (", after making the records in about " + risk::format_duration(generation_s)).c_str() : "",
        risk::format_duration(wall_s).c_str());
    if (!risk::lanes_take(plan)) std::printf("fragility: the runs step one by one in the scalar loop\n");
    const risk::DiskEstimate disk = risk::estimate_disk(shape);
    const auto out_fs = risk::file_system_space(o.out_dir);
    const std::uintmax_t memory = risk::estimate_memory(shape);
    std::printf(
        "fragility: estimate: at most %s on disk: runs.csv %s (%s per run), journal %s (%zu B per run, removed at "
        "the end), curves %s, plots %s, summary.json %s; %s free on the file system of --out; memory %s per "
        "process\n",
        risk::format_bytes(disk.total()).c_str(), risk::format_bytes(disk.runs_csv).c_str(),
        risk::format_bytes(runs ? disk.runs_csv / runs : 0).c_str(), risk::format_bytes(disk.journal).c_str(),
        risk::kJournalRecordBytes, risk::format_bytes(disk.curves).c_str(), risk::format_bytes(disk.plots).c_str(),
        risk::format_bytes(disk.summary).c_str(),
        out_fs ? risk::format_bytes(out_fs->free_bytes).c_str() : "unknown", risk::format_bytes(memory).c_str());
    std::fflush(stdout);
    if (!o.estimate) {
      try {
        check_disk_space(o, disk, out_fs, journal);
        const std::uintmax_t ram = physical_memory_bytes();
        const auto local = static_cast<std::uintmax_t>(std::max(1, cluster.local_size()));
        if (ram > 0 && memory * local > ram) {
          throw io::UsageError("the study's records and results would take about " +
                               risk::format_bytes(memory * local) + " of memory on this machine, which has " +
                               risk::format_bytes(ram) +
                               "; give fewer or shorter records, fewer runs or a longer --step-s");
        }
      } catch (...) {
        refusal = std::current_exception();
      }
    }
  }
  if (o.estimate) return true;
  if (cluster.any(refusal != nullptr)) {
    if (refusal) std::rethrow_exception(refusal);
    throw io::UsageError("rank 0 refused the study");
  }
  return false;
}

void execute(const FragilityOptions& o) {
  risk::Cluster cluster;
  risk::FragilityPlan plan = plan_options(o);
  const bool root = cluster.rank() == 0;
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const unsigned threads =
      o.threads ? o.threads : std::max(1u, hw / static_cast<unsigned>(std::max(1, cluster.local_size())));
  const double records = static_cast<double>(o.records.empty() ? synthetic_count(o) : o.records.size());
  if (o.records_dir.empty() &&
      records * static_cast<double>(plan.pga_g.size() * plan.idle_years.size() * plan.modes.size()) > kMaxRuns) {
    throw io::UsageError("the study would have more than 1e8 runs; give fewer records, levels, idle times or modes");
  }
  const auto files = record_files(o);
  const bool synthetic = files.empty();
  load_record_files(files, plan);
  if (static_cast<double>(plan.run_count()) > kMaxRuns) {
    throw io::UsageError("the study has " + std::to_string(plan.run_count()) + " runs; at most 1e8 are allowed");
  }
  auto limit_states = risk::default_limit_states(o.gap_m, o.floor_accel_g);
  for (auto& l : limit_states) {
    if (l.name == "stroke") l.threshold = plan.base.damper.rating.stroke_m;  // the damper's (thesis: 0.2921 m)
  }
  structure::IsolatorBank bearings;
  bearings.init(plan.base.building);
  if (bearings.displacement_capacity_m() > 0.0)
    limit_states.push_back(risk::bearing_capacity_limit_state(bearings.displacement_capacity_m()));
  if (o.drift_m) limit_states.push_back(risk::story_drift_limit_state(*o.drift_m));
  if (announce_cost(o, plan, synthetic, limit_states, journal_folder(o), cluster, threads)) return;
  std::filesystem::path out;
  std::exception_ptr open_error;
  const std::filesystem::path journal = journal_folder(o);
  if (root) {
    try {
      check_journal_folder(o, journal);
      out = open_out_dir(o.out_dir);
    } catch (...) {
      open_error = std::current_exception();
    }
  }
  if (cluster.any(open_error != nullptr)) {
    if (open_error) std::rethrow_exception(open_error);
    throw io::UsageError("--out: rank 0 could not use the output folder");
  }
  risk::StudyRunOptions ro;
  ro.threads = threads;
  if (synthetic) make_synthetic_records(o, plan, cluster, ro.threads);
  ro.journal_dir = journal;
  if (root) ro.progress = ProgressPrinter(cluster.size(), plan.run_count());
  risk::StudyRunResult result;
  try {
    result = risk::run_study(plan, cluster, ro);
  } catch (const std::exception& e) {
    if (cluster.size() > 1) {
      std::fprintf(stderr, "mrd: error: rank %d: %s\n", cluster.rank(), e.what());
      cluster.abort(1);
    }
    throw;
  }
  if (!root) return;

  const auto curves = risk::fit_fragilities(plan, result.runs, limit_states, {o.bootstrap, o.seed, 41});
  risk::FragilitySession session;
  session.computed = result.computed;
  session.resumed = result.resumed;
  session.wall_s = result.wall_s;
  session.computed_rank0 = result.computed_here;
  session.cpu_s_rank0 = result.cpu_s;
  session.ranks = cluster.size();
  session.threads_per_rank = ro.threads;
  session.bootstrap = o.bootstrap;
  session.synthetic = synthetic;
  session.warnings = risk::fragility_warnings(result.runs, plan.base.damper.rating);
  const auto problems = risk::write_fragility_outputs(out, plan, result.runs, limit_states, curves, session);
  commit_out_dir();
  warn_plots_not_written("fragility", problems);
  print_warnings("fragility", session.warnings);
  risk::remove_journal(ro.journal_dir);
  const double core_h = result.wall_s * cluster.size() * ro.threads / 3600.0;
  std::printf(
      "fragility: %zu runs computed, %zu resumed, in %.2f s on %d rank(s) x %u thread(s): %.0f runs per "
      "core-hour of wall time, %.0f per CPU-hour (rank 0)\n",
      result.computed, result.resumed, result.wall_s, cluster.size(), ro.threads,
      core_h > 0 ? static_cast<double>(result.computed) / core_h : 0.0,
      result.cpu_s > 0 ? static_cast<double>(result.computed_here) / result.cpu_s * 3600.0 : 0.0);
  std::printf("wrote %s/runs.csv, fragility.csv, fragility_curves.csv and summary.json\n", o.out_dir.c_str());
}

}  // namespace
}  // namespace fragility_command

Command add_fragility_command(CLI::App& parent) {
  using namespace fragility_command;
  return make_command(parent, kFragilityHelp, add_options, execute);
}

}  // namespace mrd::cli
