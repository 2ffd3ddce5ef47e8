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
#include "host_sim/cli/drive_option.hpp"
#include "host_sim/cli/fluid_option.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/cli/sim_spec.hpp"
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
15 A continuous by I^2t, +-10 V command at 1 V/A; --drive FILE: your drive, README "Your drive"), coil 4.8 ohm with L 5.0 H at 1 A and 3.0 H at
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
[control] period, mode and numeric build, its [damper] (with its coil) and [fluid], its [drive] when
it has one, the controller's inputs and command quantized as the board's CAN frames carry them;
`mrd configure` writes such a file); --control still picks the mode when given, and --step-s,
--numeric, --damper and --fluid (and --drive beside a [drive]) are refused with it (the board
file decides them).

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
  drive                           the hardware plant's drive, its drive file's name (null for thesis)
  peak_coil_current_a             max |coil current| over the ticks, A
  rms_coil_current_a              RMS coil current over the ticks, A
  time_above_rated_s              time with |coil current| above the rated 2.5 A, s
  command_changes_per_s           changes of the current command between consecutive ticks, per s of run
  peak_coil_temperature_rise_k    max coil temperature above ambient, K (i^2 R into a first-order
                                  thermal model of the damper's coil: the thesis coil's 4.8 ohm,
                                  2 K/W, 20 min, or a damper file's [coil]; both plants)
  peak_damper_velocity_m_s        max |base velocity relative to the ground|, m/s
  warnings                        sentences, one per limit of the model the run exceeds: stroke
                                  +-0.2921 m and velocity 0.2491 m/s (Table 3.1), current 0-2.5 A
                                  (Table 4.1), force 200 kN; also printed on stderr
Files: DIR/timeseries.csv (every step; columns name their units), DIR/timeseries_response.png
(displacement, force, floor acceleration, current over time, like Fig. 6.9-6.11) and
DIR/timeseries_loop.png (force against stroke).)"};

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
    std::printf("  drive                        %10s\n", r.spec.hardware_drive_name.c_str());
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
  add_drive_option(app, o.drive, "the hardware plant's drive (--plant hardware)");
  add_seed_option(app, o.sensor_seed, "Seed of the hardware plant's sensor noise", "--sensor-seed");
  app.add_option("--offset-mm", o.offset_mm, "Hardware plant: damper parked this far off its stroke centre, mm")
      ->capture_default_str();
  add_out_option(app, o.out_dir, "Folder for summary.json, timeseries.csv and plots");
}

void execute(const SimOptions& o) {
  const run::SimSpec spec = sim_spec(o);
  const std::unique_ptr<run::Controller> controller = sim_controller(o, spec);
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
