/// `mrd-drive-sim`: the PWM current drive on a CAN interface. Takes current
/// commands only from the controller's node id, falls back to its safe
/// current when valid commands stop for longer than the timeout, and reports
/// every state change with the time since the last valid command.

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>

#include "firmware/platform/linux/posix_clock.hpp"
#include "firmware/platform/linux/socketcan_bus.hpp"
#include "firmware/app/option_checks.hpp"
#include "host_sim/peers/peer_main_common.hpp"
#include "host_sim/peers/peer_nodes.hpp"

namespace {

using namespace mrd;

const char* state_name(protocol::DriveState s) {
  switch (s) {
    case protocol::DriveState::kDisabled: return "disabled";
    case protocol::DriveState::kFollowing: return "following";
    case protocol::DriveState::kSafe: return "safe";
    case protocol::DriveState::kFault: return "fault";
  }
  return "?";
}

struct Options {
  std::string board_file, can_if;
  bool lockstep = false;
  double safe_current_a = fw::kPassiveOnCurrent_a, timeout_ms = 20.0, duration_s = 0.0, command_wait_s = 1.0,
         idle_exit_s = 3.0;
  bool safe_current_given = false;
  double fault_at_s = -1.0, fault_for_s = 0.0;
  int sched_fifo = 0;

  /// The injected fault is on at `t_ns` (time since start).
  bool fault_at(std::int64_t t_ns) const {
    const double t = static_cast<double>(t_ns) * 1e-9;
    return fault_at_s >= 0.0 && t >= fault_at_s && t < fault_at_s + fault_for_s;
  }
};

/// One line per change of the drive's state.
class StateReport {
 public:
  explicit StateReport(const peers::DriveNode& node) : node_(node) {}
  void operator()(std::int64_t t_ns) {
    const auto& o = node_.logic().output();
    if (o.state == last_) return;
    std::printf("mrd-drive-sim: t=%.4f s: %s -> %s, applied %.3f A", static_cast<double>(t_ns) * 1e-9,
                state_name(last_), state_name(o.state), static_cast<double>(o.applied_current_a));
    const auto& n = node_.logic().counters();
    if (o.state == protocol::DriveState::kSafe && n.last_fallback_latency_ns >= 0)
      std::printf(" (last valid command %.3f ms before; previous drive tick %.3f ms before)",
                  static_cast<double>(n.last_fallback_latency_ns) / 1e6,
                  static_cast<double>(n.last_fallback_tick_gap_ns) / 1e6);
    std::printf("\n");
    last_ = o.state;
  }

 private:
  const peers::DriveNode& node_;
  protocol::DriveState last_ = protocol::DriveState::kDisabled;
};

/// Ticks on the plant's SimCoilState frames until the bus falls silent.
void run_lockstep(peers::DriveNode& node, hal::CanBus& bus, hal::Clock& clock, const Options& o,
                  std::int64_t period_ns, StateReport& report) {
  std::int64_t last_rx = clock.now_ns(), await_since = 0;
  bool started = false;
  while (!peers::g_peer_stop.load()) {
    const bool was_awaiting = node.awaiting_command();
    node.set_fault(o.fault_at(static_cast<std::int64_t>(node.ticks()) * period_ns));
    if (node.poll()) report(static_cast<std::int64_t>(node.ticks()) * period_ns);
    if (node.awaiting_command() && !was_awaiting) await_since = clock.now_ns();
    if (node.awaiting_command() && clock.now_ns() - await_since > static_cast<std::int64_t>(o.command_wait_s * 1e9)) {
      node.decide_without_command();
      report(static_cast<std::int64_t>(node.ticks()) * period_ns);
    }
    if (bus.wait_readable(std::chrono::milliseconds(20))) {
      last_rx = clock.now_ns();
      started = true;
    } else if (started && clock.now_ns() - last_rx > static_cast<std::int64_t>(o.idle_exit_s * 1e9)) {
      break;
    }
  }
}

/// Ticks on the clock at the board's period for `duration_s` (or until stopped).
void run_free(peers::DriveNode& node, hal::Clock& clock, const Options& o, std::int64_t period_ns,
              StateReport& report) {
  const std::int64_t t0 = clock.now_ns();
  std::int64_t deadline = t0;
  while (!peers::g_peer_stop.load()) {
    const std::int64_t now = clock.now_ns();
    if (o.duration_s > 0.0 && now - t0 > static_cast<std::int64_t>(o.duration_s * 1e9)) break;
    node.set_fault(o.fault_at(now - t0));
    node.free_tick(now);
    report(now - t0);
    deadline += period_ns;
    clock.sleep_until_ns(deadline);
  }
}

void print_summary(const peers::DriveNode& node, const Options& o) {
  const auto& n = node.logic().counters();
  std::printf("mrd-drive-sim: summary ticks=%llu accepted=%u rejected=%u repeated=%u stale=%u foreign=%u "
              "fallbacks=%u last_fallback_latency_ms=%.3f last_fallback_tick_gap_ms=%.3f timeout_ms=%.3f "
              "final_state=%s\n",
              static_cast<unsigned long long>(node.ticks()), n.accepted, n.rejected, n.repeated, n.stale, n.foreign,
              n.fallbacks, static_cast<double>(n.last_fallback_latency_ns) / 1e6,
              static_cast<double>(n.last_fallback_tick_gap_ns) / 1e6, o.timeout_ms,
              state_name(node.logic().output().state));
}

/// Opens the interface and runs the drive; exit status 1 when the interface cannot be used.
int run(const app::BoardConfig& board, const peers::DriveConfig& dc, const Options& o) {
  try {
    posix::SocketCanBus bus(board.can_interface, peers::drive_filters(board.nodes));
    peers::DriveNode node(bus, dc, board.period_s());
    posix::PosixClock clock;
    if (o.sched_fifo > 0) std::fputs(posix::apply_realtime({o.sched_fifo, true, -1}).c_str(), stdout);
    const std::int64_t period_ns = static_cast<std::int64_t>(board.period_us) * 1000;
    std::printf("mrd-drive-sim: on %s (node %u, commands from node %u), safe current %.3f A after %.1f ms, "
                "over-current above %.3f A, %s\n",
                board.can_interface.c_str(), board.nodes.drive, board.nodes.controller,
                static_cast<double>(dc.safe_current_a), o.timeout_ms, static_cast<double>(dc.peak_limit_a),
                o.lockstep ? "lockstep" : "free-running");
    StateReport report(node);
    if (o.lockstep) {
      run_lockstep(node, bus, clock, o, period_ns, report);
    } else {
      run_free(node, clock, o, period_ns, report);
    }
    print_summary(node, o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-drive-sim: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mrd-drive-sim: simulated PWM current drive (30A8 class) on a CAN interface.", "mrd-drive-sim"};
  Options o;
  app.add_option("--board", o.board_file, "Board file for node ids, period and interface");
  app.add_option("--can", o.can_if, "CAN interface (default: the board's, else vcan0)");
  app.add_flag("--lockstep", o.lockstep, "Tick on the plant's SimCoilState frames (deterministic)");
  app.add_option("--safe-current-a", o.safe_current_a,
                 "Current applied when commands stop, A (default: the board's passive-on current, "
                 "controller.nominal_current_a; 2.5 A for the thesis's)")
      ->check(app::finite_in(0.0, 30.0, "A"))
      ->each([&o](const std::string&) { o.safe_current_given = true; });
  app.add_option("--timeout-ms", o.timeout_ms, "Command timeout, ms")
      ->capture_default_str()
      ->check(app::positive_up_to(app::kMaxProgramTime_s * 1e3, "ms"));
  app.add_option("--duration-s", o.duration_s, "Free-running: stop after this long, s (default: until SIGTERM)")
      ->check(app::positive_up_to(app::kMaxProgramTime_s, "s"));
  app.add_option("--command-wait-s", o.command_wait_s, "Lockstep: decide a tick without command after this, s")
      ->capture_default_str()
      ->check(app::positive_up_to(app::kMaxProgramTime_s, "s"));
  app.add_option("--idle-exit-s", o.idle_exit_s, "Lockstep: stop when no frame arrives for this long, s")
      ->capture_default_str()
      ->check(app::positive_up_to(app::kMaxProgramTime_s, "s"));
  app.add_option("--fault-at-s", o.fault_at_s, "Inject a drive fault at this time (simulated time in lockstep), s")
      ->check(app::finite_in(0.0, app::kMaxProgramTime_s, "s"));
  app.add_option("--fault-for-s", o.fault_for_s, "Duration of the injected fault, s")
      ->check(app::finite_in(0.0, app::kMaxProgramTime_s, "s"));
  app.add_option("--sched-fifo", o.sched_fifo, "Run at this SCHED_FIFO priority (1..99), as a drive with its own CPU")
      ->check(CLI::Range(1, 99));
  if (const auto status = peers::parse_options(app, argc, argv, "mrd-drive-sim")) return *status;

  peers::install_stop_signals();
  app::BoardConfig board;
  try {
    board = peers::board_or_defaults(o.board_file);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-drive-sim: error: %s\n", e.what());
    return 2;
  }
  if (!o.can_if.empty()) board.can_interface = o.can_if;
  if (!(o.safe_current_a >= -10.0 && o.safe_current_a <= 10.0) || !(o.timeout_ms > 0.0)) {
    std::fprintf(stderr, "mrd-drive-sim: error: --safe-current-a must be within ±10 A, --timeout-ms > 0\n");
    return 2;
  }
  // The board's drive: its damper's passive-on current when commands stop, its peak's over-current fault.
  peers::DriveConfig dc = peers::drive_config(board);
  if (o.safe_current_given) dc.safe_current_a = static_cast<float>(o.safe_current_a);
  dc.command_timeout_ns = static_cast<std::int64_t>(o.timeout_ms * 1e6);
  return run(board, dc, o);
}
