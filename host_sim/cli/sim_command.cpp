#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>

#include <memory>
#include <optional>
#include <utility>

#include "firmware/app/board_config.hpp"
#include "host_sim/cli/building_option.hpp"
#include "host_sim/cli/command.hpp"
#include "host_sim/cli/damper_option.hpp"
#include "host_sim/cli/fluid_option.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/io/text.hpp"
#include "mrd/units.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/wire_controller.hpp"
#include "host_sim/run/run_outputs.hpp"
#include "host_sim/run/sim_run.hpp"

namespace mrd::cli {
namespace sim_command {
namespace {

constexpr CommandHelp kSimHelp{
    "sim", "Closed-loop earthquake run of the building (the thesis's or --building FILE)",
    R"(The closed loop: the building, by default the 6-DOF base-isolated building of Table 6.1, or
--building FILE (any shear building, isolated on lead-rubber or friction-pendulum bearings or
fixed-base, dampers on chosen elements; README "Your building"), stepped by the exact zero-order
hold at --step-s (an isolated building's bearings in sub-steps, structural_substeps); the MR
damper(s) (Bingham + transition, Eq. 4.1-4.4; idle-time participant ratio, Eq. 5.5-5.12; coil
dynamics Eq. 4.5), and the controller, which senses the first damper.
Without --record the run uses a synthetic Kanai-Tajimi motion and says so; --record none runs
without ground motion (zero acceleration) for --duration-s.

--plant thesis (default): ideal sensors and drive, the coil current follows Eq. 4.5.
--plant hardware: the rig of Sec. 3.2: PWM drive on a 72 V bus (PI current loop, 30 A peak,
15 A continuous by I^2t, +-10 V command at 1 V/A), coil 4.8 ohm with L 5.0 H at 1 A and 3.0 H at
2 A, the field lagging the coil current by Eq. 4.5's slow branch; LVDT (+-0.2921 m, 16 bit,
2 um RMS), load cell (+-250 kN, 16 bit, 250 N RMS) and coil-current sensor (+-15 A, 12 bit,
5 mA RMS), noise seeded by --sensor-seed; the damper parked --offset-mm off its stroke centre
(the LVDT reads it; the building is at rest). See host_sim/plant/README.md.

--damper FILE runs another damper (its force law, current laws, coil, participant ratio, rating and
cylinder; README "Your damper and fluid"; default dampers/thesis-200kn.toml), --fluid FILE another
MR fluid (Table 5.3's quantities or a measured maximum settling time, Table 5.6's coefficients;
default fluids/thesis-model-fluid.toml); with the default files the outputs are the same bytes as
without them. The warnings' limits are the damper's [rating]; the hardware plant's coil is the
damper file's resistance_ohm, inductance_1a_h and inductance_2a_h when it has them (else Table
3.1's). The controller is the thesis's (fw::ControllerConfig) unless --board FILE gives a board
file: then the run is that board's configuration, as mrd-firmware runs it (its [controller] at its
[control] period, mode and numeric build, its [damper] and [fluid], the controller's inputs and
command quantized as the board's CAN frames carry them; `mrd configure` writes such a file); --control still picks the mode when given, and --step-s, --numeric, --damper and --fluid
are refused with it (the board file decides them).

Fields of DIR/summary.json:
  peak_base_displacement_m        max |base (DOF 0) displacement relative to the ground|, m
  peak_damper_force_kn            max |force of one damper (the first)|, kN
  peak_superstructure_accel_m_s2  max |absolute acceleration| over DOFs 1..N-1 (thesis: floors 1-5;
                                  a fixed base: every DOF), m/s^2
  peak_base_accel_m_s2            max |absolute acceleration| of the base (DOF 0), m/s^2
  peak_isolator_force_kn          max |sum of the isolators' forces, counts included|, kN (0 without)
  peak_story_drift_m              max |story deformation| over elements 1..N-1 (fixed base: all), m
  peak_damper_stroke_m            max |deformation of the first damper's element|, m
  building, dofs, structural_substeps  the building's name, its DOFs, sub-steps per step
  peak_current_a                  max |coil current|, A
  sq, final_participant_ratio     settling quotient at the start (Eq. 5.5), PR at the end (Eq. 5.9)
  record, pga_m_s2, scale_factor, control, numeric, idle_years, duration_s, step_s: the run's inputs
  plant                           thesis | hardware
  sensor_seed                     --sensor-seed of the hardware plant's sensor noise (null for thesis)
  parking_offset_m                --offset-mm in m: where the hardware plant's damper was parked off
                                  its stroke centre (null for thesis: ideal sensors, damper centred)
  peak_coil_current_a             max |coil current| over the ticks, A
  rms_coil_current_a              RMS coil current over the ticks, A
  time_above_rated_s              time with |coil current| above the rated 2.5 A, s
  command_changes_per_s           changes of the current command between consecutive ticks, per s of run
  peak_coil_temperature_rise_k    max coil temperature above ambient, K (i^2 R into a first-order
                                  thermal model: 2 K/W, 20 min; both plants)
  peak_damper_velocity_m_s        max |base velocity relative to the ground|, m/s
  warnings                        sentences, one per limit of the model the run exceeds: stroke
                                  +-0.2921 m and velocity 0.2491 m/s (Table 3.1), current 0-2.5 A
                                  (Table 4.1), force 200 kN; also printed on stderr
Files: DIR/timeseries.csv (every step; columns name their units), DIR/timeseries_response.png
(displacement, force, floor acceleration, current over time, like Fig. 6.9-6.11) and
DIR/timeseries_loop.png (force against stroke).)"};

struct SimOptions {
  std::string record;
  double pga_g = run::kThesisPga_g;
  std::string control = "passive-off";
  bool control_given = false;
  std::string numeric = "float";
  bool numeric_given = false;
  bool step_given = false;
  std::string board;
  double idle_years = 0.0;
  double duration_s = 0.0;
  bool duration_given = false;  ///< --duration-s was given (without it: the record's length)
  double step_s = 1.0e-3;
  std::uint64_t seed = 1;
  std::string plant = "thesis";
  std::uint64_t sensor_seed = 1;
  double offset_mm = 3.0;
  std::string building;
  std::string damper;
  std::string fluid;
  std::string out_dir;
};

/// --board FILE read as mrd-firmware reads it; nothing without --board.
/// Refuses the options the board file decides.
std::optional<app::BoardConfig> board_of(const SimOptions& o) {
  if (o.board.empty()) return std::nullopt;
  for (const auto& [given, name] : {std::pair{o.step_given, "--step-s"}, std::pair{o.numeric_given, "--numeric"},
                                    std::pair{!o.damper.empty(), "--damper"}, std::pair{!o.fluid.empty(), "--fluid"}}) {
    if (given) throw io::UsageError(std::string(name) + " cannot be given with --board: the board file decides it");
  }
  try {
    return app::parse_board_config(io::read_regular_file(o.board, app::kMaxBoardFileBytes), io::file_label(o.board));
  } catch (const app::BoardConfigError& e) {
    throw io::UsageError(e.what());
  }
}

plant::PlantKind parse_plant_kind(const std::string& text) {
  require_choice("--plant", text, {"thesis", "hardware"});
  return text == "hardware" ? plant::PlantKind::kHardware : plant::PlantKind::kThesis;
}

/// The run the options ask for; throws io::UsageError for a bad option.
run::SimSpec sim_spec(const SimOptions& o) {
  check_pga_g(o.pga_g);
  check_idle_years(o.idle_years);
  if (o.duration_given) {
    require_positive("--duration-s", o.duration_s, "a duration");
    require_at_most("--duration-s", o.duration_s, kMaxDuration_s, "100000 s");
  }
  require_step_s(o.step_s, 0.02, "0.02 s");
  require_finite_at_least("--offset-mm", o.offset_mm, -292.1);
  require_at_most("--offset-mm", o.offset_mm, 292.1, "292.1 mm");
  run::SimSpec spec;
  spec.plant = parse_plant_kind(o.plant);
  spec.sensor_seed = o.sensor_seed;
  spec.stroke_offset_m = o.offset_mm * 1e-3;
  spec.record = o.record;
  spec.pga_g = o.pga_g;
  spec.mode = run::parse_control_mode(o.control);
  spec.numeric = run::parse_numeric_kind(o.numeric);
  spec.idle_years = o.idle_years;
  spec.duration_s = o.duration_s;
  spec.step_s = o.step_s;
  spec.seed = o.seed;
  spec.keep_record = !o.out_dir.empty();
  const std::optional<app::BoardConfig> board = board_of(o);
  spec.building = load_building(o.building);
  const DamperAndFluid d = load_damper_and_fluid("sim", o.damper, o.fluid);
  spec.damper = d.params;
  spec.settling = d.settling;
  if (const std::optional<app::BoardConfig>& b = board) {
    spec.step_s = b->period_s();
    spec.numeric = b->fixed_point ? run::NumericKind::kFixed : run::NumericKind::kFloat;
    if (!o.control_given) spec.mode = b->mode;
    spec.damper = b->damper;
    spec.settling = b->settling;
  }
  const discrepancy::CoilCircuit& circuit = d.damper.coil_circuit;
  if (circuit.resistance_ohm) spec.hardware_coil.resistance_ohm = *circuit.resistance_ohm;
  if (circuit.inductance_1a_h) {
    spec.hardware_coil.inductance_1a_h = *circuit.inductance_1a_h;
    spec.hardware_coil.inductance_2a_h = *circuit.inductance_2a_h;
    // The saturated floor (an assumption, plant/coil.hpp) stays below the coil's own L(2 A).
    spec.hardware_coil.min_inductance_h = std::min(spec.hardware_coil.min_inductance_h, *circuit.inductance_2a_h);
  }
  if (spec.plant == plant::PlantKind::kHardware && !o.damper.empty() &&
      (!circuit.resistance_ohm || !circuit.inductance_1a_h))
    print_warnings("sim", {io::file_label(o.damper) + ": the hardware plant's coil is the thesis's (Table 3.1) where "
                           "the file's [coil] has no resistance_ohm or inductance_1a_h/inductance_2a_h"});
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
  const plant::CoilFigures& c = s.coil;
  std::printf("  plant                        %10s\n", plant::plant_kind_name(r.spec.plant));
  if (r.spec.plant == plant::PlantKind::kHardware) {
    std::printf("  sensor seed                  %10llu\n", static_cast<unsigned long long>(r.spec.sensor_seed));
    std::printf("  parking offset               %10.4f mm\n", r.spec.stroke_offset_m * 1e3);
  }
  std::printf("  rms coil current             %10.4f A\n", c.rms_coil_current_a);
  const std::string above = "time above rated " + io::format_number("%g", r.spec.damper.rating.current_a) + " A";
  std::printf("  %-29s%10.3f s\n", above.c_str(), c.time_above_rated_s);
  std::printf("  command changes              %10.2f per s\n", c.command_changes_per_s);
  std::printf("  peak coil temperature rise   %10.4f K\n", c.peak_coil_temperature_rise_k);
  std::fflush(stdout);
  print_warnings("sim", run::sim_warnings(r));
}

void add_options(CLI::App& app, SimOptions& o) {
  app.add_option("--record", o.record,
                 "Ground-motion record: CSV (time_s,accel_m_s2) or PEER .AT2; none: no ground motion");
  add_pga_g_option(app, o.pga_g, "Scale the record to this PGA, g (Table 6.3: 0.1127)");
  app.add_option("--control", o.control, "passive-off | passive-on | semi-active")
      ->capture_default_str()
      ->each([&o](const std::string&) { o.control_given = true; });
  app.add_option("--numeric", o.numeric, "Numeric build of the firmware control core: float | fixed | double (the host's reference, with neither build's rounding)")
      ->capture_default_str()
      ->each([&o](const std::string&) { o.numeric_given = true; });
  app.add_option("--board", o.board,
                 "Board file whose [controller], [damper], [fluid] and [control] period, mode and build the run uses "
                 "(as mrd-firmware runs them)");
  add_idle_years_option(app, o.idle_years, "Idle time before the earthquake, years");
  app.add_option("--duration-s", o.duration_s,
                 "Simulated time, s, > 0 (default: the record's length; 40 s synthetic)")
      ->each([&o](const std::string&) { o.duration_given = true; });
  add_step_s_option(app, o.step_s, "Simulation and control step, s");
  app.get_option("--step-s")->each([&o](const std::string&) { o.step_given = true; });
  add_seed_option(app, o.seed, "Seed of the synthetic motion (without --record)");
  app.add_option("--plant", o.plant, "thesis | hardware")->capture_default_str();
  add_building_option(app, o.building);
  add_damper_option(app, o.damper);
  add_fluid_option(app, o.fluid);
  add_seed_option(app, o.sensor_seed, "Seed of the hardware plant's sensor noise", "--sensor-seed");
  app.add_option("--offset-mm", o.offset_mm, "Hardware plant: damper parked this far off its stroke centre, mm")
      ->capture_default_str();
  add_out_option(app, o.out_dir, "Folder for summary.json, timeseries.csv and plots");
}

void execute(const SimOptions& o) {
  const run::SimSpec spec = sim_spec(o);
  const std::optional<app::BoardConfig> board = board_of(o);
  std::unique_ptr<run::Controller> controller;
  if (board) {
    fw::ControllerConfig c = board->controller_config();
    c.mode = spec.mode;
    // As the board runs it: its inputs and command through the CAN frames' quantization.
    controller = std::make_unique<run::WireQuantizedController>(run::make_configured_controller(c, spec.numeric));
  } else {
    controller = run::make_controller(spec.mode, spec.step_s, spec.numeric);
  }
  compute_print_write(
      "sim", o.out_dir, [&] { return run::run_sim(spec, *controller); }, print_summary, run::write_sim_outputs);
}

}  // namespace
}  // namespace sim_command

Command add_sim_command(CLI::App& parent) {
  using namespace sim_command;
  return make_command(parent, kSimHelp, add_options, execute);
}

}  // namespace mrd::cli
