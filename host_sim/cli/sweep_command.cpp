#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "host_sim/cli/command.hpp"
#include "host_sim/report/output_dir.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/sweep.hpp"
#include "host_sim/run/sweep_report.hpp"

namespace mrd::cli {
namespace {

constexpr const char* kSweepHelp = R"(Runs every record x control mode x idle time in closed loop on all cores (thesis §6.5) and
writes DIR/sweep.csv (one row per run: record, control, idle_years, sq, peak_base_displacement_m,
peak_damper_force_kn, peak_superstructure_accel_m_s2, peak_base_accel_m_s2, peak_current_a,
final_participant_ratio) and, per control mode, the plots of Fig. 6.12-6.20 (peak base
displacement, damper force and superstructure acceleration against idle time), plus
DIR/summary.json (runs, wall time, simulated seconds per wall second, files).
Defaults: the four records of Table 6.2 from the shared data folder at 0.1127 g (Table 6.3), every
control mode this build has, idle 0 to 1 year every 0.05 year. Past the maximum settling time
(0.853 years, Eq. 5.4) SQ saturates and the curves flatten.)";

struct SweepOptions {
  std::vector<std::string> records;
  double pga_g = run::kThesisPga_g;
  std::vector<std::string> controls;
  double idle_from = 0.0;
  double idle_to = 1.0;
  double idle_step = 0.05;
  double step_s = 1.0e-3;
  unsigned threads = 0;
  std::string out_dir = "out/sweep";
};

}  // namespace

Command add_sweep_command(CLI::App& parent) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* app = parent.add_subcommand("sweep", "Idle-time sweep: records x control modes x idle times");
  app->add_option("--record", o->records, "Ground-motion record(s) (default: the four of Table 6.2)");
  app->add_option("--pga-g", o->pga_g, "PGA every record is scaled to, g")->capture_default_str();
  app->add_option("--control", o->controls, "Control mode(s) (default: all this build has)");
  app->add_option("--idle-from", o->idle_from, "First idle time, years")->capture_default_str();
  app->add_option("--idle-to", o->idle_to, "Last idle time, years")->capture_default_str();
  app->add_option("--idle-step", o->idle_step, "Idle-time step, years")->capture_default_str();
  app->add_option("--step-s", o->step_s, "Simulation step, s")->capture_default_str();
  app->add_option("--threads", o->threads, "Worker threads (0: all cores)")->capture_default_str();
  app->add_option("--out", o->out_dir, "Output folder")->capture_default_str();
  app->footer(kSweepHelp);
  return {app, [o] {
            require_positive("--pga-g", o->pga_g, "a PGA");
            require_finite_at_least("--idle-from", o->idle_from, 0.0);
            require_finite_at_least("--idle-to", o->idle_to, o->idle_from);
            require_finite_at_least("--idle-step", o->idle_step, 1e-6);
            require_finite_at_least("--step-s", o->step_s, 1e-6);
            if (o->step_s > 0.02) throw io::UsageError("--step-s: expected at most 0.02 s");

            run::SweepSpec spec;
            spec.base.step_s = o->step_s;
            spec.threads = o->threads;
            spec.idle_years = run::idle_grid(o->idle_from, o->idle_to, o->idle_step);
            if (o->controls.empty()) {
              spec.modes = run::available_modes();
            } else {
              for (const auto& c : o->controls) spec.modes.push_back(run::parse_control_mode(c));
            }
            report::prepare_output_dir(o->out_dir);
            if (o->records.empty()) {
              spec.motions = run::thesis_study_motions(o->pga_g, o->step_s);
              if (spec.motions.front().synthetic) {
                std::printf("shared ground motions not found: sweeping four synthetic motions instead\n");
              }
            } else {
              for (const auto& r : o->records) spec.motions.push_back(run::load_study_motion(r, o->pga_g, o->step_s));
            }

            const bool tty = ::isatty(STDERR_FILENO) != 0;
            std::size_t last_decile = 0;
            const auto t0 = std::chrono::steady_clock::now();
            const auto rows = run::run_sweep(spec, [&](std::size_t done, std::size_t total) {
              if (tty) {
                std::fprintf(stderr, "\rsweep: %zu/%zu runs", done, total);
                if (done == total) std::fprintf(stderr, "\n");
              } else if (done * 10 / total > last_decile || done == total) {
                last_decile = done * 10 / total;
                std::fprintf(stderr, "sweep: %zu/%zu runs\n", done, total);
              }
            });
            const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            double simulated_s = 0.0;
            for (const auto& r : rows) simulated_s += r.summary.duration_s;
            std::printf("sweep: %zu runs, %.1f s simulated in %.2f s wall (%.0fx real time on %u threads)\n",
                        rows.size(), simulated_s, wall_s, simulated_s / wall_s,
                        spec.threads ? spec.threads : std::thread::hardware_concurrency());

            std::vector<std::string> pngs;
            const auto problems = run::write_sweep_outputs(o->out_dir, spec, rows, &pngs);
            for (const auto& p : problems) std::fprintf(stderr, "mrd sweep: warning: plot not written: %s\n", p.c_str());
            nlohmann::json motions = nlohmann::json::array();
            for (const auto& m : spec.motions) {
              motions.push_back({{"name", m.name}, {"source", m.source}, {"synthetic", m.synthetic},
                                 {"scale_factor", m.scale_factor}, {"pga_m_s2", m.pga_m_s2}});
            }
            nlohmann::json modes = nlohmann::json::array();
            for (auto m : spec.modes) modes.push_back(control::mode_name(m));
            const nlohmann::json j{{"runs", rows.size()},      {"wall_time_s", wall_s},
                                   {"simulated_s", simulated_s}, {"real_time_factor", simulated_s / wall_s},
                                   {"motions", motions},        {"controls", modes},
                                   {"idle_years", spec.idle_years}, {"csv", "sweep.csv"},
                                   {"plots", pngs}};
            report::write_file_atomically(std::filesystem::path(o->out_dir) / "summary.json", j.dump(2) + "\n");
            std::printf("wrote %s/sweep.csv, summary.json and %zu plots\n", o->out_dir.c_str(), pngs.size());
          }};
}

}  // namespace mrd::cli
