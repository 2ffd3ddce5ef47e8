/// `mrd-sim-board`: the `sim` board — the firmware runtime (control task and core), drive
/// and DAQ + plant nodes on an in-memory CAN bus in one process, in lockstep.
/// Prints the same summary line as `mrd-plant-sim`.

#include <CLI/CLI.hpp>

#include <cstdio>

#include "firmware/app/option_checks.hpp"
#include "host_sim/peers/in_process_board.hpp"
#include "host_sim/peers/peer_main_common.hpp"
#include "host_sim/excitation/scaled_motion.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/structure/building_file.hpp"
#include "mrd/units.hpp"

int main(int argc, char** argv) {
  using namespace mrd;
  CLI::App app{"mrd-sim-board: the in-process sim board (firmware task + peers on an in-memory CAN bus).",
               "mrd-sim-board"};
  std::string board_file, record, mode, building_file;
  double pga_g = 0.1127, duration_s = 0.0, idle_years = 0.0;
  app.add_option("--board", board_file, "Board file (boards/sim/board.toml)")->required();
  app.add_option("--record", record, "Ground-motion record: CSV (time_s,accel_m_s2) or PEER .AT2")->required();
  app.add_option("--pga-g", pga_g, "Scale the record to this PGA, g")
      ->capture_default_str()
      ->check(app::positive_up_to(100.0, "g"));
  app.add_option("--duration-s", duration_s, "Simulated time, s (default: the record's length)")
      ->check(app::positive_up_to(1.0e5, "s"));
  app.add_option("--idle-years", idle_years, "Idle time before the motion, years")
      ->capture_default_str()
      ->check(app::finite_in(0.0, 1000.0, "years"));
  app.add_option("--building", building_file,
                 "Building file (TOML; README \"Your building\"; default: the thesis building of Table 6.1)");
  app.add_option("--mode", mode, "Override the board's mode: passive-off | passive-on | semi-active");
  if (const auto status = peers::parse_options(app, argc, argv, "mrd-sim-board")) return *status;
  try {
    app::BoardConfig board = peers::load_board_file(board_file);
    if (!mode.empty()) {
      const auto m = control::parse_mode_name(mode);
      if (!m) throw io::UsageError("--mode: expected passive-off, passive-on or semi-active, got '" + mode + "'");
      board.mode = *m;
    }
    if (!(pga_g > 0.0) || !(duration_s >= 0.0) || !(idle_years >= 0.0))
      throw io::UsageError("--pga-g must be > 0, --duration-s and --idle-years >= 0");
    plant::PlantSpec spec;
    spec.step_s = board.period_s();
    spec.damper = board.damper;      // the board file's [damper] and [fluid]: the damper it controls
    spec.settling = board.settling;
    spec.idle_time_s = units::years_to_s(idle_years);
    if (!building_file.empty()) spec.building = structure::read_building_file(building_file);
    const std::vector<double> ag =
        excitation::load_scaled_motion(record, pga_g, spec.step_s, duration_s).accel_m_s2;
    peers::InProcessBoard b(board, spec, peers::drive_config(board));
    for (double a : ag) b.step(a);
    const auto& t = b.task_status();
    std::printf("mrd-sim-board: %s, %s, building %s (%d DOFs), %zu ticks, frames rejected %u\n", board.name.c_str(),
                control::mode_name(board.mode), spec.building.name.c_str(), spec.building.dofs(), ag.size(),
                t.rejected_total());
    peers::print_plant_summary("mrd-sim-board", b.summary());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-sim-board: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
