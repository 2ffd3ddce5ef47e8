#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "host_sim/cli/building_option.hpp"
#include "host_sim/cli/command.hpp"
#include "host_sim/cli/damper_option.hpp"
#include "host_sim/cli/fluid_option.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/rths/benchmark.hpp"
#include "host_sim/rths/damper_rths_outputs.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/motions.hpp"
#include "mrd/units.hpp"
#include "host_sim/rths/rths_outputs.hpp"
#include "host_sim/rths/rths_run.hpp"

namespace mrd::cli {
namespace rths_command {
namespace {

constexpr CommandHelp kRthsHelp{
    "rths", "Real-time hybrid simulation, emulated: the virtual RTHS benchmark (Silva et al. 2020) or the thesis's "
            "set-up (--specimen damper)",
    R"(--specimen benchmark (default): the virtual RTHS benchmark. Each loop tick: the laboratory's sensors are read (displacement, force), the numerical
substructure (the building without the specimen's mass, damping and stiffness at --specimen-dof,
integrated by the explicit Chen-Ricles algorithm with the measured force as input) gives the next
target displacement, the compensator turns it into the actuator's command, and the laboratory
(the benchmark's control plant G, exact zero-order hold at the loop rate; +-3.8 V 18-bit
converters; white sensor noise of the published powers, variance = power x rate) follows it.
The all-numerical reference (the specimen numerical, exact ZOH) is run beside it.

Compensators: none; sample (phase lead (50.8316 s + 8570.397)/(s + 8570.397) on the target, PI
Kp = 2, Ki = 95 on the tracking error); polynomial (Horiuchi: 3rd-order extrapolation over the
identified plant's delay); adaptive (Chae et al. 2013: a0 x + a1 x' + a2 x'', windowed least
squares, rate-limited and bounded); model (1/G's expansion c0 + c1 s + c2 s^2 + c3 s^3 of the
identified plant, c0..c2 adapted by a normalized gradient).

Fields of DIR/summary.json:
  status                   ok, force_limit, tracking_limit (the laboratory stopped and held its
                           command; the run still ends and is written), not_finite, unstable
  criteria.j1_lag_s        lag at the peak of the cross-correlation of measured and target, s
  criteria.j2/j3_*_pct     normalized RMS / peak tracking error, %
  criteria.j4..j9_*_pct    normalized RMS / peak error of floors 1, 2, 3 against the reference, %
  peak_force_n, force_limit_n, force_limit_exceeded   the actuator's force, N
  plant, laboratory        the values used (a drawn plant with its seed)
  coefficient_names, final_coefficients   the compensator's coefficients (over time in
                           coefficients.csv, every 10 ms)
Files: tracking.csv (time_s, target_m, measured_m, command_m, force_n, floor_i_m,
reference_floor_i_m; at most 1 kHz), coefficients.csv, tracking.png, floors.png.

--specimen damper: the thesis's own set-up (Sec. 3.3, 6.4). The building (the thesis's 6-DOF
building, or --building FILE with one damper placement) is numerical, stepped as mrd sim steps it
(exact zero-order hold at the loop rate, --rate-hz, default 1000; isolators in sub-steps); the MR
damper (--damper, --fluid, --idle-years as in mrd sim) is the physical specimen behind a
servo-hydraulic actuator: a pure delay of --delay-ms (whole loop steps) and a first-order servo
lag of --lag-ms; the controller (--control, the firmware control core as in mrd sim) senses the
actuator's stroke and the measured force. --compensate model: each command is the numerical
building's own prediction over the delay (its exact steps under the record's future ground
acceleration, the damper's force from a model of the specimen driven by the measured stroke and
rate) through the lag's inverse; none: the target itself. The all-numerical closed loop (what
mrd sim runs with the same building, damper, fluid, record, PGA, control and idle time) is run
beside it. The record is scaled to --pga-g as in mrd sim.
Fields of DIR/summary.json:
  status                   ok, or unstable when the RTHS diverged (its peak base displacement
                           above twice the closed loop's, or not finite: null); the run still
                           ends and is written
  warnings                 sentences: the run diverged, or its peak base displacement is more than
                           2 % off the closed loop's; also printed on stderr
  peak_base_displacement_m.rths, .closed_loop, .gap_pct   max |x_0| of both, m; gap
                           100 (rths - closed_loop) / closed_loop, %
  peak_damper_force_n.rths, .closed_loop                 max |force of one damper|, N
  tracking.rms_error_pct   100 rms(actuator - target) / rms(target), the damper's stroke
  tracking.peak_error_m    max |actuator - target|, m
  tracking.rms_velocity_error_pct   the same for the stroke's rate
  building, damper, fluid, record, pga_g, control, idle_years, rate_hz, delay_s, lag_s,
  compensation             the run's inputs
Files: tracking.csv (time_s, target_m, actuator_m, actuator_velocity_m_s, command_m, force_n,
current_a, base_displacement_m, closed_loop_base_displacement_m, closed_loop_force_n; every
tick), tracking.png, base.png.)"};

struct RthsOptions {
  std::string specimen = "benchmark";
  std::string building;
  int benchmark_case = 1;
  std::string record;
  double scale = rths::kBenchmarkRecordScale;
  double rate_hz = 4096.0;
  CLI::Option* rate_option = nullptr;
  std::string compensator = "adaptive";
  int specimen_dof = 1;
  double force_limit_kn = 8.9;
  double tracking_limit_mm = 10.0;
  std::uint64_t plant_seed = 0;
  std::uint64_t noise_seed = 1;
  CLI::Option* plant_seed_option = nullptr;
  CLI::Option* case_option = nullptr;
  double duration_s = 0.0;
  CLI::Option* duration_option = nullptr;
  std::string out_dir;
  // --specimen damper
  std::string control = "semi-active";
  std::string damper;
  std::string fluid;
  double idle_years = 0.0;
  double pga_g = run::kThesisPga_g;
  double delay_ms = 15.0;
  double lag_ms = 2.0;
  std::string compensate = "model";
  /// The options of one specimen only, refused with the other.
  std::vector<CLI::Option*> benchmark_only, damper_only;
};

void add_options(CLI::App& app, RthsOptions& o) {
  add_out_option(app, o.out_dir, "Folder for summary.json, CSV and PNG (created if missing)")->required();
  app.add_option("--specimen", o.specimen,
                 "benchmark: the virtual RTHS benchmark (Silva et al. 2020); damper: the thesis's set-up, the MR "
                 "damper physical behind an actuator, the building numerical")
      ->capture_default_str();
  app.add_option("--building", o.building,
                 "Building file (TOML; full matrices allowed, README \"Your building\"); default: the benchmark's "
                 "3-storey reference structure of --case, with --specimen damper the thesis building");
  o.case_option = app.add_option("--case", o.benchmark_case,
                                 "Benchmark structure case 1-4: 1000 kg per floor at 5 %, 1100 kg at 4 %, 1300 kg "
                                 "at 3 %, 1000 kg at 3 % (without --building)")
                      ->capture_default_str();
  app.add_option("--record", o.record, "Ground-motion record: CSV (time_s,accel_m_s2) or PEER .AT2")->required();
  app.add_option("--scale", o.scale, "Factor on the record's accelerations (the benchmark's 0.4), > 0, <= 100")
      ->capture_default_str();
  o.rate_option = app.add_option(
      "--rate-hz", o.rate_hz,
      "Loop rate, Hz, 100-100000 (default: the benchmark's 4096; with --specimen damper 1000, a period of whole "
      "microseconds)");
  app.add_option("--compensator", o.compensator, "none, sample, polynomial, adaptive or model")
      ->capture_default_str();
  app.add_option("--specimen-dof", o.specimen_dof, "The specimen's DOF, 1-based (the benchmark's 1)")
      ->capture_default_str();
  app.add_option("--force-limit-kn", o.force_limit_kn,
                 "The actuator's force limit, kN: beyond it the laboratory stops and holds (the benchmark's 8.9)")
      ->capture_default_str();
  app.add_option("--tracking-limit-mm", o.tracking_limit_mm,
                 "Stop when |measured - target| exceeds it, mm, > 0")
      ->capture_default_str();
  o.plant_seed_option =
      add_seed_option(app, o.plant_seed, "Draw the laboratory's plant from the published uncertainty with this seed "
                                         "(default: the nominal plant)", "--plant-seed");
  add_seed_option(app, o.noise_seed, "Seed of the sensor noise", "--noise-seed");
  o.duration_option = app.add_option("--duration-s", o.duration_s, "Simulated time, s, > 0 (default: the record's)");
  for (const char* name : {"--case", "--scale", "--compensator", "--specimen-dof", "--force-limit-kn",
                           "--tracking-limit-mm", "--plant-seed", "--noise-seed"})
    o.benchmark_only.push_back(app.get_option(name));

  o.damper_only.push_back(
      app.add_option("--control", o.control, "--specimen damper: passive-off | passive-on | semi-active")
          ->capture_default_str());
  add_damper_option(app, o.damper);
  o.damper_only.push_back(app.get_option("--damper"));
  add_fluid_option(app, o.fluid);
  o.damper_only.push_back(app.get_option("--fluid"));
  add_idle_years_option(app, o.idle_years, "--specimen damper: idle time before the earthquake, years");
  o.damper_only.push_back(app.get_option("--idle-years"));
  add_pga_g_option(app, o.pga_g, "--specimen damper: scale the record to this PGA, g (Table 6.3: 0.1127)");
  o.damper_only.push_back(app.get_option("--pga-g"));
  o.damper_only.push_back(app.add_option("--delay-ms", o.delay_ms,
                                         "--specimen damper: the actuator's pure delay, ms, 0-1000, whole loop steps "
                                         "(the thesis's 10-20)")
                              ->capture_default_str());
  o.damper_only.push_back(
      app.add_option("--lag-ms", o.lag_ms, "--specimen damper: the actuator's first-order servo lag, ms, 0-1000")
          ->capture_default_str());
  o.damper_only.push_back(app.add_option("--compensate", o.compensate,
                                         "--specimen damper: model (the numerical building's prediction over the "
                                         "delay, the lag's inverse) or none")
                              ->capture_default_str());
}

/// Refuses, with "<option>: only with --specimen <other>", an option given
/// that belongs to the other specimen.
void refuse_other_specimens_options(const std::vector<CLI::Option*>& others, const char* other) {
  for (const CLI::Option* opt : others) {
    if (opt != nullptr && opt->count() > 0)
      throw io::UsageError(opt->get_name() + ": only with --specimen " + other);
  }
}

rths::CompensatorKind checked_compensator(const std::string& name) {
  rths::CompensatorKind k{};
  if (!rths::compensator_from_name(name, k))
    throw io::UsageError("--compensator: expected none, sample, polynomial, adaptive or model, got '" + name + "'");
  return k;
}

void execute_benchmark(const RthsOptions& o) {
  refuse_other_specimens_options(o.damper_only, "damper");
  require_positive("--scale", o.scale, "a record scale");
  require_at_most("--scale", o.scale, 100.0, "100");
  require_finite_at_least("--rate-hz", o.rate_hz, 100.0);
  require_at_most("--rate-hz", o.rate_hz, 1e5, "100000 Hz");
  require_positive("--force-limit-kn", o.force_limit_kn, "a force limit");
  require_at_most("--force-limit-kn", o.force_limit_kn, 1e5, "100000 kN");
  require_positive("--tracking-limit-mm", o.tracking_limit_mm, "a tracking limit");
  require_at_most("--tracking-limit-mm", o.tracking_limit_mm, 1e4, "10000 mm");
  if (o.duration_option->count() > 0) {
    require_positive("--duration-s", o.duration_s, "a duration");
    require_at_most("--duration-s", o.duration_s, kMaxDuration_s, "100000 s");
  }
  if (!o.building.empty() && o.case_option->count() > 0)
    throw io::UsageError("--case: not allowed with --building (the cases are the benchmark structure's)");
  if (o.benchmark_case < 1 || o.benchmark_case > 4)
    throw io::UsageError("--case: expected 1, 2, 3 or 4, got " + std::to_string(o.benchmark_case));
  const rths::CompensatorKind kind = checked_compensator(o.compensator);

  const structure::BuildingParams building =
      o.building.empty() ? rths::benchmark_structure(o.benchmark_case) : load_building(o.building);
  if (o.specimen_dof < 1 || o.specimen_dof > building.dofs())
    throw io::UsageError("--specimen-dof: expected 1.." + std::to_string(building.dofs()) + " (the building's DOFs), got " +
                         std::to_string(o.specimen_dof));

  rths::RthsSpec spec;
  spec.building = rths::structure_matrices(building);
  spec.specimen_dof = o.specimen_dof - 1;
  if (!(spec.building.m(spec.specimen_dof, spec.specimen_dof) > spec.plant.specimen.mass_kg))
    throw io::UsageError("--specimen-dof: DOF " + std::to_string(o.specimen_dof) + "'s mass is not more than the "
                         "specimen's 29.13 kg");
  rths::RthsDescription d;
  d.building = building.name;
  d.record = o.record;
  d.record_scale = o.scale;
  if (o.plant_seed_option->count() > 0) {
    std::mt19937_64 rng(o.plant_seed);
    spec.plant = rths::draw_lab_plant(rths::LabPlantParams{}, rths::LabPlantUncertainty{}, rng);
    d.plant_drawn = true;
    d.plant_seed = o.plant_seed;
  }
  spec.identified_plant = rths::LabPlantParams{};
  spec.lab.force_limit_n = o.force_limit_kn * 1e3;
  spec.lab.tracking_limit_m = o.tracking_limit_mm * 1e-3;
  spec.lab.noise_seed = o.noise_seed;
  spec.compensator.kind = kind;
  spec.rate_hz = o.rate_hz;
  spec.keep_every = static_cast<int>(std::ceil(o.rate_hz / 1000.0 - 1e-9));
  spec.ground_accel_m_s2 = rths::benchmark_record(o.record, o.scale, o.rate_hz);
  if (o.duration_option->count() > 0)
    spec.ground_accel_m_s2.resize(static_cast<std::size_t>(std::floor(o.duration_s * o.rate_hz)) + 1, 0.0);

  const auto out = open_out_dir(o.out_dir);
  const rths::RthsResult r = rths::run_rths(spec);
  const auto& j = r.criteria.j;
  std::printf("RTHS of %s under %s x %g at %g Hz, %s compensation: %s\n", d.building.c_str(), o.record.c_str(),
              o.scale, o.rate_hz, rths::compensator_name(kind), r.status.c_str());
  std::printf("  J1 %.2f ms  J2 %.2f %%  J3 %.2f %%  J4 %.2f %%  J5 %.2f %%  J6 %.2f %%  J7 %.2f %%  J8 %.2f %%  J9 %.2f %%\n",
              1e3 * j[0], j[1], j[2], j[3], j[4], j[5], j[6], j[7], j[8]);
  std::printf("  peak actuator force %.0f N (limit %.0f N)\n", r.peak_force_n, spec.lab.force_limit_n);
  if (r.status != "ok")
    std::fprintf(stderr, "mrd rths: warning: the laboratory stopped (%s); the actuator held its command from then on\n",
                 r.status.c_str());
  warn_plots_not_written("rths", rths::write_rths_outputs(out, spec, d, r));
  commit_out_dir();
  std::printf("wrote %s\n", (std::filesystem::path(o.out_dir) / "summary.json").c_str());
}

/// The thesis's set-up, `--specimen damper`: the checks of its options, the
/// RTHS and the all-numerical closed loop beside it, the outputs.
void execute_damper(const RthsOptions& o) {
  refuse_other_specimens_options(o.benchmark_only, "benchmark");
  const double rate_hz = o.rate_option->count() > 0 ? o.rate_hz : 1000.0;
  require_finite_at_least("--rate-hz", rate_hz, 100.0);
  require_at_most("--rate-hz", rate_hz, 1e5, "100000 Hz");
  const double period_us = 1e6 / rate_hz;
  if (std::fabs(period_us - std::round(period_us)) > 1e-9 * period_us)
    throw io::UsageError("--rate-hz: with --specimen damper the period must be a whole number of microseconds (the "
                         "control core's), got " + io::format_number("%g", rate_hz) + " Hz (" +
                         io::format_number("%.6g", period_us) + " us)");
  const double step_s = std::round(period_us) * 1e-6;
  require_finite_at_least("--delay-ms", o.delay_ms, 0.0);
  require_at_most("--delay-ms", o.delay_ms, 1000.0, "1000 ms");
  const double delay_steps = o.delay_ms * 1e-3 / step_s;
  if (std::fabs(delay_steps - std::round(delay_steps)) > 1e-6 * std::max(1.0, delay_steps))
    throw io::UsageError("--delay-ms: expected a whole number of loop steps (" + io::format_number("%g", 1e3 * step_s) +
                         " ms at " + io::format_number("%g", rate_hz) + " Hz), got " +
                         io::format_number("%g", o.delay_ms));
  require_finite_at_least("--lag-ms", o.lag_ms, 0.0);
  require_at_most("--lag-ms", o.lag_ms, 1000.0, "1000 ms");
  require_choice("--compensate", o.compensate, {"model", "none"});
  check_idle_years(o.idle_years);
  check_pga_g(o.pga_g);
  if (o.duration_option->count() > 0) {
    require_positive("--duration-s", o.duration_s, "a duration");
    require_at_most("--duration-s", o.duration_s, kMaxDuration_s, "100000 s");
  }
  const control::ControlMode mode = run::parse_control_mode(o.control);

  rths::DamperRthsSpec spec;
  spec.plant.step_s = step_s;
  spec.plant.idle_time_s = units::years_to_s(o.idle_years);
  spec.plant.building = load_building(o.building);
  const std::string building_label = o.building.empty() ? "the thesis building" : io::file_label(o.building);
  if (spec.plant.building.dampers.size() != 1)
    throw io::UsageError("--building: " + building_label + " has " +
                         std::to_string(spec.plant.building.dampers.size()) +
                         " damper placements; the RTHS puts one placement (any count) behind the actuator");
  const DamperAndFluid df = load_damper_and_fluid("rths", o.damper, o.fluid);
  spec.plant.damper = df.params;
  spec.plant.settling = df.settling;
  spec.delay_s = std::round(delay_steps) * step_s;
  spec.lag_s = o.lag_ms * 1e-3;
  spec.compensate = o.compensate == "model";
  const run::StudyMotion motion =
      run::load_study_motion(o.record, o.pga_g, step_s, o.duration_option->count() > 0 ? o.duration_s : 0.0);
  const auto controller = [&] {
    try {
      return run::make_controller(mode, step_s);
    } catch (const io::UsageError& e) {
      throw io::UsageError(std::string("--rate-hz: the control core refuses the period: ") + e.what());
    }
  };

  rths::DamperRthsDescription d;
  d.building = spec.plant.building.name;
  d.dofs = spec.plant.building.dofs();
  d.damper = o.damper.empty() ? "thesis-200kn" : io::file_label(o.damper);
  d.fluid = o.fluid.empty() ? "thesis-model-fluid" : io::file_label(o.fluid);
  d.record = o.record;
  d.pga_g = motion.pga_m_s2 / units::kStandardGravity_m_s2;
  d.scale_factor = motion.scale_factor;
  d.control = control::mode_name(mode);
  d.idle_years = o.idle_years;
  d.duration_s = static_cast<double>(motion.accel_m_s2.size()) * step_s;

  const auto out = open_out_dir(o.out_dir);
  rths::DamperRthsOutcome r;
  r.rths = rths::run_damper_rths(spec, motion.accel_m_s2, *controller(), &r.record);
  r.closed_loop = run::run_closed_loop(spec.plant, motion.accel_m_s2, *controller(), &r.closed_loop_record);
  std::printf("RTHS of %s with the damper behind a %g ms delay and %g ms lag, %s compensation, %s, under %s at %.4g g, "
              "%g Hz: %s\n",
              d.building.c_str(), 1e3 * spec.delay_s, 1e3 * spec.lag_s, o.compensate.c_str(), d.control.c_str(),
              o.record.c_str(), d.pga_g, rate_hz, r.status().c_str());
  std::printf("  peak base displacement  RTHS %.6g mm, closed loop %.6g mm, gap %+.4g %%\n",
              1e3 * r.rths.peak_base_displacement_m, 1e3 * r.closed_loop.peak_base_displacement_m, r.gap_pct());
  std::printf("  tracking                rms %.4g %% (rate %.4g %%), peak %.4g mm\n", r.rths.rms_tracking_error_pct,
              r.rths.rms_velocity_error_pct, 1e3 * r.rths.peak_tracking_error_m);
  std::printf("  peak damper force       RTHS %.6g kN, closed loop %.6g kN\n", 1e-3 * r.rths.peak_damper_force_n,
              1e-3 * r.closed_loop.peak_damper_force_n);
  print_warnings("rths", rths::damper_rths_warnings(spec, r));
  warn_plots_not_written("rths", rths::write_damper_rths_outputs(out, spec, d, r));
  commit_out_dir();
  std::printf("wrote %s\n", (std::filesystem::path(o.out_dir) / "summary.json").c_str());
}

void execute(const RthsOptions& o) {
  require_choice("--specimen", o.specimen, {"benchmark", "damper"});
  if (o.specimen == "damper")
    execute_damper(o);
  else
    execute_benchmark(o);
}

}  // namespace
}  // namespace rths_command

Command add_rths_command(CLI::App& parent) {
  using namespace rths_command;
  return make_command(parent, kRthsHelp, add_options, execute);
}

}  // namespace mrd::cli
