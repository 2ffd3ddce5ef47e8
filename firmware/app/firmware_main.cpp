/// `mrd-firmware`: the controller for a Linux board. Reads the board file,
/// opens the CAN interface (SocketCAN) and the GPIO lines (libgpiod; none
/// when the board file says `[gpio] fitted = false`), asks for SCHED_FIFO and
/// locked memory, and hands them to the board runtime (firmware/app/runtime),
/// which runs the control task at the board's period on CLOCK_MONOTONIC, or
/// in lockstep with a simulated plant (one tick per complete set of inputs).
///
/// Free-running, the runtime also runs the mixing task (idle-time estimator
/// and mixing scheduler) in the board's numeric build: its state is restored
/// at start from the board's state file ([state] path) with the time the
/// board was off (CLOCK_REALTIME against the record's stamp) counted as idle
/// time, saved by a writer thread (never inside a tick) every save_every_s,
/// after a confirmed mixing cycle and at exit. In lockstep (a simulated plant
/// replaying an earthquake from its own idle time) the mixing task does not run.
///
/// Exit status: 0 done, 1 runtime failure (no CAN, no GPIO), 2 bad input,
/// 3 (--print-state) the state record is unreadable or corrupt.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "firmware/app/board_config.hpp"
#include "firmware/app/option_checks.hpp"
#include "firmware/app/no_lines_fitted.hpp"
#include "firmware/app/runtime.hpp"
#include "firmware/core/controller_config.hpp"
#include "firmware/core/damper_controller.hpp"
#include "firmware/core/idle_estimator.hpp"
#include "firmware/core/state_store.hpp"
#include "firmware/platform/linux/background_state_store.hpp"
#include "firmware/platform/linux/file_state_store.hpp"
#include "firmware/platform/linux/posix_clock.hpp"
#include "firmware/platform/linux/regular_file.hpp"
#include "firmware/platform/linux/socketcan_bus.hpp"
#include "mrd/units.hpp"
#ifdef MRD_HAVE_GPIOD
#include "firmware/platform/linux/gpiod_io.hpp"
#endif

namespace {

constexpr int kExitRuntime = 1;
constexpr int kExitUsage = 2;
constexpr int kExitBadState = 3;

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
  std::string state_path;
  double save_every_s = 0.0;
  bool log_saves = false;
  bool print_state = false;
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

/// "mrd-firmware: state saved seq=N" after each write (the writer thread).
void log_save(mrd::hal::StoreStatus status, const mrd::hal::StateRecord& record) {
  mrd::fw::PersistedIdleState s;
  const bool readable = mrd::fw::decode_state(record, s) == mrd::fw::DecodeStatus::kOk;
  if (status == mrd::hal::StoreStatus::kOk && readable) {
    std::printf("mrd-firmware: state saved seq=%u\n", s.save_sequence);
  } else {
    std::printf("mrd-firmware: state save failed: %s\n", mrd::hal::store_status_name(status));
  }
  std::fflush(stdout);
}

/// The wall clock in the mixing task's numbers: seconds (reference build) or milliseconds.
template <class Mixing>
typename Mixing::Rtc rtc_of(double unix_s) {
  if constexpr (std::is_floating_point_v<typename Mixing::Rtc>) {
    return unix_s;
  } else {
    return std::llround(unix_s * 1e3);
  }
}

/// Restores the estimator's state and prints the boot line.
template <class Mixing>
void boot_mixing(Mixing& mixing, mrd::hal::StateStore& store, const mrd::hal::WallClock& rtc, const std::string& path) {
  double unix_s = 0.0;
  const bool rtc_valid = rtc.now_s(unix_s);
  const mrd::fw::IdleBootReport rep = mixing.boot(store, 0, rtc_of<Mixing>(unix_s), rtc_valid);
  const auto& e = mixing.estimator().estimate();
  std::printf("mrd-firmware: boot: state %s: %s%s%s off_days=%.4f equivalent_idle_years=%.6f sq=%.4f pr=%.4f "
              "capacity=%.4f cycles=%u rtc=%s idle_flags=0x%x\n",
              path.c_str(), mrd::hal::store_status_name(rep.load),
              rep.load == mrd::hal::StoreStatus::kOk ? " " : "",
              rep.load == mrd::hal::StoreStatus::kOk ? mrd::fw::decode_status_name(rep.decode) : "",
              rep.offline_s / 86400.0, static_cast<double>(e.equivalent_idle_s) / mrd::units::kSecondsPerYear,
              static_cast<double>(e.sq), static_cast<double>(e.participant_ratio),
              static_cast<double>(e.capacity_fraction), e.mixing_cycles, rtc_valid ? "valid" : "invalid",
              static_cast<unsigned>(e.flags));
  if (e.flags & mrd::fw::kIdleAssumedSettled)
    std::printf("mrd-firmware: boot: no usable state or clock: the damper is taken as fully settled (worst case)\n");
  std::fflush(stdout);
}

/// After the boot line: why the reader refused the state file, when it did
/// (the boot line says io-error; the worst case is then assumed).
void report_unread_state(const mrd::posix::FileStateStore& file) {
  const mrd::posix::FileCheck& c = file.last_load();
  if (c.ok() || c.problem == mrd::posix::FileProblem::kMissing) return;
  std::printf("mrd-firmware: boot: state %s: %s%s\n", file.path().c_str(),
              mrd::posix::problem_text(c, mrd::hal::kStateRecordSize).c_str(),
              mrd::posix::is_non_regular(c.problem) ? " (not read, and never replaced by a save)" : "");
  std::fflush(stdout);
}

/// What the board's fluid and damper make of a saved equivalent idle time τ:
/// T_max (Eq. 5.4, or the fluid's measured one), SQ (Eq. 5.5), a_PR
/// (Eq. 5.6), the capacity (Eq. 5.10–5.12) and how long until the capacity
/// falls to the scheduler's threshold without motion (a_PR⁻¹ of the
/// threshold's PR, less τ).
void print_idle_physics(const mrd::app::BoardConfig& board, double idle_s) {
  mrd::fw::SettlingModel model;
  if (!model.init(board.mixing_task_config().estimator.model)) {
    std::printf("mrd-firmware: fluid %s, damper %s: the settling model rejects the configuration\n",
                board.fluid_name.c_str(), board.damper_name.c_str());
    return;
  }
  model.reset(idle_s, 0.0);
  const double due_idle_s = model.idle_of_pr(model.pr_of_capacity(board.mixing.capacity_threshold));
  const double y = mrd::units::kSecondsPerYear;
  std::printf("mrd-firmware: fluid %s, damper %s: t_max_years=%.6f sq=%.6f pr=%.6f capacity=%.6f "
              "below_threshold_in_years=%.6f (threshold %.3f)\n",
              board.fluid_name.c_str(), board.damper_name.c_str(), model.max_settling_time_s() / y,
              model.sq_of_idle(idle_s), model.participant_ratio(0.0), model.capacity_fraction(0.0),
              std::max(0.0, due_idle_s - idle_s) / y, board.mixing.capacity_threshold);
}

/// --print-state: the record in the state file, without CAN or GPIO, and
/// what the board's fluid and damper make of it. A path that is not a
/// regular file is a usage error (exit 2).
int print_state(const mrd::app::BoardConfig& board) {
  const std::string& path = board.state_path;
  mrd::posix::FileStateStore file(path);
  mrd::hal::StateRecord record{};
  const mrd::hal::StoreStatus st = file.load(record);
  if (st == mrd::hal::StoreStatus::kMissing) {
    std::printf("mrd-firmware: state %s: missing\n", path.c_str());
    return 0;
  }
  if (mrd::posix::is_non_regular(file.last_load().problem)) {
    std::fprintf(stderr, "mrd-firmware: error: state %s: %s\n", path.c_str(),
                 mrd::posix::problem_text(file.last_load(), mrd::hal::kStateRecordSize).c_str());
    return kExitUsage;
  }
  if (st != mrd::hal::StoreStatus::kOk) {
    const std::string why = mrd::posix::problem_text(file.last_load(), mrd::hal::kStateRecordSize);
    std::printf("mrd-firmware: state %s: corrupt (%s%s%s)\n", path.c_str(), mrd::hal::store_status_name(st),
                why.empty() ? "" : ": ", why.c_str());
    return kExitBadState;
  }
  mrd::fw::PersistedIdleState s;
  const mrd::fw::DecodeStatus d = mrd::fw::decode_state(record, s);
  if (d != mrd::fw::DecodeStatus::kOk) {
    std::printf("mrd-firmware: state %s: corrupt (%s)\n", path.c_str(), mrd::fw::decode_status_name(d));
    return kExitBadState;
  }
  // The record's line last: scripts read the outcome from the last line.
  print_idle_physics(board, static_cast<double>(s.equivalent_idle_ms) * 1e-3);
  std::printf("mrd-firmware: state %s: ok seq=%u cycles=%u idle_years=%.6f rtc_ms=%lld lifetime_volume_m3=%.6f\n",
              path.c_str(), s.save_sequence, s.mixing_cycles,
              static_cast<double>(s.equivalent_idle_ms) * 1e-3 / mrd::units::kSecondsPerYear,
              static_cast<long long>(s.rtc_ms), static_cast<double>(s.lifetime_volume) * mrd::fw::kStateVolumeCountM3);
  return 0;
}

template <class Policy>
int run(const mrd::app::BoardConfig& board, const Options& o) {
  using Core = mrd::fw::DamperController<Policy>;
  auto core = std::make_unique<Core>();
  if (const auto e = core->init(board.controller_config());
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

  // The mixing task and its state (free-running only).
  using Mixing = mrd::app::BasicMixingTask<Policy>;
  std::unique_ptr<Mixing> mixing;
  mrd::posix::FileStateStore file_store(board.state_path);
  std::unique_ptr<mrd::posix::BackgroundStateStore> store;
  mrd::posix::PosixWallClock rtc;
  if (!o.lockstep) {
    mixing = std::make_unique<Mixing>();
    if (!mixing->init(board.mixing_task_config())) {
      std::fprintf(stderr, "mrd-firmware: error: %s: [mixing]/[state]: the idle-time estimator or the mixing "
                   "scheduler rejects the configuration\n", o.board_file.c_str());
      return kExitUsage;
    }
    mrd::posix::BackgroundStateStore::WriteListener listener;
    if (o.log_saves) listener = log_save;
    store = std::make_unique<mrd::posix::BackgroundStateStore>(file_store, listener);
    boot_mixing(*mixing, *store, rtc, board.state_path);
    report_unread_state(file_store);
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
  if (mixing) {
    ports.store = store.get();
    ports.rtc = &rtc;
  }
  auto runtime = std::make_unique<mrd::app::BoardRuntime<Core, Mixing>>(*core, ports, board.task_config(), rc);
  if (mixing) runtime->attach_mixing(mixing.get());
  announce(board, o);
  if (o.lockstep) {
    runtime->run_lockstep(g_stop);
  } else {
    runtime->run_periodic(g_stop);
  }
  if (mixing) {
    const bool saved = runtime->save_now();
    store->flush();
    std::printf("mrd-firmware: state %s at exit: %s (%llu writes, %llu failed)\n", board.state_path.c_str(),
                saved ? "saved" : "not saved", static_cast<unsigned long long>(store->writes()),
                static_cast<unsigned long long>(store->failed_writes()));
  }
  return 0;
}

/// The board file, read under the reader policy (a regular file of at most
/// app::kMaxBoardFileBytes, opened without blocking) and parsed, its state
/// path checked to be a regular file or absent; throws app::BoardConfigError.
mrd::app::BoardConfig load_board(const std::string& path) {
  std::string text;
  if (const auto c = mrd::posix::read_regular_file(path.c_str(), mrd::app::kMaxBoardFileBytes, text); !c.ok()) {
    throw mrd::app::BoardConfigError(path + ": " + mrd::posix::problem_text(c, mrd::app::kMaxBoardFileBytes));
  }
  return mrd::app::parse_board_config(text, path, mrd::posix::non_regular_problem);
}

/// The board file with the command line's overrides; nullopt after printing why not.
std::optional<mrd::app::BoardConfig> board_of(const Options& o) {
  mrd::app::BoardConfig board;
  try {
    board = load_board(o.board_file);
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
  if (!o.state_path.empty()) {
    if (o.state_path.front() != '/' || o.state_path.back() == '/') {
      std::fprintf(stderr, "mrd-firmware: error: --state: expected an absolute file path, got '%s'\n",
                   o.state_path.c_str());
      return std::nullopt;
    }
    if (const std::string problem = mrd::posix::non_regular_problem(o.state_path); !problem.empty()) {
      std::fprintf(stderr, "mrd-firmware: error: --state: %s: %s\n", o.state_path.c_str(), problem.c_str());
      return std::nullopt;
    }
    board.state_path = o.state_path;
  }
  if (o.save_every_s > 0.0) board.save_every_s = o.save_every_s;
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
  app.add_option("--state", o.state_path, "Override the board's state file ([state] path), an absolute path");
  app.add_option("--save-every-s", o.save_every_s, "Override how often the state is saved ([state] save_every_s), s")
      ->check(mrd::app::positive_up_to(86400.0, "s"));
  app.add_flag("--log-saves", o.log_saves, "Print a line after each save of the state");
  app.add_flag("--print-state", o.print_state, "Print the state file's record and exit (no CAN, no GPIO)");
  try {
    app.parse(argc, argv);
    mrd::app::refuse_empty_values(app);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "mrd-firmware: error: %s\n", e.what());
    return kExitUsage;
  }
  const std::optional<mrd::app::BoardConfig> board = board_of(o);
  if (!board) return kExitUsage;
  if (o.print_state) return print_state(*board);

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  return board->fixed_point ? run<mrd::num::Fixed32Policy>(*board, o) : run<mrd::num::Float32Policy>(*board, o);
}
