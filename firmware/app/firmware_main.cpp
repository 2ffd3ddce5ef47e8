/// `mrd-firmware`: the controller for a Linux board. Reads the board file,
/// opens the CAN interface (SocketCAN) and the GPIO lines (libgpiod; none
/// when the board file says `[gpio] fitted = false`), asks for SCHED_FIFO and
/// locked memory, and hands them to the board runtime (firmware/app/runtime),
/// which runs the control task at the board's period on CLOCK_MONOTONIC, or
/// in lockstep with a simulated plant (one tick per complete set of inputs).
/// Exit status: 0 done, 1 runtime failure (no CAN, no GPIO), 2 bad input.

#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "firmware/app/board_config.hpp"
#include "firmware/app/option_checks.hpp"
#include "firmware/app/no_lines_fitted.hpp"
#include "firmware/app/runtime.hpp"
#include "firmware/core/controller_config.hpp"
#include "firmware/core/damper_controller.hpp"
#include "firmware/platform/linux/posix_clock.hpp"
#include "firmware/platform/linux/socketcan_bus.hpp"
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

/// The runtime's lines on stdout, flushed one by one.
class StdoutLog final : public mrd::app::RuntimeLog {
 public:
  void line(const char* text) noexcept override {
    std::fputs(text, stdout);
    std::fputc('\n', stdout);
    std::fflush(stdout);
  }
};

/// Thrown when the board file asks for what this build cannot do.
struct BuildError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The board's discrete lines: libgpiod on the board file's chip, or none.
std::unique_ptr<mrd::hal::DigitalIo> open_lines(const mrd::app::BoardConfig& board) {
  if (!board.gpio_fitted) {
    std::printf("mrd-firmware: [gpio] fitted = false: no discrete lines (drive-enable and maintenance-due not "
                "driven, drive-fault reads inactive)\n");
    return std::make_unique<mrd::app::NoLinesFitted>();
  }
#ifdef MRD_HAVE_GPIOD
  mrd::posix::GpiodSpec g;
  g.chip = board.gpio_chip;
  auto line = [](const mrd::app::GpioLine& l) { return mrd::posix::GpiodLineSpec{l.offset, l.name, l.active_low}; };
  g.drive_enable = line(board.drive_enable);
  g.drive_fault = line(board.drive_fault);
  g.maintenance_due = line(board.maintenance_due);
  auto gpiod = std::make_unique<mrd::posix::GpiodIo>(g);
  std::printf("mrd-firmware: gpio %s\n", gpiod->describe().c_str());
  return gpiod;
#else
  throw BuildError("the board file has [gpio] lines but this build has no libgpiod");
#endif
}

/// The start-up lines: board, mode, period, bus, pacing, and real-time settings.
void announce(const mrd::app::BoardConfig& board, const Options& o) {
  std::printf("mrd-firmware: board %s, %s, %s, period %u us, CAN %s (node %u), %s\n", board.name.c_str(),
              mrd::control::mode_name(board.mode), board.fixed_point ? "fixed point" : "float", board.period_us,
              board.can_interface.c_str(), board.nodes.controller,
              o.lockstep ? "lockstep with the plant" : "fixed period on CLOCK_MONOTONIC");
  if (o.lockstep) {
    // Paced by the plant, not by time: priorities would only add context switches.
    std::printf("realtime: not applied in lockstep (the simulated plant paces the loop)\n");
  } else {
    std::fputs(mrd::posix::apply_realtime({board.sched_fifo_priority, board.lock_memory, board.cpu}).c_str(), stdout);
  }
  std::fflush(stdout);
}

template <class Policy>
int run(const mrd::app::BoardConfig& board, const Options& o) {
  using Core = mrd::fw::DamperController<Policy>;
  auto core = std::make_unique<Core>();
  if (const auto e = core->init(mrd::fw::default_controller_config(board.mode, board.period_s()));
      e != mrd::fw::ConfigError::kNone) {
    std::fprintf(stderr, "mrd-firmware: error: %s: the control core rejects the configuration (%s)\n",
                 o.board_file.c_str(), mrd::fw::config_error_name(e));
    return kExitUsage;
  }

  std::unique_ptr<mrd::posix::SocketCanBus> bus;
  std::unique_ptr<mrd::hal::DigitalIo> io;
  try {
    bus = std::make_unique<mrd::posix::SocketCanBus>(board.can_interface, mrd::app::control_task_filters(board.nodes));
    io = open_lines(board);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-firmware: error: %s\n", e.what());
    return kExitRuntime;
  }

  mrd::posix::PosixClock clock;
  StdoutLog log;
  mrd::app::RuntimeConfig rc;
  rc.period_ns = static_cast<std::int64_t>(board.period_us) * 1000;
  rc.max_ticks = o.ticks;
  rc.report_every_ns = static_cast<std::int64_t>(o.report_every_s * 1e9);
  rc.lockstep_idle_exit_ns = static_cast<std::int64_t>(o.idle_exit_s * 1e9);
  mrd::app::RuntimePorts ports{clock, *bus, *io};
  ports.log = &log;
  auto runtime = std::make_unique<mrd::app::BoardRuntime<Core>>(*core, ports, board.task_config(), rc);
  announce(board, o);
  if (o.lockstep) {
    runtime->run_lockstep(g_stop);
  } else {
    runtime->run_periodic(g_stop);
  }
  return 0;
}

/// The board file with the command line's overrides; nullopt after printing why not.
std::optional<mrd::app::BoardConfig> board_of(const Options& o) {
  mrd::app::BoardConfig board;
  try {
    board = mrd::app::load_board_config(o.board_file);
  } catch (const mrd::app::BoardConfigError& e) {
    std::fprintf(stderr, "mrd-firmware: error: %s\n", e.what());
    return std::nullopt;
  }
  if (!o.mode.empty()) {
    const auto mode = mrd::control::parse_mode_name(o.mode);
    if (!mode) {
      std::fprintf(stderr, "mrd-firmware: error: --mode: expected passive-off, passive-on or semi-active, got '%s'\n",
                   o.mode.c_str());
      return std::nullopt;
    }
    board.mode = *mode;
  }
  if (!o.can_interface.empty()) board.can_interface = o.can_interface;
  if (board.can_interface.empty()) {
    std::fprintf(stderr, "mrd-firmware: error: %s: can.interface: empty (the in-process sim board runs as "
                 "mrd-sim-board, not mrd-firmware)\n", o.board_file.c_str());
    return std::nullopt;
  }
  return board;
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
      ->capture_default_str()
      ->check(mrd::app::positive_up_to(mrd::app::kMaxProgramTime_s, "s"));
  app.add_option("--report-every-s", o.report_every_s, "Print the summary line this often, s (default: at exit only)")
      ->check(mrd::app::positive_up_to(mrd::app::kMaxProgramTime_s, "s"));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "mrd-firmware: error: %s\n", e.what());
    return kExitUsage;
  }
  const std::optional<mrd::app::BoardConfig> board = board_of(o);
  if (!board) return kExitUsage;

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  return board->fixed_point ? run<mrd::num::Fixed32Policy>(*board, o) : run<mrd::num::Float32Policy>(*board, o);
}
