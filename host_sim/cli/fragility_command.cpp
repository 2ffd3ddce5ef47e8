#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "host_sim/cli/command.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/excitation/scaled_motion.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/risk/cluster.hpp"
#include "host_sim/risk/fragility_fit.hpp"
#include "host_sim/risk/fragility_report.hpp"
#include "host_sim/risk/stochastic_motion.hpp"
#include "host_sim/risk/study_runner.hpp"
#include "host_sim/run/controller.hpp"

namespace mrd::cli {
namespace fragility_command {
namespace {

constexpr CommandHelp kFragilityHelp{
    "fragility", "Fragility curves: records x PGA x idle time x control mode, on all cores or MPI ranks",
    R"(Runs every record x PGA level x idle time x control mode in closed loop and fits, for each
control mode, idle time and limit state, a lognormal fragility P(LS | PGA) = Phi(ln(PGA/theta)/beta)
by maximum likelihood over the PGA levels (Baker 2015, binomial likelihood), with 5-95 % bootstrap
bands over the records. Records: --records DIR (every .csv and .at2 in it, by name), --record FILE,
or --synthetic N stochastic motions with an evolving spectrum (Rezaeian & Der Kiureghian 2008
model, seeded by --seed and the record's number; host_sim/risk/stochastic_motion.hpp). Each record
is scaled to each PGA.
Limit states (exceeded when the peak reaches the threshold):
  stroke          peak base displacement >= 0.2921 m, the damper's stroke (thesis 3.1)
  isolation_gap   peak base displacement >= --gap-m (default 0.20 m, an assumption)
  floor_accel     peak absolute floor acceleration, floors 1-5, >= --floor-accel-g (default 0.3 g)
Parallel: threads (--threads, default the cores over the ranks on the node) and, under mpirun or
srun, MPI ranks: the runs are numbered (control, idle, PGA, record; record fastest), cut in chunks
of 8 and chunk c goes to rank c mod N; rank 0 gathers and writes. runs.csv is the same bytes for
any number of ranks and threads. Progress and the time left on stderr (rank 0).
Resume: completed runs are appended to journal files in --journal (default DIR.journal beside
--out); a killed study run again with the same options skips them. The journal is removed once
the outputs are in place.
Files: DIR/runs.csv (run, record, control, idle_years, pga_g, peak_base_displacement_m,
peak_damper_force_kn, peak_floor_accel_m_s2, peak_base_accel_m_s2, peak_story_drift_m),
DIR/fragility.csv (control, limit_state, threshold (m or m/s2), idle_years, status (fitted |
none_exceeded | all_exceeded), median_pga_g, beta, their 5 and 95 % bootstrap percentiles, runs,
exceedances), DIR/fragility_curves.csv (each curve and band at 41 PGAs), one plot per control mode
and limit state (fragility_<control>_<limit state>.png, a curve per idle time), DIR/summary.json
(runs, runs_computed, runs_resumed, records, pga_g, idle_years, controls, limit_states, curves,
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
  double step_s = 1.0e-3;
  unsigned threads = 0;
  std::string journal;
  std::string out_dir = "out/fragility";
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
  require_step_s(o.step_s, 0.02, "0.02 s");
  risk::FragilityPlan plan;
  plan.pga_g = sorted_unique("--pga-g", o.pga_g);
  plan.idle_years = sorted_unique("--idle-years", o.idle_years);
  plan.seed = o.seed;
  plan.base.step_s = o.step_s;
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
  if (!o.records_dir.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_directory(o.records_dir, ec)) {
      throw io::UsageError("--records: '" + o.records_dir + "' is not a folder");
    }
    for (const auto& e : std::filesystem::directory_iterator(o.records_dir, ec)) {
      const std::string ext = io::to_lower(e.path().extension().string());
      if (e.is_regular_file() && (ext == ".csv" || ext == ".at2")) files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) throw io::UsageError("--records: no .csv or .at2 record in '" + o.records_dir + "'");
  }
  return files;
}

/// The records at the runs' step: the files given, or the stochastic motions
/// (each depends only on its seed: rank r of N makes records r, r + N, ... on
/// its threads and the ranks share them).
void load_records(const FragilityOptions& o, risk::FragilityPlan& plan, const risk::Cluster& cluster,
                  unsigned threads) {
  const auto files = record_files(o);
  for (const auto& f : files) {
    const auto m = excitation::load_scaled_motion(f, 1.0, plan.base.step_s);
    plan.records.push_back({m.name, m.source, m.accel_m_s2});
  }
  if (!files.empty()) return;
  const unsigned n = o.synthetic ? o.synthetic : 20;
  risk::StochasticMotionRanges ranges;
  ranges.duration_s = o.duration_s;
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
  add_step_s_option(app, o.step_s, "Simulation step, s");
  add_threads_option(app, o.threads, "Worker threads per rank (0: the node's cores over its ranks)");
  app.add_option("--journal", o.journal, "Resume journal folder (default: DIR.journal beside --out)");
  add_out_option(app, o.out_dir, "Output folder")->capture_default_str();
}

void execute(const FragilityOptions& o) {
  risk::Cluster cluster;
  risk::FragilityPlan plan = plan_options(o);
  const bool root = cluster.rank() == 0;
  std::filesystem::path out;
  std::exception_ptr open_error;
  if (root) {
    try {
      out = open_out_dir(o.out_dir);
    } catch (...) {
      open_error = std::current_exception();
    }
  }
  if (cluster.any(open_error != nullptr)) {
    if (open_error) std::rethrow_exception(open_error);
    throw io::UsageError("--out: rank 0 could not use the output folder");
  }
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  risk::StudyRunOptions ro;
  ro.threads = o.threads ? o.threads : std::max(1u, hw / static_cast<unsigned>(std::max(1, cluster.local_size())));
  const double records = static_cast<double>(o.records.empty() ? (o.synthetic ? o.synthetic : 20) : o.records.size());
  if (o.records_dir.empty() &&
      records * static_cast<double>(plan.pga_g.size() * plan.idle_years.size() * plan.modes.size()) > kMaxRuns) {
    throw io::UsageError("the study would have more than 1e8 runs; give fewer records, levels, idle times or modes");
  }
  load_records(o, plan, cluster, ro.threads);
  if (static_cast<double>(plan.run_count()) > kMaxRuns) {
    throw io::UsageError("the study has " + std::to_string(plan.run_count()) + " runs; at most 1e8 are allowed");
  }
  ro.journal_dir = o.journal.empty() ? std::filesystem::path(o.out_dir + ".journal") : std::filesystem::path(o.journal);
  if (root) {
    std::printf(
        "fragility: %zu records x %zu PGA levels x %zu idle times x %zu control modes = %zu runs on %d rank(s) x %u "
        "thread(s)\n",
        plan.records.size(), plan.pga_g.size(), plan.idle_years.size(), plan.modes.size(), plan.run_count(),
        cluster.size(), ro.threads);
    std::fflush(stdout);
    ro.progress = ProgressPrinter(cluster.size(), plan.run_count());
  }
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

  const auto limit_states = risk::default_limit_states(o.gap_m, o.floor_accel_g);
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
  session.synthetic = record_files(o).empty();
  const auto problems = risk::write_fragility_outputs(out, plan, result.runs, limit_states, curves, session);
  commit_out_dir();
  warn_plots_not_written("fragility", problems);
  std::error_code ec;
  std::filesystem::remove_all(ro.journal_dir, ec);
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
