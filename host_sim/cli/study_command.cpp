#include <cstdio>
#include <string>

#include "host_sim/cli/building_option.hpp"
#include "host_sim/cli/damper_option.hpp"
#include "host_sim/cli/fluid_option.hpp"
#include "host_sim/cli/command.hpp"
#include "host_sim/cli/options.hpp"
#include "mrd/control/io.hpp"
#include "host_sim/run/study.hpp"

namespace mrd::cli {
namespace study_command {
namespace {

constexpr CommandHelp kStudyHelp{
    "study", "Chapter-6 study: records x modes, fully mixed vs idle, with report",
    R"(The headline study of thesis chapter 6: the four records of Table 6.2 scaled to 0.1127 g
(Table 6.3) in every control mode this build has, fully mixed against 2.5 years idle
(Fig. 6.9-6.11), plus the idle-time sweep of Fig. 6.12-6.20 and the chapter-5 checks it rests on.
Writes DIR/report.md (Markdown with the tables and plots), DIR/summary.json (per record and mode:
peak_base_displacement_m, peak_damper_force_kn, peak_superstructure_accel_m_s2, sq,
peak_isolator_force_kn (0 without isolators) and peak_story_drift_m, fully mixed and idle; building,
dofs), one comparison PNG per record and mode, and DIR/sweep/ (mrd sweep's files).
--building FILE runs the study on another building (README "Your building"; default the thesis
building, buildings/thesis-6dof.toml, whose report is the same bytes with or without the file).
For any other building the report names it, gives its first modes, and its table adds the peak
story drift (and the isolators' peak force when it has isolators); sweep/sweep.csv appends
peak_isolator_force_kn and peak_story_drift_m.
--damper FILE and --fluid FILE run the study with another damper and MR fluid (README "Your damper
and fluid"; defaults dampers/thesis-200kn.toml and fluids/thesis-model-fluid.toml, the same bytes
with or without them): the report names them, its settling time is the fluid's in the damper's
cylinder, and the warnings' limits are the damper's [rating]. The sine tests of Table 5.1 stay the
thesis damper's check against Table 5.2.)"};

struct StudyCliOptions {
  run::StudyOptions study;
  std::string building;
  std::string damper;
  std::string fluid;
  bool no_sweep = false;
  std::string out_dir = "out/study";
};

void print_motion_notice(const run::StudyResult& r) {
  if (r.synthetic_motions) std::printf("shared ground motions not found: the study used synthetic motions\n");
}

void print_table(const run::StudyResult& r) {
  std::printf("%-22s %-12s %28s %26s\n", "record", "control", "peak base disp [mm]", "peak force [kN]");
  for (const auto& row : r.rows) {
    std::printf("%-22s %-12s %12.1f -> %8.1f %14.1f -> %8.1f\n", row.motion.c_str(), control::mode_name(row.mode),
                row.fully_mixed.peak_base_displacement_m * 1e3, row.idle.peak_base_displacement_m * 1e3,
                row.fully_mixed.peak_damper_force_n / 1e3, row.idle.peak_damper_force_n / 1e3);
  }
}

void add_options(CLI::App& app, StudyCliOptions& o) {
  add_pga_g_option(app, o.study.pga_g, "PGA of every record, g");
  add_idle_years_option(app, o.study.idle_years, "Idle time compared with fully mixed, years");
  app.add_flag("--no-sweep", o.no_sweep, "Skip the idle-time sweep");
  add_threads_option(app, o.study.threads, "Worker threads for the sweep (0: all cores)");
  add_building_option(app, o.building);
  add_damper_option(app, o.damper);
  add_fluid_option(app, o.fluid);
  add_out_option(app, o.out_dir, "Output folder")->capture_default_str();
}

void execute(const StudyCliOptions& o) {
  check_pga_g(o.study.pga_g);
  check_idle_years(o.study.idle_years);
  run::StudyOptions study = o.study;
  study.with_sweep = !o.no_sweep;
  study.building = load_building(o.building);
  const DamperAndFluid d = load_damper_and_fluid("study", o.damper, o.fluid);
  study.damper = d.params;
  study.settling = d.settling;
  if (!is_thesis_damper(d)) study.damper_name = d.damper.name;
  if (!is_thesis_settling(d)) study.fluid_name = d.fluid.name;
  const auto out = open_out_dir(o.out_dir);
  const run::StudyResult r = run::run_study(study);
  const auto problems = run::write_study_outputs(out, r);
  commit_out_dir();
  print_motion_notice(r);
  warn_plots_not_written("study", problems);
  print_table(r);
  std::fflush(stdout);
  print_warnings("study", run::study_warnings(r));
  std::printf("wrote %s/report.md\n", o.out_dir.c_str());
}

}  // namespace
}  // namespace study_command

Command add_study_command(CLI::App& parent) {
  using namespace study_command;
  return make_command(parent, kStudyHelp, add_options, execute);
}

}  // namespace mrd::cli
