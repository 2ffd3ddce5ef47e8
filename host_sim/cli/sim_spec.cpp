#include "host_sim/cli/sim_spec.hpp"

#include <algorithm>
#include <utility>

#include "host_sim/cli/building_option.hpp"
#include "host_sim/cli/command.hpp"
#include "host_sim/cli/damper_option.hpp"
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
  // The coil's resistance is spec.damper's (coil_heat); its inductance the damper file's.
  const discrepancy::CoilCircuit& circuit = d.damper.coil_circuit;
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
