#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "host_sim/cli/building_option.hpp"
#include "host_sim/cli/command.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/rths/benchmark.hpp"
#include "host_sim/rths/rths_outputs.hpp"
#include "host_sim/rths/rths_run.hpp"

namespace mrd::cli {
namespace rths_command {
namespace {

constexpr CommandHelp kRthsHelp{
    "rths", "Real-time hybrid simulation, emulated: the virtual RTHS benchmark (Silva et al. 2020) or your building",
    R"(Each loop tick: the laboratory's sensors are read (displacement, force), the numerical
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
reference_floor_i_m; at most 1 kHz), coefficients.csv, tracking.png, floors.png.)"};

struct RthsOptions {
  std::string building;
  int benchmark_case = 1;
  std::string record;
  double scale = rths::kBenchmarkRecordScale;
  double rate_hz = 4096.0;
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
};

void add_options(CLI::App& app, RthsOptions& o) {
  add_out_option(app, o.out_dir, "Folder for summary.json, CSV and PNG (created if missing)")->required();
  app.add_option("--building", o.building,
                 "Building file (TOML; full matrices allowed, README \"Your building\"); default: the benchmark's "
                 "3-storey reference structure of --case");
  o.case_option = app.add_option("--case", o.benchmark_case,
                                 "Benchmark structure case 1-4: 1000 kg per floor at 5 %, 1100 kg at 4 %, 1300 kg "
                                 "at 3 %, 1000 kg at 3 % (without --building)")
                      ->capture_default_str();
  app.add_option("--record", o.record, "Ground-motion record: CSV (time_s,accel_m_s2) or PEER .AT2")->required();
  app.add_option("--scale", o.scale, "Factor on the record's accelerations (the benchmark's 0.4), > 0, <= 100")
      ->capture_default_str();
  app.add_option("--rate-hz", o.rate_hz, "Loop rate, Hz, 100-100000 (the benchmark's 4096; a board's 1000)")
      ->capture_default_str();
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
}

rths::CompensatorKind checked_compensator(const std::string& name) {
  rths::CompensatorKind k{};
  if (!rths::compensator_from_name(name, k))
    throw io::UsageError("--compensator: expected none, sample, polynomial, adaptive or model, got '" + name + "'");
  return k;
}

void execute(const RthsOptions& o) {
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

}  // namespace
}  // namespace rths_command

Command add_rths_command(CLI::App& parent) {
  using namespace rths_command;
  return make_command(parent, kRthsHelp, add_options, execute);
}

}  // namespace mrd::cli
