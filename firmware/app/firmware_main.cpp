/// `mrd-firmware`: the controller for a Linux board. Reads the board file,
/// opens the CAN interface (SocketCAN) and the GPIO lines (libgpiod), asks
/// for SCHED_FIFO and locked memory, and runs the control task at the board's
/// period on CLOCK_MONOTONIC (absolute deadlines, overruns counted), or in
/// lockstep with a simulated plant (one tick per complete set of inputs).
/// Exit status: 0 done, 1 runtime failure (no CAN, no GPIO), 2 bad input.

#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>

#include "firmware/app/board_config.hpp"
#include "firmware/app/control_task.hpp"
#include "firmware/app/core_config.hpp"
#include "firmware/app/periodic_schedule.hpp"
#include "firmware/core/damper_controller.hpp"
#include "firmware/platform/linux/posix_clock.hpp"
#include "firmware/platform/linux/socketcan_bus.hpp"
#include "firmware/platform/sim/memory_io.hpp"
#ifdef MRD_HAVE_GPIOD
#include "firmware/platform/linux/gpiod_io.hpp"
#endif

namespace {

constexpr int kExitRuntime = 1;
constexpr int kExitUsage = 2;

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop.store(true); }

struct Options {
  std::string board_file;
  std::string mode;
  std::string can_interface;
  bool lockstep = false;
  std::uint64_t ticks = 0;
  double idle_exit_s = 2.0;
  double report_every_s = 0.0;
};

struct LoopResult {
  std::uint32_t overruns = 0;
  std::int64_t worst_late_ns = 0;
};

template <class Task>
void print_summary(const Task& task, const LoopResult& r, std::uint64_t enable_changes) {
  const mrd::app::ControlTaskStatus& s = task.status();
  std::printf(
      "mrd-firmware: summary ticks=%llu overruns=%u worst_late_us=%.1f frames_rx=%llu accepted=%llu rejected=%u "
      "(checksum %u, length %u, range %u, field %u, repeated %u, stale %u) unexpected_ids=%u tx_errors=%u "
      "sensor_timeout_ticks=%u drive_fault_ticks=%u bus_error_ticks=%u gpio_errors=%u enable_changes=%llu "
      "last_command_a=%.3f drive_enable=%d bus=%s\n",
      static_cast<unsigned long long>(s.ticks), r.overruns, static_cast<double>(r.worst_late_ns) / 1e3,
      static_cast<unsigned long long>(s.frames_received), static_cast<unsigned long long>(s.frames_accepted),
      s.rejected_total(), s.rejected(mrd::protocol::DecodeError::kBadChecksum),
      s.rejected(mrd::protocol::DecodeError::kWrongLength), s.rejected(mrd::protocol::DecodeError::kOutOfRange),
      s.rejected(mrd::protocol::DecodeError::kBadField), s.repeated_counters, s.stale_counters, s.unexpected_ids,
      s.tx_errors, s.sensor_timeout_ticks, s.drive_fault_ticks, s.bus_error_ticks, s.gpio_errors,
      static_cast<unsigned long long>(enable_changes), static_cast<double>(s.last_output.current_command_a),
      s.last_output.drive_enable ? 1 : 0, mrd::hal::bus_state_name(s.bus_state));
}

template <class Policy>
int run(const mrd::app::BoardConfig& board, const Options& o) {
  using Core = mrd::fw::DamperController<Policy>;
  auto core = std::make_unique<Core>();
  if (const auto e = core->init(mrd::app::core_config(board)); e != mrd::fw::ConfigError::kNone) {
    std::fprintf(stderr, "mrd-firmware: error: %s: the control core rejects the configuration (%s)\n",
                 o.board_file.c_str(), mrd::fw::config_error_name(e));
    return kExitUsage;
  }

  std::unique_ptr<mrd::posix::SocketCanBus> bus;
  std::unique_ptr<mrd::hal::DigitalIo> io;
  try {
    const auto filters = mrd::app::control_task_filters(board.nodes);
    bus = std::make_unique<mrd::posix::SocketCanBus>(board.can_interface, filters);
    if (board.gpio_enabled) {
#ifdef MRD_HAVE_GPIOD
      mrd::posix::GpiodSpec g;
      g.chip = board.gpio_chip;
      auto line = [](const mrd::app::GpioLine& l) { return mrd::posix::GpiodLineSpec{l.offset, l.name, l.active_low}; };
      g.drive_enable = line(board.drive_enable);
      g.drive_fault = line(board.drive_fault);
      g.maintenance_due = line(board.maintenance_due);
      auto gpiod = std::make_unique<mrd::posix::GpiodIo>(g);
      std::printf("mrd-firmware: gpio %s\n", gpiod->describe().c_str());
      io = std::move(gpiod);
#else
      std::fprintf(stderr, "mrd-firmware: error: the board file has [gpio] but this build has no libgpiod\n");
      return kExitRuntime;
#endif
    } else {
      io = std::make_unique<mrd::sim::MemoryIo>();
      std::printf("mrd-firmware: no [gpio] in the board file: drive-enable and fault lines kept in memory\n");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-firmware: error: %s\n", e.what());
    return kExitRuntime;
  }

  mrd::app::ControlTask<Core> task(*core, *bus, *io, board.task_config());
  task.reset();
  std::printf("mrd-firmware: board %s, %s, %s, period %u us, CAN %s (node %u), %s\n", board.name.c_str(),
              mrd::control::mode_name(board.mode), board.fixed_point ? "fixed point" : "float",
              board.period_us, board.can_interface.c_str(), board.nodes.controller,
              o.lockstep ? "lockstep with the plant" : "fixed period on CLOCK_MONOTONIC");
  if (o.lockstep) {
    // Paced by the plant, not by time: priorities would only add context switches.
    std::printf("realtime: not applied in lockstep (the simulated plant paces the loop)\n");
  } else {
    std::fputs(mrd::posix::apply_realtime({board.sched_fifo_priority, board.lock_memory, board.cpu}).c_str(), stdout);
  }
  std::fflush(stdout);

  mrd::posix::PosixClock clock;
  LoopResult r;
  bool enable = false;
  std::uint64_t enable_changes = 0;
  auto note_enable = [&] {
    const bool now = task.status().last_output.drive_enable;
    if (task.tick() == 1 || now != enable) {
      if (task.tick() != 1) ++enable_changes;
      std::printf("mrd-firmware: tick %llu: drive-enable line %s\n", static_cast<unsigned long long>(task.tick() - 1),
                  now ? "active" : "inactive");
      std::fflush(stdout);
      enable = now;
    }
  };
  const std::int64_t period_ns = static_cast<std::int64_t>(board.period_us) * 1000;
  const std::int64_t report_ns = static_cast<std::int64_t>(o.report_every_s * 1e9);
  std::int64_t next_report = clock.now_ns() + report_ns;
  auto more = [&] { return !g_stop.load() && (o.ticks == 0 || task.tick() < o.ticks); };

  if (o.lockstep) {
    const auto idle = std::chrono::nanoseconds(static_cast<std::int64_t>(o.idle_exit_s * 1e9));
    std::int64_t last_rx = clock.now_ns();
    while (more()) {
      task.poll_rx();
      if (task.lockstep_ready()) {
        task.step_tick();
        note_enable();
        last_rx = clock.now_ns();
        continue;
      }
      if (!bus->wait_readable(std::chrono::milliseconds(100))) {
        const bool started = task.tick() > 0;
        if (clock.now_ns() - last_rx > (started ? idle.count() : 30 * idle.count())) {
          std::printf("mrd-firmware: lockstep: no complete tick for %.1f s after tick %llu: the plant has finished\n",
                      static_cast<double>(clock.now_ns() - last_rx) / 1e9,
                      static_cast<unsigned long long>(task.tick()));
          break;
        }
      }
    }
  } else {
    mrd::app::PeriodicSchedule schedule(period_ns, clock.now_ns());
    while (more()) {
      task.run_tick();
      note_enable();
      const std::int64_t deadline = schedule.after_tick(clock.now_ns());
      r.overruns = schedule.overruns();
      r.worst_late_ns = schedule.worst_late_ns();
      task.set_overruns(r.overruns);
      clock.sleep_until_ns(deadline);
      if (report_ns > 0 && clock.now_ns() >= next_report) {
        print_summary(task, r, enable_changes);
        std::fflush(stdout);
        next_report += report_ns;
      }
    }
  }
  print_summary(task, r, enable_changes);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mrd-firmware: the MR-damper controller for a Linux board (SocketCAN + libgpiod).", "mrd-firmware"};
  Options o;
  app.add_option("--board", o.board_file, "Board file (boards/<name>/board.toml)")->required();
  app.add_option("--mode", o.mode, "Override the board's control mode: passive-off | passive-on | semi-active");
  app.add_option("--can", o.can_interface, "Override the board's CAN interface (e.g. vcan0)");
  app.add_flag("--lockstep", o.lockstep,
               "Step once per complete set of plant inputs (simulated plant) instead of on the clock");
  app.add_option("--ticks", o.ticks, "Stop after this many control ticks (default: run until SIGTERM)");
  app.add_option("--idle-exit-s", o.idle_exit_s, "Lockstep: stop when no tick completes for this long, s")
      ->capture_default_str();
  app.add_option("--report-every-s", o.report_every_s, "Print the summary line this often, s (0: at exit only)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "mrd-firmware: error: %s\n", e.what());
    return kExitUsage;
  }

  mrd::app::BoardConfig board;
  try {
    board = mrd::app::load_board_config(o.board_file);
  } catch (const mrd::app::BoardConfigError& e) {
    std::fprintf(stderr, "mrd-firmware: error: %s\n", e.what());
    return kExitUsage;
  }
  if (!o.mode.empty() && !mrd::app::parse_mode_name(o.mode, board.mode)) {
    std::fprintf(stderr, "mrd-firmware: error: --mode: expected passive-off, passive-on or semi-active, got '%s'\n",
                 o.mode.c_str());
    return kExitUsage;
  }
  if (!o.can_interface.empty()) board.can_interface = o.can_interface;
  if (board.can_interface.empty()) {
    std::fprintf(stderr, "mrd-firmware: error: %s: can.interface: empty (the in-process sim board runs as "
                 "mrd-sim-board, not mrd-firmware)\n", o.board_file.c_str());
    return kExitUsage;
  }

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  return board.fixed_point ? run<mrd::num::Fixed32Policy>(board, o) : run<mrd::num::Float32Policy>(board, o);
}
