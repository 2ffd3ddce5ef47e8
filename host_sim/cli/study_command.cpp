#include <cstdio>
#include <memory>
#include <string>

#include "host_sim/cli/command.hpp"
#include "mrd/control/io.hpp"
#include "host_sim/report/output_dir.hpp"
#include "host_sim/run/study.hpp"

namespace mrd::cli {
namespace {

constexpr const char* kStudyHelp = R"(The headline study of thesis chapter 6: the four records of Table 6.2 scaled to 0.1127 g
(Table 6.3) in every control mode this build has, fully mixed against 2.5 years idle
(Fig. 6.9-6.11), plus the idle-time sweep of Fig. 6.12-6.20 and the chapter-5 checks it rests on.
Writes DIR/report.md (Markdown with the tables and plots), DIR/summary.json (per record and mode:
peak_base_displacement_m, peak_damper_force_kn, peak_superstructure_accel_m_s2 and sq, fully mixed
and idle), one comparison PNG per record and mode, and DIR/sweep/.)";

struct StudyCliOptions {
  run::StudyOptions study;
  bool no_sweep = false;
  std::string out_dir = "out/study";
};

}  // namespace

Command add_study_command(CLI::App& parent) {
  auto o = std::make_shared<StudyCliOptions>();
  CLI::App* app = parent.add_subcommand("study", "Chapter-6 study: records x modes, fully mixed vs idle, with report");
  app->add_option("--pga-g", o->study.pga_g, "PGA of every record, g")->capture_default_str();
  app->add_option("--idle-years", o->study.idle_years, "Idle time compared with fully mixed, years")->capture_default_str();
  app->add_flag("--no-sweep", o->no_sweep, "Skip the idle-time sweep");
  app->add_option("--threads", o->study.threads, "Worker threads for the sweep (0: all cores)")->capture_default_str();
  app->add_option("--out", o->out_dir, "Output folder")->capture_default_str();
  app->footer(kStudyHelp);
  return {app, [o] {
            require_positive("--pga-g", o->study.pga_g, "a PGA");
            require_finite_at_least("--idle-years", o->study.idle_years, 0.0);
            o->study.with_sweep = !o->no_sweep;
            const auto r = run::run_study(o->study, o->out_dir);
            if (r.synthetic_motions) std::printf("shared ground motions not found: the study used synthetic motions\n");
            for (const auto& p : r.plot_problems) std::fprintf(stderr, "mrd study: warning: plot not written: %s\n", p.c_str());
            std::printf("%-22s %-12s %28s %26s\n", "record", "control", "peak base disp [mm]", "peak force [kN]");
            for (const auto& row : r.rows) {
              std::printf("%-22s %-12s %12.1f -> %8.1f %14.1f -> %8.1f\n", row.motion.c_str(), control::mode_name(row.mode),
                          row.fully_mixed.peak_base_displacement_m * 1e3, row.idle.peak_base_displacement_m * 1e3,
                          row.fully_mixed.peak_damper_force_n / 1e3, row.idle.peak_damper_force_n / 1e3);
            }
            std::printf("wrote %s/report.md\n", o->out_dir.c_str());
          }};
}

}  // namespace mrd::cli
