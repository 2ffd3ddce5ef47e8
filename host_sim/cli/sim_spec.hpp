#pragma once
/// The options of `mrd sim` and what they make: the run (run::SimSpec) and
/// its controller. Shared by the `mrd sim` subcommand and the Python module
/// (python/), so that both check the same values with the same messages.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "firmware/app/board_config.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/sim_run.hpp"

namespace mrd::cli {

/// The values of `mrd sim`'s options, as the command line gives them.
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
  std::string drive;  ///< --drive FILE: the hardware plant's drive (empty: the thesis's)
  std::string out_dir;
};

/// --board FILE read as mrd-firmware reads it; nothing without --board.
/// Refuses the options the board file decides (io::UsageError).
std::optional<app::BoardConfig> sim_board(const SimOptions& o);

/// The run the options ask for; throws io::UsageError for a bad option or
/// file. Prints the damper and fluid files' warnings on stderr ("mrd sim:
/// warning: ...").
run::SimSpec sim_spec(const SimOptions& o);

/// The controller of the run `spec` (made by sim_spec(o)): the firmware
/// control core for spec.mode, spec.step_s and spec.numeric, or with --board
/// that board's configured core behind its CAN frames' quantization.
std::unique_ptr<run::Controller> sim_controller(const SimOptions& o, const run::SimSpec& spec);

}  // namespace mrd::cli
