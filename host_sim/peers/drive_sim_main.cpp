/// `mrd-drive-sim`: the PWM current drive on a CAN interface. Takes current
/// commands only from the controller's node id, falls back to its safe
/// current when valid commands stop for longer than the timeout, and reports
/// every state change with the time since the last valid command.

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>

#include "host_sim/peers/peer_main_common.hpp"
#include "host_sim/peers/peer_nodes.hpp"
#include "firmware/platform/linux/posix_clock.hpp"
#include "firmware/platform/linux/socketcan_bus.hpp"

namespace {
const char* state_name(mrd::protocol::DriveState s) {
  switch (s) {
    case mrd::protocol::DriveState::kDisabled: return "disabled";
    case mrd::protocol::DriveState::kFollowing: return "following";
    case mrd::protocol::DriveState::kSafe: return "safe";
    case mrd::protocol::DriveState::kFault: return "fault";
  }
  return "?";
}
}  // namespace

int main(int argc, char** argv) {
  using namespace mrd;
  CLI::App app{"mrd-drive-sim: simulated PWM current drive (30A8 class) on a CAN interface.", "mrd-drive-sim"};
  std::string board_file, can_if;
  bool lockstep = false;
  double safe_current_a = 2.5, timeout_ms = 20.0, duration_s = 0.0, command_wait_s = 1.0, idle_exit_s = 3.0;
  double fault_at_s = -1.0, fault_for_s = 0.0;
  app.add_option("--board", board_file, "Board file for node ids, period and interface");
  app.add_option("--can", can_if, "CAN interface (default: the board's, else vcan0)");
  app.add_flag("--lockstep", lockstep, "Tick on the plant's SimCoilState frames (deterministic)");
  app.add_option("--safe-current-a", safe_current_a, "Current applied when commands stop, A")->capture_default_str();
  app.add_option("--timeout-ms", timeout_ms, "Command timeout, ms")->capture_default_str();
  app.add_option("--duration-s", duration_s, "Free-running: stop after this long, s (0: until SIGTERM)");
  app.add_option("--command-wait-s", command_wait_s, "Lockstep: decide a tick without command after this, s")
      ->capture_default_str();
  app.add_option("--idle-exit-s", idle_exit_s, "Lockstep: stop when no frame arrives for this long, s")
      ->capture_default_str();
  app.add_option("--fault-at-s", fault_at_s, "Inject a drive fault at this time (simulated time in lockstep), s");
  app.add_option("--fault-for-s", fault_for_s, "Duration of the injected fault, s");
  int sched_fifo = 0;
  app.add_option("--sched-fifo", sched_fifo, "Run at this SCHED_FIFO priority (1..99), as a drive with its own CPU");
  CLI11_PARSE(app, argc, argv);

  peers::install_stop_signals();
  app::BoardConfig board;
  try {
    board = peers::board_or_defaults(board_file);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-drive-sim: error: %s\n", e.what());
    return 2;
  }
  if (!can_if.empty()) board.can_interface = can_if;
  if (!(safe_current_a >= -10.0 && safe_current_a <= 10.0) || !(timeout_ms > 0.0)) {
    std::fprintf(stderr, "mrd-drive-sim: error: --safe-current-a must be within ±10 A, --timeout-ms > 0\n");
    return 2;
  }
  peers::DriveConfig dc;
  dc.nodes = board.nodes;
  dc.safe_current_a = static_cast<float>(safe_current_a);
  dc.command_timeout_ns = static_cast<std::int64_t>(timeout_ms * 1e6);

  try {
    const auto filters = peers::drive_filters(board.nodes);
    posix::SocketCanBus bus(board.can_interface, filters);
    peers::DriveNode node(bus, dc, board.period_s(), lockstep);
    posix::PosixClock clock;
    if (sched_fifo > 0) std::fputs(posix::apply_realtime({sched_fifo, true, -1}).c_str(), stdout);
    const std::int64_t period_ns = static_cast<std::int64_t>(board.period_us) * 1000;
    const std::int64_t t0 = clock.now_ns();
    std::printf("mrd-drive-sim: on %s (node %u, commands from node %u), safe current %.3f A after %.1f ms, %s\n",
                board.can_interface.c_str(), board.nodes.drive, board.nodes.controller, safe_current_a, timeout_ms,
                lockstep ? "lockstep" : "free-running");
    auto fault_at = [&](std::int64_t t_ns) {
      const double t = static_cast<double>(t_ns) * 1e-9;
      return fault_at_s >= 0.0 && t >= fault_at_s && t < fault_at_s + fault_for_s;
    };
    protocol::DriveState last = protocol::DriveState::kDisabled;
    auto report = [&](std::int64_t t_ns) {
      const auto& o = node.logic().output();
      if (o.state == last) return;
      std::printf("mrd-drive-sim: t=%.4f s: %s -> %s, applied %.3f A", static_cast<double>(t_ns) * 1e-9,
                  state_name(last), state_name(o.state), static_cast<double>(o.applied_current_a));
      if (o.state == protocol::DriveState::kSafe && node.logic().counters().last_fallback_latency_ns >= 0)
        std::printf(" (last valid command %.3f ms before; previous drive tick %.3f ms before)",
                    static_cast<double>(node.logic().counters().last_fallback_latency_ns) / 1e6,
                    static_cast<double>(node.logic().counters().last_fallback_tick_gap_ns) / 1e6);
      std::printf("\n");
      last = o.state;
    };
    if (lockstep) {
      std::int64_t last_rx = clock.now_ns(), await_since = 0;
      bool started = false;
      while (!peers::g_peer_stop.load()) {
        const bool was_awaiting = node.awaiting_command();
        node.set_fault(fault_at(static_cast<std::int64_t>(node.ticks()) * period_ns));
        if (node.poll()) report(static_cast<std::int64_t>(node.ticks()) * period_ns);
        if (node.awaiting_command() && !was_awaiting) await_since = clock.now_ns();
        if (node.awaiting_command() &&
            clock.now_ns() - await_since > static_cast<std::int64_t>(command_wait_s * 1e9)) {
          node.decide_without_command();
          report(static_cast<std::int64_t>(node.ticks()) * period_ns);
        }
        if (bus.wait_readable(std::chrono::milliseconds(20))) {
          last_rx = clock.now_ns();
          started = true;
        } else if (started && clock.now_ns() - last_rx > static_cast<std::int64_t>(idle_exit_s * 1e9)) {
          break;
        }
      }
    } else {
      std::int64_t deadline = clock.now_ns();
      while (!peers::g_peer_stop.load()) {
        const std::int64_t now = clock.now_ns();
        if (duration_s > 0.0 && now - t0 > static_cast<std::int64_t>(duration_s * 1e9)) break;
        node.set_fault(fault_at(now - t0));
        node.free_tick(now);
        report(now - t0);
        deadline += period_ns;
        clock.sleep_until_ns(deadline);
      }
    }
    const auto& n = node.logic().counters();
    std::printf("mrd-drive-sim: summary ticks=%llu accepted=%u rejected=%u repeated=%u stale=%u foreign=%u "
                "fallbacks=%u last_fallback_latency_ms=%.3f last_fallback_tick_gap_ms=%.3f timeout_ms=%.3f "
                "final_state=%s\n",
                static_cast<unsigned long long>(node.ticks()), n.accepted, n.rejected, n.repeated, n.stale, n.foreign,
                n.fallbacks, static_cast<double>(n.last_fallback_latency_ns) / 1e6,
                static_cast<double>(n.last_fallback_tick_gap_ns) / 1e6, timeout_ms,
                state_name(node.logic().output().state));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-drive-sim: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
