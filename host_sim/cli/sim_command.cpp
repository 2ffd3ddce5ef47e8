#include <cstdio>
#include <string>

#include "host_sim/cli/command.hpp"
#include "host_sim/cli/options.hpp"
#include "mrd/units.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/run_outputs.hpp"
#include "host_sim/run/sim_run.hpp"

namespace mrd::cli {
namespace {

constexpr CommandHelp kSimHelp{
    "sim", "Closed-loop earthquake run of the base-isolated building",
    R"(The closed loop: the 6-DOF base-isolated building of Table 6.1 (exact zero-order hold at
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
DIR/timeseries_loop.png (force against stroke).)"};

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

/// The run the options ask for; throws io::UsageError for a bad option.
run::SimSpec sim_spec(const SimOptions& o) {
  check_pga_g(o.pga_g);
  check_idle_years(o.idle_years);
  require_finite_at_least("--duration-s", o.duration_s, 0.0);
  require_step_s(o.step_s, 0.02, "0.02 s");
  run::SimSpec spec;
  spec.record = o.record;
  spec.pga_g = o.pga_g;
  spec.mode = run::parse_control_mode(o.control);
  spec.numeric = run::parse_numeric_kind(o.numeric);
  spec.idle_years = o.idle_years;
  spec.duration_s = o.duration_s;
  spec.step_s = o.step_s;
  spec.seed = o.seed;
  spec.keep_record = !o.out_dir.empty();
  return spec;
}

void print_summary(const run::SimRun& r) {
  if (r.spec.record.empty()) std::printf("no --record given: using %s\n", r.motion.source.c_str());
  const plant::PlantSummary& s = r.summary;
  std::printf("%s, PGA %.4g g (x%.4f), %s (%s core), idle %.4g years (SQ %.3f), %.2f s\n", r.motion.name.c_str(),
              r.motion.pga_m_s2 / units::kStandardGravity_m_s2, r.motion.scale_factor,
              control::mode_name(r.spec.mode), run::numeric_name(r.spec.numeric), r.spec.idle_years, s.sq,
              s.duration_s);
  std::printf("  peak base displacement       %10.4f mm\n", s.peak_base_displacement_m * 1e3);
  std::printf("  peak damper force            %10.3f kN\n", s.peak_damper_force_n / 1e3);
  std::printf("  peak superstructure accel    %10.4f m/s^2\n", s.peak_superstructure_accel_m_s2);
  std::printf("  peak base accel              %10.4f m/s^2\n", s.peak_base_accel_m_s2);
  std::printf("  peak coil current            %10.3f A\n", s.peak_current_a);
}

void add_options(CLI::App& app, SimOptions& o) {
  app.add_option("--record", o.record, "Ground-motion record: CSV (time_s,accel_m_s2) or PEER .AT2");
  add_pga_g_option(app, o.pga_g, "Scale the record to this PGA, g (Table 6.3: 0.1127)");
  app.add_option("--control", o.control, "passive-off | passive-on | semi-active")->capture_default_str();
  app.add_option("--numeric", o.numeric, "Numeric build of the firmware control core: float | fixed")
      ->capture_default_str();
  add_idle_years_option(app, o.idle_years, "Idle time before the earthquake, years");
  app.add_option("--duration-s", o.duration_s, "Simulated time, s (default: the record's length; 40 s synthetic)");
  add_step_s_option(app, o.step_s, "Simulation and control step, s");
  app.add_option("--seed", o.seed, "Seed of the synthetic motion (without --record)")->capture_default_str();
  add_out_option(app, o.out_dir, "Folder for summary.json, timeseries.csv and plots");
}

void execute(const SimOptions& o) {
  const run::SimSpec spec = sim_spec(o);
  const auto controller = run::make_controller(spec.mode, spec.step_s, spec.numeric);
  compute_print_write(
      "sim", o.out_dir, [&] { return run::run_sim(spec, *controller); }, print_summary, run::write_sim_outputs);
}

}  // namespace

Command add_sim_command(CLI::App& parent) {
  return make_command(parent, kSimHelp, add_options, execute);
}

}  // namespace mrd::cli
