/// `mrd-plant-sim`: the DAQ node and the plant (the building, the thesis's
/// 6-DOF one or a building file's, + MR damper) on a CAN interface. Lockstep: one tick per coil drive from the drive
/// simulator, deterministic and equal to `mrd sim`. Free-running: 1 tick per
/// period on CLOCK_MONOTONIC.

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>

#include "firmware/app/option_checks.hpp"
#include "host_sim/peers/peer_main_common.hpp"
#include "host_sim/peers/peer_nodes.hpp"
#include "firmware/platform/linux/posix_clock.hpp"
#include "firmware/platform/linux/socketcan_bus.hpp"
#include "host_sim/excitation/scaled_motion.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/structure/building_file.hpp"
#include "mrd/units.hpp"

int main(int argc, char** argv) {
  using namespace mrd;
  CLI::App app{"mrd-plant-sim: DAQ node + simulated building and MR damper on a CAN interface.", "mrd-plant-sim"};
  std::string board_file, can_if, record, building_file;
  double pga_g = 0.1127, duration_s = 0.0, idle_years = 0.0, wait_s = 10.0, start_delay_s = 0.0;
  bool lockstep = false;
  app.add_option("--board", board_file, "Board file for node ids, period and interface (default: protocol defaults)");
  app.add_option("--can", can_if, "CAN interface (default: the board's, else vcan0)");
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
  app.add_flag("--lockstep", lockstep, "Wait for the drive's coil drive of every tick (deterministic)");
  app.add_option("--wait-s", wait_s, "Lockstep: give up when a tick's coil drive takes longer, s")
      ->capture_default_str()
      ->check(app::positive_up_to(app::kMaxProgramTime_s, "s"));
  app.add_option("--start-delay-s", start_delay_s, "Wait this long before the first tick, s")
      ->capture_default_str()
      ->check(app::finite_in(0.0, app::kMaxProgramTime_s, "s"));
  if (const auto status = peers::parse_options(app, argc, argv, "mrd-plant-sim")) return *status;

  peers::install_stop_signals();
  app::BoardConfig board;
  plant::PlantSpec spec;
  std::vector<double> ag;
  try {
    board = peers::board_or_defaults(board_file);
    if (!(pga_g > 0.0) || !(duration_s >= 0.0) || !(idle_years >= 0.0))
      throw io::UsageError("--pga-g must be > 0, --duration-s and --idle-years >= 0");
    spec.step_s = board.period_s();
    spec.damper = board.damper;      // the board file's [damper] and [fluid]: the damper it controls
    spec.settling = board.settling;
    spec.idle_time_s = units::years_to_s(idle_years);
    if (!building_file.empty()) spec.building = structure::read_building_file(building_file);
    ag = excitation::load_scaled_motion(record, pga_g, spec.step_s, duration_s).accel_m_s2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-plant-sim: error: %s\n", e.what());
    return 2;
  }
  if (!can_if.empty()) board.can_interface = can_if;

  try {
    const auto filters = peers::plant_filters(board.nodes);
    posix::SocketCanBus bus(board.can_interface, filters);
    peers::PlantNode node(bus, board.nodes, spec);
    posix::PosixClock clock;
    std::printf("mrd-plant-sim: %zu ticks of %.4g s on %s, %s, building %s (%d DOFs)\n", ag.size(), spec.step_s,
                board.can_interface.c_str(), lockstep ? "lockstep" : "free-running", spec.building.name.c_str(),
                spec.building.dofs());
    clock.sleep_until_ns(clock.now_ns() + static_cast<std::int64_t>(start_delay_s * 1e9));
    const std::int64_t period_ns = static_cast<std::int64_t>(board.period_us) * 1000;
    std::int64_t deadline = clock.now_ns();
    for (std::size_t k = 0; k < ag.size() && !peers::g_peer_stop.load(); ++k) {
      if (lockstep) {
        node.begin_tick(ag[k]);
        const std::int64_t give_up = clock.now_ns() + static_cast<std::int64_t>(wait_s * 1e9);
        while (!node.try_finish_tick()) {
          if (clock.now_ns() > give_up || peers::g_peer_stop.load()) {
            std::fprintf(stderr, "mrd-plant-sim: error: no coil drive for tick %zu within %.1f s (is mrd-drive-sim "
                         "running in lockstep on %s?)\n", k, wait_s, board.can_interface.c_str());
            return 1;
          }
          bus.wait_readable(std::chrono::milliseconds(50));
        }
      } else {
        node.free_tick(ag[k]);
        deadline += period_ns;
        clock.sleep_until_ns(deadline);
      }
    }
    std::printf("mrd-plant-sim: rejected frames %u, values not encodable %u\n", node.rejected(), node.encode_errors());
    peers::print_plant_summary("mrd-plant-sim", node.model().summary());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-plant-sim: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
