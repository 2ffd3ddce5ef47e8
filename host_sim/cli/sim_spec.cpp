#include "host_sim/cli/sim_spec.hpp"

#include <algorithm>
#include <utility>

#include "host_sim/cli/building_option.hpp"
#include "host_sim/cli/command.hpp"
#include "host_sim/cli/damper_option.hpp"
#include "host_sim/cli/drive_option.hpp"
#include "host_sim/cli/fluid_option.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/run/wire_controller.hpp"

namespace mrd::cli {

std::optional<app::BoardConfig> sim_board(const SimOptions& o) {
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

namespace {

/// The controller limits its commands to the drive it was configured for (the
/// thesis rig's, or a board's from `mrd configure --drive`); a simulated drive
/// with other limits is said.
std::vector<std::string> controller_drive_mismatch(const std::optional<app::BoardConfig>& board,
                                                   const drive::DriveFile& d) {
  const fw::ControllerConfig c = board ? board->controller_config() : fw::ControllerConfig{};
  const plant::PwmDriveParams& p = d.params;
  const double command_a = drive::command_limit_a(p);
  if (c.command_limit_a == command_a && c.drive_continuous_limit_a == p.continuous_current_a &&
      c.drive_peak_limit_a == p.peak_current_a)
    return {};
  const auto g = [](double v) { return io::format_number("%g", v); };
  return {std::string("drive: the ") + (board ? "board" : "thesis's controller") + " was configured for a drive of +-" +
          g(c.command_limit_a) + " A command, " + g(c.drive_continuous_limit_a) + " A continuous and " +
          g(c.drive_peak_limit_a) +
          " A peak; the simulated drive's are +-" + g(command_a) + ", " + g(p.continuous_current_a) + " and " +
          g(p.peak_current_a) + " A (mrd configure --drive configures a board for it)"};
}

plant::PlantKind sim_plant_kind(const std::string& text) {
  require_choice("--plant", text, {"thesis", "hardware"});
  return text == "hardware" ? plant::PlantKind::kHardware : plant::PlantKind::kThesis;
}

}  // namespace

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
  spec.plant = sim_plant_kind(o.plant);
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
  const std::optional<app::BoardConfig> board = sim_board(o);
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
  if (spec.plant == plant::PlantKind::kHardware && !o.damper.empty() &&
      (!circuit.resistance_ohm || !circuit.inductance_1a_h))
    print_warnings("sim", {io::file_label(o.damper) + ": the hardware plant's coil is the thesis's (Table 3.1) where "
                           "the file's [coil] has no resistance_ohm or inductance_1a_h/inductance_2a_h"});
  if (!o.drive.empty() && spec.plant != plant::PlantKind::kHardware)
    throw io::UsageError("--drive: only --plant hardware simulates a drive (the thesis plant's coil current follows "
                         "the command through Eq. 4.5)");
  const bool board_drive = board && board->drive.has_value();
  if (board_drive && !o.drive.empty())
    throw io::UsageError("--drive cannot be given with --board " + io::file_label(o.board) +
                         ": its [drive] table decides it");
  if (spec.plant == plant::PlantKind::kHardware) {
    const drive::DriveFile drive =
        board_drive ? drive_of_board(*board->drive, io::file_label(o.board)) : load_drive(o.drive);
    spec.hardware_drive = drive.params;
    spec.hardware_drive_name = drive.name;
    std::vector<std::string> warnings = drive::check_drive_fit(
        drive, plant::coil_params(spec.damper.coil_heat.resistance_ohm, spec.damper.coil_inductance),
        spec.damper.rating.current_a, spec.step_s);
    if (!board_drive) {  // a board's own [drive] holds its controller within it (board_config.cpp)
      const std::vector<std::string> mismatch = controller_drive_mismatch(board, drive);
      warnings.insert(warnings.end(), mismatch.begin(), mismatch.end());
    }
    const std::string label = board_drive   ? io::file_label(o.board) + " [drive]"
                              : o.drive.empty() ? std::string("the thesis drive")
                                                : io::file_label(o.drive);
    for (std::string& w : warnings) w = label + ": " + w;
    print_warnings("sim", warnings);
  }
  return spec;
}

std::unique_ptr<run::Controller> sim_controller(const SimOptions& o, const run::SimSpec& spec) {
  const std::optional<app::BoardConfig> board = sim_board(o);
  if (board) {
    fw::ControllerConfig c = board->controller_config();
    c.mode = spec.mode;
    // As the board runs it: its inputs and command through the CAN frames' quantization.
    return std::make_unique<run::WireQuantizedController>(run::make_configured_controller(c, spec.numeric));
  }
  return run::make_controller(spec.mode, spec.step_s, spec.numeric);
}

}  // namespace mrd::cli
