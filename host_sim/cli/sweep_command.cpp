#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "host_sim/cli/building_option.hpp"
#include "host_sim/cli/damper_option.hpp"
#include "host_sim/cli/fluid_option.hpp"
#include "host_sim/cli/command.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/sweep.hpp"
#include "host_sim/run/sweep_report.hpp"

namespace mrd::cli {
namespace sweep_command {
namespace {

constexpr CommandHelp kSweepHelp{
    "sweep", "Idle-time sweep: records x control modes x idle times",
    R"(Runs every record x control mode x idle time in closed loop on all cores (thesis §6.5) and
writes DIR/sweep.csv (one row per run: record, control, idle_years, sq, peak_base_displacement_m,
peak_damper_force_kn, peak_superstructure_accel_m_s2, peak_base_accel_m_s2, peak_current_a,
final_participant_ratio) and, per control mode, the plots of Fig. 6.12-6.20 (peak base
displacement, damper force and superstructure acceleration against idle time), plus
DIR/summary.json (runs, wall time, simulated seconds per wall second, files, building and dofs,
and warnings: how many runs exceed the model's stroke, velocity, current or force limits, also
printed on stderr).
Defaults: the four records of Table 6.2 from the shared data folder at 0.1127 g (Table 6.3), every
control mode this build has, idle 0 to 1 year every 0.05 year. Past the maximum settling time
(0.853 years, Eq. 5.4) SQ saturates and the curves flatten.
--building FILE sweeps another building (README "Your building"; default the thesis building,
buildings/thesis-6dof.toml, whose outputs are the same bytes with or without the file). For any
other building sweep.csv appends two columns, peak_isolator_force_kn (the isolators' summed force,
0 without isolators) and peak_story_drift_m (max |element deformation| over the stories), and the
plots name the building instead of the thesis figure.
--damper FILE and --fluid FILE sweep another damper and MR fluid (README "Your damper and fluid";
defaults dampers/thesis-200kn.toml and fluids/thesis-model-fluid.toml, the same bytes with or
without them): the settling time is then the fluid's in the damper's cylinder, and the warnings'
limits are the damper's [rating].)"};

/// Most idle times one sweep runs.
constexpr int kMaxIdlePoints = 10000;

struct SweepOptions {
  std::vector<std::string> records;
  double pga_g = run::kThesisPga_g;
  std::vector<std::string> controls;
  double idle_from = 0.0;
  double idle_to = 1.0;
  double idle_step = 0.05;
  double step_s = 1.0e-3;
  unsigned threads = 0;
  std::string building;
  std::string damper;
  std::string fluid;
  std::string out_dir = "out/sweep";
};

/// The sweep the options ask for, without its motions; throws
/// io::UsageError for a bad option.
run::SweepSpec sweep_spec(const SweepOptions& o) {
  check_pga_g(o.pga_g);
  require_finite_at_least("--idle-from", o.idle_from, 0.0);
  require_at_most("--idle-from", o.idle_from, kMaxIdleYears, "1000 years");
  require_finite_at_least("--idle-to", o.idle_to, o.idle_from);
  require_at_most("--idle-to", o.idle_to, kMaxIdleYears, "1000 years");
  require_finite_at_least("--idle-step", o.idle_step, 1e-6);
  if ((o.idle_to - o.idle_from) / o.idle_step > kMaxIdlePoints) {
    throw io::UsageError("--idle-step: " + io::format_number("%.6g", o.idle_step) + " years from --idle-from to " +
                         "--idle-to gives more than " + std::to_string(kMaxIdlePoints) + " idle times");
  }
  require_step_s(o.step_s, 0.02, "0.02 s");
  run::SweepSpec spec;
  spec.base.step_s = o.step_s;
  spec.base.building = load_building(o.building);
  const DamperAndFluid d = load_damper_and_fluid("sweep", o.damper, o.fluid);
  spec.base.damper = d.params;
  spec.base.settling = d.settling;
  spec.threads = o.threads;
  spec.idle_years = run::idle_grid(o.idle_from, o.idle_to, o.idle_step);
  if (o.controls.empty()) {
    spec.modes = run::available_modes();
  } else {
    for (const auto& c : o.controls) spec.modes.push_back(run::parse_control_mode(c));
  }
  return spec;
}

/// The records given, or the four of Table 6.2 (four synthetic motions
/// when the shared folder is absent, and it says so).
std::vector<run::StudyMotion> sweep_motions(const SweepOptions& o) {
  std::vector<run::StudyMotion> motions;
  if (o.records.empty()) {
    motions = run::thesis_study_motions(o.pga_g, o.step_s);
    if (motions.front().synthetic) {
      std::printf("shared ground motions not found: sweeping four synthetic motions instead\n");
    }
  } else {
    for (const auto& r : o.records) motions.push_back(run::load_study_motion(r, o.pga_g, o.step_s));
  }
  return motions;
}

void print_timing(const run::SweepSpec& spec, const std::vector<run::SweepRow>& rows, double wall_s) {
  const double simulated_s = run::simulated_seconds(rows);
  std::printf("sweep: %zu runs, %.1f s simulated in %.2f s wall (%.0fx real time on %u threads)\n", rows.size(),
              simulated_s, wall_s, simulated_s / wall_s,
              spec.threads ? spec.threads : std::thread::hardware_concurrency());
}

/// Progress on stderr: a counter on a terminal, every tenth of the runs otherwise.
class ProgressPrinter {
 public:
  void operator()(std::size_t done, std::size_t total) {
    if (tty_) {
      std::fprintf(stderr, "\rsweep: %zu/%zu runs", done, total);
      if (done == total) std::fprintf(stderr, "\n");
    } else if (done * 10 / total > last_decile_ || done == total) {
      last_decile_ = done * 10 / total;
      std::fprintf(stderr, "sweep: %zu/%zu runs\n", done, total);
    }
  }

 private:
  bool tty_ = ::isatty(STDERR_FILENO) != 0;
  std::size_t last_decile_ = 0;
};

void add_options(CLI::App& app, SweepOptions& o) {
  app.add_option("--record", o.records, "Ground-motion record(s) (default: the four of Table 6.2)");
  add_pga_g_option(app, o.pga_g, "PGA every record is scaled to, g");
  app.add_option("--control", o.controls, "Control mode(s) (default: all this build has)");
  app.add_option("--idle-from", o.idle_from, "First idle time, years")->capture_default_str();
  app.add_option("--idle-to", o.idle_to, "Last idle time, years")->capture_default_str();
  app.add_option("--idle-step", o.idle_step, "Idle-time step, years")->capture_default_str();
  add_step_s_option(app, o.step_s, "Simulation step, s");
  add_threads_option(app, o.threads, "Worker threads (0: all cores)");
  add_building_option(app, o.building);
  add_damper_option(app, o.damper);
  add_fluid_option(app, o.fluid);
  add_out_option(app, o.out_dir, "Output folder")->capture_default_str();
}

void execute(const SweepOptions& o) {
  run::SweepSpec spec = sweep_spec(o);
  const auto out = open_out_dir(o.out_dir);
  spec.motions = sweep_motions(o);
  const auto t0 = std::chrono::steady_clock::now();
  const auto rows = run::run_sweep(spec, ProgressPrinter{});
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  print_timing(spec, rows, wall_s);
  std::fflush(stdout);
  print_warnings("sweep", run::sweep_warnings(rows, spec.base));
  std::vector<std::string> pngs;
  const auto problems = run::write_sweep_report(out, spec, rows, wall_s, &pngs);
  commit_out_dir();
  warn_plots_not_written("sweep", problems);
  std::printf("wrote %s/sweep.csv, summary.json and %zu plots\n", o.out_dir.c_str(), pngs.size());
}

}  // namespace
}  // namespace sweep_command

Command add_sweep_command(CLI::App& parent) {
  using namespace sweep_command;
  return make_command(parent, kSweepHelp, add_options, execute);
}

}  // namespace mrd::cli
