/// `mrd-rths-lab`: the emulated laboratory of an RTHS as a program on the CAN
/// bus (lab_node.hpp): the benchmark's servo-hydraulic actuator with its
/// specimen (nominal, or drawn from the published uncertainty by
/// --plant-seed), ±3.8 V 18-bit converters, sensor noise of the published
/// powers, and the stop when |force| or |measured − target| leave their limits
/// (the actuator holds; the stop is reported on CAN after every command).
/// Sends its beacon every 100 ms until the first command, then answers each
/// command with the next measurement; ends at the runtime's run status, after
/// --command-timeout-ms without a command once running (stopped and held), or
/// at a signal.
///
/// --specimen damper: the thesis's set-up's laboratory (damper_lab_node.hpp):
/// the actuator (--delay-ms, --lag-ms) stroking the MR damper of the board
/// file's [damper] and [fluid] after --idle-years, its drive (answering the
/// board's control task's CurrentCommand) and DAQ (DaqMotion, DriveStatus);
/// the force limit is then the actuator's 250 kN unless --force-limit-kn.
///
/// With --own-clock the damper laboratory steps every period on its own
/// CLOCK_MONOTONIC from the first command on, with the latest command (the
/// last one held when none arrived); its line "own clock overruns=…
/// worst_late_us=… held_steps=…" comes before the summary.
///
/// Last line on stdout: "mrd-rths-lab: summary steps=… state=… stop=…
/// stop_step=… peak_force_n=… rejected=… sequence_gaps=… tx_errors=… run=…".
/// Exit status: 0 the runtime ended the run, 1 runtime failure (no CAN, no
/// runtime), 2 bad input.

#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "firmware/platform/linux/posix_clock.hpp"
#include "firmware/platform/linux/socketcan_bus.hpp"
#include "firmware/app/periodic_schedule.hpp"
#include "host_sim/peers/peer_main_common.hpp"
#include "host_sim/rths_board/damper_lab_node.hpp"
#include "host_sim/rths_board/lab_node.hpp"
#include "mrd/physics/settling.hpp"
#include "mrd/units.hpp"

namespace {

namespace rb = mrd::rths_board;
using Clock = std::chrono::steady_clock;

struct Options {
  std::string board_file, can_interface;
  double rate_hz = 0.0, tracking_limit_mm = 10.0, force_limit_kn = 8.9, start_timeout_s = 60.0;
  int lab_node = rb::kDefaultLabNode;
  int command_timeout_ms = 1000;
  std::uint64_t plant_seed = 0, noise_seed = 1;
  std::string specimen = "benchmark";
  double delay_ms = 15.0, lag_ms = 2.0, idle_years = 0.0;
  bool force_limit_given = false, own_clock = false;
  bool can_fd = false;
};

const char* run_state_name(rb::RunState s, bool finished) {
  if (!finished) return "none";
  switch (s) {
    case rb::RunState::kFinished: return "finished";
    case rb::RunState::kLabStopped: return "lab_stopped";
    case rb::RunState::kAborted: return "aborted";
  }
  return "unknown";
}

/// Beacons until the first command, then answers commands until the
/// runtime's run status, a command timeout or a signal; the summary line.
template <class Node>
int serve_until_done(Node& lab, mrd::posix::SocketCanBus& bus, const Options& o, std::uint8_t runtime_node,
                     std::int64_t period_ns = 0) {
  const auto started = Clock::now();
  auto last_command = started;
  auto next_beacon = started;
  int exit_status = 0;
  while (!lab.finished() && !mrd::peers::g_peer_stop.load()) {
    const auto now = Clock::now();
    if (lab.state() == rb::LabState::kWaiting) {
      if (now >= next_beacon) {
        lab.send_beacon();
        next_beacon = now + std::chrono::milliseconds(100);
      }
      if (now - started > std::chrono::duration<double>(o.start_timeout_s)) {
        std::fprintf(stderr, "mrd-rths-lab: error: no command from node %u within %.1f s\n", runtime_node,
                     o.start_timeout_s);
        exit_status = 1;
        break;
      }
    } else if (now - last_command > std::chrono::milliseconds(o.command_timeout_ms)) {
      lab.stop_for_command_timeout();
      exit_status = 1;
      break;
    }
    if constexpr (requires { lab.step_on_clock(); }) {
      if (o.own_clock && lab.has_command()) {
        // Own clock: a step every period on CLOCK_MONOTONIC with the latest
        // command (the last one held when none arrived), from the first command on.
        mrd::posix::PosixClock clock;
        mrd::app::PeriodicSchedule schedule(period_ns, clock.now_ns());
        while (!lab.finished() && !mrd::peers::g_peer_stop.load()) {
          if (lab.serve() > 0) last_command = Clock::now();
          if (Clock::now() - last_command > std::chrono::milliseconds(o.command_timeout_ms)) {
            lab.stop_for_command_timeout();
            exit_status = 1;
            break;
          }
          lab.step_on_clock();
          clock.sleep_until_ns(schedule.after_tick(clock.now_ns()));
        }
        std::printf("mrd-rths-lab: own clock overruns=%u worst_late_us=%.1f held_steps=%u\n", schedule.overruns(),
                    static_cast<double>(schedule.worst_late_ns()) / 1e3, lab.held_steps());
        break;
      }
    }
    bus.wait_readable(std::chrono::milliseconds(lab.state() == rb::LabState::kWaiting ? 20 : 5));
    if (lab.serve() > 0) last_command = Clock::now();
  }
  if constexpr (requires { lab.current_late(); })
    std::printf("mrd-rths-lab: drive current_late=%u (commands stepped on without that tick's current command)\n",
                lab.current_late());
  std::printf("mrd-rths-lab: summary steps=%llu state=%s stop=%s stop_step=%llu peak_force_n=%.3f rejected=%u "
              "sequence_gaps=%u tx_errors=%u run=%s\n",
              static_cast<unsigned long long>(lab.steps()), rb::lab_state_name(lab.state()),
              rb::lab_stop_reason_name(lab.stop_reason()), static_cast<unsigned long long>(lab.stop_step()),
              lab.peak_force_n(), lab.rejected(), lab.sequence_gaps(), lab.tx_errors(),
              run_state_name(lab.run_state(), lab.finished()));
  return exit_status;
}

int run_damper(const Options& o, const mrd::app::BoardConfig& board) {
  rb::DamperLabConfig c;
  c.rate_hz = o.rate_hz > 0.0 ? o.rate_hz : 1e6 / static_cast<double>(board.period_us);
  c.nodes = board.nodes;
  c.drive = mrd::peers::drive_config(board);  // the board's drive: its safe current and peak
  c.lab_node = static_cast<std::uint8_t>(o.lab_node);
  c.delay_s = std::round(o.delay_ms * 1e-3 * c.rate_hz) / c.rate_hz;
  c.lag_s = o.lag_ms * 1e-3;
  c.damper = board.damper;
  c.settling_quotient = mrd::physics::settling_quotient_after_idle(mrd::units::years_to_s(o.idle_years), board.settling);
  c.tracking_limit_m = o.tracking_limit_mm * 1e-3;
  c.own_clock = o.own_clock;
  if (o.force_limit_given) c.force_limit_n = o.force_limit_kn * 1e3;
  const double delay_steps = o.delay_ms * 1e-3 * c.rate_hz;
  if (std::fabs(delay_steps - std::round(delay_steps)) > 1e-6 || std::lround(delay_steps) < 1) {
    std::fprintf(stderr, "mrd-rths-lab: error: --delay-ms: %g ms is not a whole number (at least one) of steps at %.0f Hz\n",
                 o.delay_ms, c.rate_hz);
    return 2;
  }
  for (const std::uint8_t n : {board.nodes.controller, board.nodes.drive, board.nodes.daq})
    if (c.lab_node == n) {
      std::fprintf(stderr, "mrd-rths-lab: error: --lab-node: %u is a node of the board's damper loop\n", c.lab_node);
      return 2;
    }
  const mrd::hal::CanFilter filters[] = {
      {mrd::protocol::can_id(mrd::protocol::MsgId::kCurrentCommand, c.nodes.controller), 0x7FF},
      {mrd::protocol::can_id(mrd::protocol::MsgId::kRthsCommand, c.nodes.controller), 0x7FF},
      {mrd::protocol::can_id(mrd::protocol::MsgId::kRthsRunStatus, c.nodes.controller), 0x7FF}};
  std::unique_ptr<mrd::posix::SocketCanBus> bus;
  std::unique_ptr<rb::DamperLabNode> lab;
  try {
    bus = std::make_unique<mrd::posix::SocketCanBus>(board.can_interface, filters);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths-lab: error: %s\n", e.what());
    return 1;
  }
  try {
    lab = std::make_unique<rb::DamperLabNode>(*bus, c);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths-lab: error: %s\n", e.what());
    return 2;
  }
  std::printf("mrd-rths-lab: CAN %s (lab node %u; drive node %u, DAQ node %u; runtime and control node %u), %.0f Hz, "
              "specimen damper (%s, idle %.3g years), actuator %.1f ms + %.1f ms lag, tracking limit %.3f mm, force "
              "limit %.3f kN\n",
              board.can_interface.c_str(), c.lab_node, c.nodes.drive, c.nodes.daq, c.nodes.controller, c.rate_hz,
              board.name.c_str(), o.idle_years, 1e3 * c.delay_s, 1e3 * c.lag_s, o.tracking_limit_mm,
              1e-3 * c.force_limit_n);
  std::fputs(mrd::posix::apply_realtime({board.sched_fifo_priority, board.lock_memory, board.cpu}).c_str(), stdout);
  std::fflush(stdout);
  return serve_until_done(*lab, *bus, o, c.nodes.controller, std::llround(1e9 / c.rate_hz));
}

int run(const Options& o) {
  mrd::app::BoardConfig board;
  rb::LabNodeConfig c;
  try {
    board = mrd::peers::load_board_file(o.board_file);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths-lab: error: %s\n", e.what());
    return 2;
  }
  if (!o.can_interface.empty()) board.can_interface = o.can_interface;
  if (o.specimen == "damper" && o.can_fd) {
    std::fprintf(stderr, "mrd-rths-lab: error: --can-fd: only with --specimen benchmark\n");
    return 2;
  }
  if (o.specimen == "damper") return run_damper(o, board);
  c.can_fd = o.can_fd;
  c.rate_hz = o.rate_hz > 0.0 ? o.rate_hz : 1e6 / static_cast<double>(board.period_us);
  c.runtime_node = board.nodes.controller;
  c.lab_node = static_cast<std::uint8_t>(o.lab_node);
  if (c.lab_node == c.runtime_node) {
    std::fprintf(stderr, "mrd-rths-lab: error: --lab-node: %u is the board's controller node\n", c.lab_node);
    return 2;
  }
  if (o.plant_seed != 0) {
    std::mt19937_64 rng(o.plant_seed);
    c.plant = mrd::rths::draw_lab_plant(mrd::rths::LabPlantParams{}, mrd::rths::LabPlantUncertainty{}, rng);
  }
  c.spec.tracking_limit_m = o.tracking_limit_mm * 1e-3;
  c.spec.force_limit_n = o.force_limit_kn * 1e3;
  c.spec.noise_seed = o.noise_seed;

  const mrd::hal::CanFilter filters[] = {
      {mrd::protocol::can_id(mrd::protocol::MsgId::kRthsCommand, c.runtime_node), 0x7FF},
      {mrd::protocol::can_id(mrd::protocol::MsgId::kRthsRunStatus, c.runtime_node), 0x7FF}};
  std::unique_ptr<mrd::posix::SocketCanBus> bus;
  try {
    bus = std::make_unique<mrd::posix::SocketCanBus>(board.can_interface, filters, c.can_fd);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths-lab: error: %s\n", e.what());
    return 1;
  }
  rb::LabNode lab(*bus, c);
  std::printf("mrd-rths-lab: CAN%s %s (node %u, runtime node %u), %.0f Hz, plant %s (beta1 %.4g, beta2 %.6g, a3 %.4g, "
              "k_e %.6g N/m), tracking limit %.3f mm, force limit %.3f kN\n",
              c.can_fd ? " FD" : "", board.can_interface.c_str(), c.lab_node, c.runtime_node, c.rate_hz,
              o.plant_seed ? "drawn" : "nominal", c.plant.beta1, c.plant.beta2, c.plant.a3,
              c.plant.specimen.stiffness_n_m, o.tracking_limit_mm, o.force_limit_kn);
  std::fputs(mrd::posix::apply_realtime({board.sched_fifo_priority, board.lock_memory, board.cpu}).c_str(), stdout);
  std::fflush(stdout);

  return serve_until_done(lab, *bus, o, c.runtime_node);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mrd-rths-lab: the emulated RTHS laboratory (servo-hydraulic actuator, specimen, converters, sensor "
               "noise, stop) as a node on the CAN bus (peer: mrd-rths).",
               "mrd-rths-lab"};
  Options o;
  app.add_option("--board", o.board_file, "Board file (boards/<name>/board.toml): CAN interface, nodes, period")
      ->required();
  app.add_option("--rate-hz", o.rate_hz, "Step rate, Hz: the runtime's loop rate (default: the board's period)")
      ->check(mrd::app::finite_in(100.0, 65535.0, "Hz"));
  app.add_option("--lab-node", o.lab_node, "CAN node id of the laboratory")->capture_default_str()->check(
      CLI::Range(1, 15));
  app.add_option("--can", o.can_interface, "Override the board's CAN interface (e.g. vcan0)");
  app.add_flag("--can-fd", o.can_fd,
               "Command and measurement as 12-byte CAN FD frames (the runtime's --can-fd; the interface needs the FD "
               "MTU, 72: a CAN FD controller or vcan)");
  app.add_option("--tracking-limit-mm", o.tracking_limit_mm, "Stop when |measured - target| exceeds it, mm")
      ->capture_default_str()
      ->check(mrd::app::positive_up_to(1000.0, "mm"));
  app.add_option("--force-limit-kn", o.force_limit_kn,
                 "Stop when |force| exceeds it, kN (the benchmark actuator's 8.9; with --specimen damper 250)")
      ->capture_default_str()
      ->check(mrd::app::positive_up_to(1e4, "kN"))
      ->each([&o](const std::string&) { o.force_limit_given = true; });
  app.add_option("--specimen", o.specimen,
                 "benchmark: the benchmark's actuator and specimen; damper: the thesis's set-up (an actuator with "
                 "--delay-ms and --lag-ms stroking the MR damper, its drive and DAQ)")
      ->capture_default_str()
      ->check(CLI::IsMember({"benchmark", "damper"}));
  app.add_option("--delay-ms", o.delay_ms, "--specimen damper: the actuator's pure delay, ms (whole steps, >= 1)")
      ->capture_default_str()
      ->check(mrd::app::positive_up_to(1000.0, "ms"));
  app.add_option("--lag-ms", o.lag_ms, "--specimen damper: the actuator's first-order servo lag, ms")
      ->capture_default_str()
      ->check(mrd::app::finite_in(0.0, 1000.0, "ms"));
  app.add_flag("--own-clock", o.own_clock,
               "--specimen damper: step every period on this program's own clock (CLOCK_MONOTONIC) with the latest "
               "command, holding the last one when none arrived (default: one step per command); the runtime then "
               "needs --lab-own-clock");
  app.add_option("--idle-years", o.idle_years, "--specimen damper: the damper's idle time before the run, years")
      ->capture_default_str()
      ->check(mrd::app::finite_in(0.0, 1000.0, "years"));
  app.add_option("--plant-seed", o.plant_seed, "Draw the plant from the published uncertainty (0: nominal)")
      ->capture_default_str();
  app.add_option("--noise-seed", o.noise_seed, "Seed of the sensor noise")->capture_default_str();
  app.add_option("--command-timeout-ms", o.command_timeout_ms, "Once running, stop and hold after this long "
                 "without a command, ms")
      ->capture_default_str()
      ->check(CLI::Range(1, 600000));
  app.add_option("--start-timeout-s", o.start_timeout_s, "Give up when no command arrives within this long, s")
      ->capture_default_str()
      ->check(mrd::app::positive_up_to(3600.0, "s"));
  mrd::peers::install_stop_signals();
  if (const auto exit = mrd::peers::parse_options(app, argc, argv, "mrd-rths-lab")) return *exit;
  return run(o);
}
