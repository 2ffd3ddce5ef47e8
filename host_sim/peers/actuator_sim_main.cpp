/// `mrd-actuator-sim`: the optional mixing actuator on a CAN interface. With
/// --daq-at-rest it is also the DAQ of a building at rest whose damper it
/// strokes (peers::RestingDaqNode), at the board's control period, so that
/// the controller's idle-time estimator sees the mixing cycle in the stroke.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "firmware/app/option_checks.hpp"
#include "host_sim/peers/peer_main_common.hpp"
#include "host_sim/peers/peer_nodes.hpp"
#include "firmware/platform/linux/posix_clock.hpp"
#include "firmware/platform/linux/socketcan_bus.hpp"

int main(int argc, char** argv) {
  using namespace mrd;
  CLI::App app{"mrd-actuator-sim: simulated mixing actuator on a CAN interface.", "mrd-actuator-sim"};
  std::string board_file, can_if;
  double stroke_m = 0.1, velocity_m_s = 0.2, duration_s = 0.0;
  bool daq_at_rest = false;
  app.add_option("--board", board_file, "Board file for node ids and interface");
  app.add_option("--can", can_if, "CAN interface (default: the board's, else vcan0)");
  app.add_option("--stroke-limit-m", stroke_m, "Largest amplitude it drives, m")
      ->capture_default_str()
      ->check(app::positive_up_to(1.0, "m"));
  app.add_option("--velocity-limit-m-s", velocity_m_s, "Largest velocity it reaches, m/s")
      ->capture_default_str()
      ->check(app::positive_up_to(10.0, "m/s"));
  app.add_option("--duration-s", duration_s, "Stop after this long, s (default: until SIGTERM)")
      ->check(app::positive_up_to(app::kMaxProgramTime_s, "s"));
  app.add_flag("--daq-at-rest", daq_at_rest,
               "Also send the DAQ frames of a building at rest: stroke = the actuator's position, accelerations 0");
  if (const auto status = peers::parse_options(app, argc, argv, "mrd-actuator-sim")) return *status;

  peers::install_stop_signals();
  app::BoardConfig board;
  try {
    board = peers::board_or_defaults(board_file);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-actuator-sim: error: %s\n", e.what());
    return 2;
  }
  if (!can_if.empty()) board.can_interface = can_if;
  peers::ActuatorConfig ac;
  ac.nodes = board.nodes;
  ac.stroke_limit_m = static_cast<float>(stroke_m);
  ac.velocity_limit_m_s = static_cast<float>(velocity_m_s);
  try {
    const auto filters = peers::actuator_filters(board.nodes);
    posix::SocketCanBus bus(board.can_interface, filters);
    peers::ActuatorNode node(bus, ac);
    posix::PosixClock clock;
    peers::RestingDaqNode daq(bus, board.nodes);
    // 100 Hz alone; at the control period when it also stands for the DAQ.
    const std::int64_t t0 = clock.now_ns();
    const std::int64_t period_ns = daq_at_rest ? static_cast<std::int64_t>(board.period_us) * 1000 : 10'000'000;
    std::int64_t deadline = t0;
    auto last = protocol::MixingState::kIdle;
    std::printf("mrd-actuator-sim: on %s (node %u)%s\n", board.can_interface.c_str(), board.nodes.actuator,
                daq_at_rest ? ", with the DAQ of a building at rest" : "");
    double peak_m = 0.0;
    while (!peers::g_peer_stop.load()) {
      const std::int64_t now = clock.now_ns();
      if (duration_s > 0.0 && now - t0 > static_cast<std::int64_t>(duration_s * 1e9)) break;
      node.free_tick(now);
      if (daq_at_rest) {
        const double x_m = node.logic().position_m(now);
        peak_m = std::max(peak_m, std::abs(x_m));
        daq.sample(x_m);
      }
      if (node.logic().state() != last) {
        last = node.logic().state();
        std::printf("mrd-actuator-sim: t=%.2f s: state %d (peak stroke so far %.4f m)\n",
                    static_cast<double>(now - t0) * 1e-9, static_cast<int>(last), peak_m);
      }
      deadline += period_ns;
      clock.sleep_until_ns(deadline);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-actuator-sim: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
