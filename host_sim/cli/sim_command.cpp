#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "host_sim/cli/command.hpp"
#include "mrd/units.hpp"
#include "host_sim/report/output_dir.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/motions.hpp"
#include "host_sim/run/run_outputs.hpp"

namespace mrd::cli {
namespace {

constexpr const char* kSimHelp = R"(The closed loop: the 6-DOF base-isolated building of Table 6.1 (exact zero-order hold at
--step-s), the MR damper between ground and base (Bingham + transition, Eq. 4.1-4.4; idle-time
participant ratio, Eq. 5.5-5.12; coil dynamics Eq. 4.5), and the controller.
Without --record the run uses a synthetic Kanai-Tajimi motion and says so.

Fields of DIR/summary.json:
  peak_base_displacement_m        max |base displacement relative to the ground|, m
  peak_damper_force_kn            max |damper force|, kN
  peak_superstructure_accel_m_s2  max |absolute acceleration| over floors 1-5, m/s^2
  peak_base_accel_m_s2            max |absolute acceleration| of the base, m/s^2
  peak_current_a                  max |coil current|, A
  sq, final_participant_ratio     settling quotient at the start (Eq. 5.5), PR at the end (Eq. 5.9)
  record, pga_m_s2, scale_factor, control, numeric, idle_years, duration_s, step_s: the run's inputs
Files: DIR/timeseries.csv (every step; columns name their units), DIR/timeseries_response.png
(displacement, force, floor acceleration, current over time, like Fig. 6.9-6.11) and
DIR/timeseries_loop.png (force against stroke).)";

struct SimOptions {
  std::string record;
  double pga_g = run::kThesisPga_g;
  std::string control = "passive-off";
  std::string numeric = "float";
  double idle_years = 0.0;
  double duration_s = 0.0;
  double step_s = 1.0e-3;
  unsigned seed = 1;
  std::string out_dir;
};

}  // namespace

Command add_sim_command(CLI::App& parent) {
  auto o = std::make_shared<SimOptions>();
  CLI::App* app = parent.add_subcommand("sim", "Closed-loop earthquake run of the base-isolated building");
  app->add_option("--record", o->record, "Ground-motion record: CSV (time_s,accel_m_s2) or PEER .AT2");
  app->add_option("--pga-g", o->pga_g, "Scale the record to this PGA, g (Table 6.3: 0.1127)")->capture_default_str();
  app->add_option("--control", o->control, "passive-off | passive-on | semi-active")->capture_default_str();
  app->add_option("--numeric", o->numeric, "Numeric build of the firmware control core: float | fixed")
      ->capture_default_str();
  app->add_option("--idle-years", o->idle_years, "Idle time before the earthquake, years")->capture_default_str();
  app->add_option("--duration-s", o->duration_s, "Simulated time, s (default: the record's length; 40 s synthetic)");
  app->add_option("--step-s", o->step_s, "Simulation and control step, s")->capture_default_str();
  app->add_option("--seed", o->seed, "Seed of the synthetic motion (without --record)")->capture_default_str();
  app->add_option("--out", o->out_dir, "Folder for summary.json, timeseries.csv and plots");
  app->footer(kSimHelp);
  return {app, [o] {
            require_positive("--pga-g", o->pga_g, "a PGA");
            require_finite_at_least("--idle-years", o->idle_years, 0.0);
            require_finite_at_least("--duration-s", o->duration_s, 0.0);
            require_finite_at_least("--step-s", o->step_s, 1e-6);
            if (o->step_s > 0.02) throw io::UsageError("--step-s: expected at most 0.02 s");
            const control::ControlMode mode = run::parse_control_mode(o->control);
            const run::NumericKind numeric = run::parse_numeric_kind(o->numeric);
            auto controller = run::make_controller(mode, o->step_s, numeric);
            if (!o->out_dir.empty()) report::prepare_output_dir(o->out_dir);

            run::StudyMotion motion;
            if (o->record.empty()) {
              motion = run::synthetic_study_motion(o->seed, o->pga_g, o->step_s,
                                                   o->duration_s > 0.0 ? o->duration_s : 40.0);
              std::printf("no --record given: using %s\n", motion.source.c_str());
            } else {
              motion = run::load_study_motion(o->record, o->pga_g, o->step_s, o->duration_s);
            }

            run::ClosedLoopSpec spec;
            spec.step_s = o->step_s;
            spec.idle_years = o->idle_years;
            run::ClosedLoopRecord rec;
            const bool keep = !o->out_dir.empty();
            const run::ClosedLoopSummary s = run::run_closed_loop(spec, motion.accel_m_s2, *controller, keep ? &rec : nullptr);

            std::printf("%s, PGA %.4g g (x%.4f), %s (%s core), idle %.4g years (SQ %.3f), %.2f s\n",
                        motion.name.c_str(), motion.pga_m_s2 / units::kStandardGravity_m_s2, motion.scale_factor,
                        o->control.c_str(), run::numeric_name(numeric), o->idle_years, s.sq, s.duration_s);
            std::printf("  peak base displacement       %10.4f mm\n", s.peak_base_displacement_m * 1e3);
            std::printf("  peak damper force            %10.3f kN\n", s.peak_damper_force_n / 1e3);
            std::printf("  peak superstructure accel    %10.4f m/s^2\n", s.peak_superstructure_accel_m_s2);
            std::printf("  peak base accel              %10.4f m/s^2\n", s.peak_base_accel_m_s2);
            std::printf("  peak coil current            %10.3f A\n", s.peak_current_a);
            if (!keep) return;
            const std::filesystem::path dir(o->out_dir);
            const auto problems = run::write_closed_loop_outputs(
                dir, "timeseries", motion.name + ", " + o->control + ", idle " + std::to_string(o->idle_years) + " years",
                rec);
            for (const auto& p : problems) std::fprintf(stderr, "mrd sim: warning: plot not written: %s\n", p.c_str());
            const nlohmann::json j{
                {"peak_base_displacement_m", s.peak_base_displacement_m},
                {"peak_damper_force_kn", units::n_to_kn(s.peak_damper_force_n)},
                {"peak_superstructure_accel_m_s2", s.peak_superstructure_accel_m_s2},
                {"peak_base_accel_m_s2", s.peak_base_accel_m_s2},
                {"peak_current_a", s.peak_current_a},
                {"sq", s.sq},
                {"final_participant_ratio", s.final_participant_ratio},
                {"record", motion.source},
                {"synthetic_motion", motion.synthetic},
                {"pga_m_s2", motion.pga_m_s2},
                {"scale_factor", motion.scale_factor},
                {"control", o->control},
                {"numeric", run::numeric_name(numeric)},
                {"idle_years", o->idle_years},
                {"duration_s", s.duration_s},
                {"step_s", o->step_s},
            };
            report::write_file_atomically(dir / "summary.json", j.dump(2) + "\n");
            std::printf("wrote %s\n", (dir / "summary.json").c_str());
          }};
}

}  // namespace mrd::cli
