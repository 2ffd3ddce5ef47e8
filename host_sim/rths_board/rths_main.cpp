/// `mrd-rths`: the RTHS runtime for a Linux board. Reads the board file (CAN
/// interface, controller node, period, real-time settings), loads the
/// benchmark's reference structure (Silva et al. 2020, case 1–4) and the
/// record (scaled, resampled to the loop rate), waits for the laboratory's
/// beacon on the bus (`mrd-rths-lab`), then runs the loop (board_loop.hpp)
/// at the board's period on CLOCK_MONOTONIC (or --rate-hz: 1000 or 4096 Hz,
/// any rate from 100 Hz to 65535 Hz), with SCHED_FIFO and locked memory as the
/// board file asks. After the loop: J1–J9 against the all-numerical
/// reference, and the files of run_files.hpp in --out.
///
/// --specimen damper: the thesis's set-up (damper_loop.hpp): the building
/// (--building FILE, default the thesis's 6-DOF building; its damper
/// placement is the physical part) integrated by its exact ZOH steps at the
/// loop rate, the record scaled to --pga-g, the model-based compensation over
/// the actuator's --delay-ms and --lag-ms, and the board's firmware control
/// task (the same control core and task as mrd-firmware, the board file's
/// [controller], mode and numeric build) beside it on a second socket of the
/// board's CAN interface; the compensator's damper model is the board file's
/// [damper] and [fluid] after --idle-years. Peer: mrd-rths-lab --specimen
/// damper.
///
/// Last line on stdout: "mrd-rths: status=… ticks=… overruns=… worst_late_us=…
/// worst_tick_us=… stale_ticks=… rejected=… tx_errors=…" (and J2 J4 when ok).
///
/// Exit status: 0 the run finished (summary.json written), 1 runtime failure
/// (no CAN, no laboratory), 2 bad input, 3 the run ended early: the
/// laboratory's stop, a silent laboratory, a command beyond the frame's
/// range, or a signal (stop.json written, no summary).

#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <thread>

#include "firmware/app/option_checks.hpp"
#include "firmware/platform/linux/posix_clock.hpp"
#include "firmware/platform/linux/socketcan_bus.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/peers/peer_main_common.hpp"
#include "host_sim/rths/benchmark.hpp"
#include "host_sim/excitation/scaled_motion.hpp"
#include "host_sim/rths_board/board_loop.hpp"
#include "host_sim/rths_board/damper_loop.hpp"
#include "host_sim/rths_board/firmware_beside.hpp"
#include "host_sim/structure/building_file.hpp"
#include "mrd/num/policy.hpp"
#include "mrd/physics/settling.hpp"
#include "mrd/units.hpp"
#include "host_sim/rths_board/run_files.hpp"

namespace {

namespace rb = mrd::rths_board;
constexpr int kExitRuntime = 1;
constexpr int kExitUsage = 2;
constexpr int kExitStopped = 3;

struct Options {
  std::string board_file, record, out, compensator = "adaptive", can_interface;
  int structure_case = 1;
  double rate_hz = 0.0, duration_s = 0.0, scale = mrd::rths::kBenchmarkRecordScale, ready_timeout_s = 30.0;
  int lab_node = rb::kDefaultLabNode;
  int lab_silent_ms = 50;
  // --specimen damper
  std::string specimen = "benchmark", building, mode, compensate = "model";
  double pga_g = 0.1127, delay_ms = 15.0, lag_ms = 2.0, idle_years = 0.0;
  bool lab_own_clock = false;
  bool can_fd = false;
};

/// Waits for the laboratory's beacon on `bus`: 0 when it came, else the exit status.
template <class Loop>
int wait_for_lab(Loop& loop, mrd::posix::SocketCanBus& bus, const Options& o, const mrd::app::BoardConfig& board,
                 double rate_hz, std::uint8_t lab_node) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::duration<double>(o.ready_timeout_s);
  while (!loop.lab_ready()) {
    if (loop.rate_mismatch() != 0) {
      std::fprintf(stderr, "mrd-rths: error: the laboratory steps at %u Hz, the loop runs at %.0f Hz\n",
                   loop.rate_mismatch(), rate_hz);
      return kExitUsage;
    }
    if (mrd::peers::g_peer_stop.load() || std::chrono::steady_clock::now() > give_up) {
      std::fprintf(stderr, "mrd-rths: error: no laboratory beacon (node %u) on %s within %.1f s\n", lab_node,
                   board.can_interface.c_str(), o.ready_timeout_s);
      return kExitRuntime;
    }
    bus.wait_readable(std::chrono::milliseconds(20));
  }
  std::printf("mrd-rths: laboratory ready\n");
  std::fputs(mrd::posix::apply_realtime({board.sched_fifo_priority, board.lock_memory, board.cpu}).c_str(), stdout);
  std::fflush(stdout);
  return 0;
}

/// The thesis's set-up with the firmware's control core in `Policy`.
template <class Policy>
int run_damper_with(const Options& o, const mrd::app::BoardConfig& board, rb::DamperLoopSpec spec,
                    const rb::DamperRunDescription& d) {
  const mrd::hal::CanFilter filters[] = {
      {mrd::protocol::can_id(mrd::protocol::MsgId::kDaqMotion, board.nodes.daq), 0x7FF},
      {mrd::protocol::can_id(mrd::protocol::MsgId::kRthsLabStatus, spec.lab_node), 0x7FF}};
  std::unique_ptr<mrd::posix::SocketCanBus> bus, firmware_bus;
  try {
    bus = std::make_unique<mrd::posix::SocketCanBus>(board.can_interface, filters);
    firmware_bus = std::make_unique<mrd::posix::SocketCanBus>(board.can_interface,
                                                              mrd::app::control_task_filters(board.nodes));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths: error: %s\n", e.what());
    return kExitRuntime;
  }
  mrd::posix::PosixClock clock;
  std::unique_ptr<rb::FirmwareBeside<Policy>> firmware;
  std::unique_ptr<rb::DamperLoop> loop;
  try {
    firmware = std::make_unique<rb::FirmwareBeside<Policy>>(board, *firmware_bus, clock);
    loop = std::make_unique<rb::DamperLoop>(*bus, spec, [&firmware] { return firmware->tick(); });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths: error: %s: %s\n", o.board_file.c_str(), e.what());
    return kExitUsage;
  }
  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / spec.rate_hz));
  std::printf("mrd-rths: board %s, CAN %s (node %u, lab node %u), %.0f Hz (period %lld ns), specimen damper, "
              "building %s (%d DOFs), control %s (%s core), compensation %s, actuator %.1f ms + %.1f ms lag, "
              "%zu ticks of %s at %.4f g\n",
              board.name.c_str(), board.can_interface.c_str(), spec.nodes.controller, spec.lab_node, spec.rate_hz,
              static_cast<long long>(period_ns), d.building.c_str(), spec.building.dofs(), d.control.c_str(),
              board.fixed_point ? "fixed" : "float", d.compensation.c_str(), 1e3 * spec.delay_s, 1e3 * spec.lag_s,
              spec.ground_accel_m_s2.size(), o.record.c_str(), o.pga_g);
  if (const int e = wait_for_lab(*loop, *bus, o, board, spec.rate_hz, spec.lab_node); e != 0) return e;
  // Each tick waits for the laboratory's sample up to half a period.
  const rb::LoopEnd end = loop->run_periodic(clock, period_ns, mrd::peers::g_peer_stop, period_ns / 2);
  const std::string status = rb::loop_end_status(end, loop->lab_reason());
  try {
    if (end == rb::LoopEnd::kFinished) {
      rb::write_finished_damper_run(o.out, d, *loop);
      std::printf("mrd-rths: status=ok %s peak_base_displacement_m=%.6g tracking_rms_pct=%.4f control_rejected=%u\n",
                  rb::timing_fields(*loop).c_str(), loop->peak_base_displacement_m(), loop->rms_tracking_error_pct(),
                  firmware->status().rejected_total());
      return 0;
    }
    rb::write_stopped_damper_run(o.out, d, *loop);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths: error: %s\n", e.what());
    return kExitRuntime;
  }
  std::printf("mrd-rths: status=%s %s end_time_s=%.4f\n", status.c_str(), rb::timing_fields(*loop).c_str(),
              static_cast<double>(loop->ticks()) * loop->dt_s());
  return kExitStopped;
}

/// The board file with --can-interface applied; a CAN interface is required.
mrd::app::BoardConfig load_board(const Options& o) {
  mrd::app::BoardConfig board = mrd::peers::load_board_file(o.board_file);
  if (!o.can_interface.empty()) board.can_interface = o.can_interface;
  if (board.can_interface.empty())
    throw mrd::io::UsageError(o.board_file + ": can.interface: empty (mrd-rths needs a CAN interface)");
  return board;
}

/// The loop's rate: --rate-hz, else the board's control period; 100..65535 Hz.
double loop_rate_hz(const Options& o, const mrd::app::BoardConfig& board) {
  const double rate_hz = o.rate_hz > 0.0 ? o.rate_hz : 1e6 / static_cast<double>(board.period_us);
  if (rate_hz < 100.0 || rate_hz > 65535.0)
    throw mrd::io::UsageError(o.board_file + ": control.period_us: a loop rate of " + std::to_string(rate_hz) +
                              " Hz is outside 100..65535 Hz");
  return rate_hz;
}

int run_damper(const Options& o) {
  mrd::app::BoardConfig board;
  rb::DamperLoopSpec spec;
  rb::DamperRunDescription d;
  try {
    board = load_board(o);
    spec.rate_hz = loop_rate_hz(o, board);
    const double period_us = 1e6 / spec.rate_hz;
    if (std::fabs(period_us - std::round(period_us)) > 1e-9)
      throw mrd::io::UsageError("--rate-hz: " + std::to_string(spec.rate_hz) +
                                " Hz is not a whole number of microseconds (the firmware's period)");
    board.period_us = static_cast<std::uint32_t>(std::lround(period_us));
    if (!o.mode.empty()) {
      const auto m = mrd::control::parse_mode_name(o.mode);
      if (!m) throw mrd::io::UsageError("--mode: expected passive-off, passive-on or semi-active, got '" + o.mode + "'");
      board.mode = *m;
    }
    if (!o.building.empty()) spec.building = mrd::structure::read_building_file(o.building);
    if (spec.building.dampers.size() != 1)
      throw mrd::io::UsageError("--building: " + o.building + " has " + std::to_string(spec.building.dampers.size()) +
                                " damper placements; the RTHS puts one placement (any count) behind the actuator");
    const double step_s = 1.0 / spec.rate_hz;
    const double delay_steps = o.delay_ms * 1e-3 / step_s;
    if (std::fabs(delay_steps - std::round(delay_steps)) > 1e-6 || std::lround(delay_steps) < 1)
      throw mrd::io::UsageError("--delay-ms: " + std::to_string(o.delay_ms) +
                                " ms is not a whole number (at least one) of loop steps");
    spec.delay_s = std::round(delay_steps) * step_s;
    spec.lag_s = o.lag_ms * 1e-3;
    spec.compensate = o.compensate == "model";
    spec.damper = board.damper;
    spec.settling_quotient =
        mrd::physics::settling_quotient_after_idle(mrd::units::years_to_s(o.idle_years), board.settling);
    spec.ground_accel_m_s2 = mrd::excitation::load_scaled_motion(o.record, o.pga_g, step_s, o.duration_s).accel_m_s2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths: error: %s\n", e.what());
    return kExitUsage;
  }
  spec.nodes = board.nodes;
  spec.lab_node = static_cast<std::uint8_t>(o.lab_node);
  spec.lab_silent_ticks = std::max(1, static_cast<int>(std::lround(o.lab_silent_ms * 1e-3 * spec.rate_hz)));
  spec.lab_own_clock = o.lab_own_clock;
  d.board = o.board_file;
  d.record = o.record;
  d.pga_g = o.pga_g;
  d.building = o.building.empty() ? "thesis-6dof" : spec.building.name;
  d.control = mrd::control::mode_name(board.mode);
  d.compensation = o.compensate;
  d.delay_s = spec.delay_s;
  d.lag_s = spec.lag_s;
  d.rate_hz = spec.rate_hz;
  try {
    rb::prepare_out_dir(o.out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths: error: --out: %s\n", e.what());
    return kExitUsage;
  }
  return board.fixed_point ? run_damper_with<mrd::num::Fixed32Policy>(o, board, std::move(spec), d)
                           : run_damper_with<mrd::num::Float32Policy>(o, board, std::move(spec), d);
}

int run(const Options& o) {
  if (o.specimen == "damper" && o.can_fd) {
    std::fprintf(stderr, "mrd-rths: error: --can-fd: only with --specimen benchmark (the thesis's set-up talks the "
                         "closed loop's classic frames)\n");
    return kExitUsage;
  }
  if (o.specimen == "damper") return run_damper(o);
  mrd::app::BoardConfig board;
  rb::BoardLoopSpec spec;
  rb::RunDescription d;
  try {
    board = load_board(o);
    spec.rate_hz = loop_rate_hz(o, board);
    spec.building = mrd::rths::structure_matrices(mrd::rths::benchmark_structure(o.structure_case));
    spec.ground_accel_m_s2 = mrd::rths::benchmark_record(o.record, o.scale, spec.rate_hz);
    if (o.duration_s > 0.0) {
      const auto n = static_cast<std::size_t>(std::llround(o.duration_s * spec.rate_hz));
      if (n < spec.ground_accel_m_s2.size()) spec.ground_accel_m_s2.resize(std::max<std::size_t>(n, 1));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths: error: %s\n", e.what());
    return kExitUsage;
  }
  mrd::rths::compensator_from_name(o.compensator, spec.compensator.kind);
  spec.runtime_node = board.nodes.controller;
  spec.lab_node = static_cast<std::uint8_t>(o.lab_node);
  spec.lab_silent_ticks = std::max(1, static_cast<int>(std::lround(o.lab_silent_ms * 1e-3 * spec.rate_hz)));
  spec.can_fd = o.can_fd;
  d.board = o.board_file;
  d.record = o.record;
  d.record_scale = o.scale;
  d.structure = "benchmark case " + std::to_string(o.structure_case);
  d.compensator = o.compensator;
  d.rate_hz = spec.rate_hz;
  try {
    rb::prepare_out_dir(o.out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths: error: --out: %s\n", e.what());
    return kExitUsage;
  }

  const std::uint32_t lab_ids[] = {mrd::protocol::can_id(mrd::protocol::MsgId::kRthsMeasurement, spec.lab_node),
                                   mrd::protocol::can_id(mrd::protocol::MsgId::kRthsLabStatus, spec.lab_node)};
  const mrd::hal::CanFilter filters[] = {{lab_ids[0], 0x7FF}, {lab_ids[1], 0x7FF}};
  std::unique_ptr<mrd::posix::SocketCanBus> bus;
  try {
    bus = std::make_unique<mrd::posix::SocketCanBus>(board.can_interface, filters, spec.can_fd);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths: error: %s\n", e.what());
    return kExitRuntime;
  }
  auto loop = std::make_unique<rb::BoardLoop>(*bus, spec);
  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / spec.rate_hz));
  std::printf("mrd-rths: board %s, CAN%s %s (node %u, lab node %u), %.0f Hz (period %lld ns), %s, compensator %s, "
              "%zu ticks of %s x %.2f\n",
              board.name.c_str(), spec.can_fd ? " FD" : "", board.can_interface.c_str(), spec.runtime_node, spec.lab_node, spec.rate_hz,
              static_cast<long long>(period_ns), d.structure.c_str(), o.compensator.c_str(),
              spec.ground_accel_m_s2.size(), o.record.c_str(), o.scale);

  if (const int e = wait_for_lab(*loop, *bus, o, board, spec.rate_hz, spec.lab_node); e != 0) return e;

  mrd::posix::PosixClock clock;
  const rb::LoopEnd end = loop->run_periodic(clock, period_ns, mrd::peers::g_peer_stop);
  const std::string status = rb::loop_end_status(end, loop->lab_reason());
  try {
    if (end == rb::LoopEnd::kFinished) {
      const mrd::rths::Criteria c = loop->criteria();
      rb::write_finished_run(o.out, d, *loop, c);
      std::printf("mrd-rths: status=ok %s j1_s=%.4f j2_pct=%.4f j3_pct=%.4f j4_pct=%.4f j5_pct=%.4f\n",
                  rb::timing_fields(*loop).c_str(), c.j[0], c.j[1], c.j[2], c.j[3], c.j[4]);
      return 0;
    }
    rb::write_stopped_run(o.out, d, *loop);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrd-rths: error: %s\n", e.what());
    return kExitRuntime;
  }
  std::printf("mrd-rths: status=%s %s end_time_s=%.4f\n", status.c_str(), rb::timing_fields(*loop).c_str(),
              static_cast<double>(loop->ticks()) * loop->dt_s());
  return kExitStopped;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mrd-rths: real-time hybrid simulation on a Linux board: the numerical substructure at the loop rate, "
               "the actuator's command and the laboratory's measurements over CAN (peer: mrd-rths-lab).",
               "mrd-rths"};
  Options o;
  app.add_option("--board", o.board_file, "Board file (boards/<name>/board.toml): CAN, node, period, real time")
      ->required();
  app.add_option("--record", o.record, "Ground-motion record: CSV (time_s,accel_m_s2) or PEER .AT2")->required();
  app.add_option("--out", o.out, "Folder for summary.json, tracking.csv, coefficients.csv (or stop.json)")
      ->required();
  app.add_option("--specimen", o.specimen,
                 "benchmark: the virtual RTHS benchmark (Silva et al. 2020); damper: the thesis's set-up (the MR "
                 "damper in the laboratory, the building numerical, the board's control task beside it)")
      ->capture_default_str()
      ->check(CLI::IsMember({"benchmark", "damper"}));
  app.add_option("--building", o.building,
                 "--specimen damper: building file (TOML, README \"Your building\"; one damper placement, any "
                 "isolators); default: the thesis building of Table 6.1");
  app.add_option("--mode", o.mode, "--specimen damper: override the board's mode: passive-off | passive-on | "
                 "semi-active");
  app.add_option("--pga-g", o.pga_g, "--specimen damper: scale the record to this PGA, g (Table 6.3: 0.1127)")
      ->capture_default_str()
      ->check(mrd::app::positive_up_to(100.0, "g"));
  app.add_option("--delay-ms", o.delay_ms, "--specimen damper: the actuator's identified delay, ms (whole steps)")
      ->capture_default_str()
      ->check(mrd::app::positive_up_to(1000.0, "ms"));
  app.add_option("--lag-ms", o.lag_ms, "--specimen damper: the actuator's identified servo lag, ms")
      ->capture_default_str()
      ->check(mrd::app::finite_in(0.0, 1000.0, "ms"));
  app.add_option("--compensate", o.compensate, "--specimen damper: model (the prediction over the delay) or none")
      ->capture_default_str()
      ->check(CLI::IsMember({"model", "none"}));
  app.add_flag("--lab-own-clock", o.lab_own_clock,
               "--specimen damper: the laboratory steps on its own clock (mrd-rths-lab --own-clock): a sample is "
               "fresh when newer than the last one taken, whatever its counter");
  app.add_option("--idle-years", o.idle_years, "--specimen damper: the damper's idle time before the run, years")
      ->capture_default_str()
      ->check(mrd::app::finite_in(0.0, 1000.0, "years"));
  app.add_option("--case", o.structure_case, "Benchmark structure case 1-4")->capture_default_str()->check(
      CLI::Range(1, 4));
  app.add_option("--compensator", o.compensator, "none, sample, polynomial, adaptive or model")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "sample", "polynomial", "adaptive", "model"}));
  app.add_option("--rate-hz", o.rate_hz, "Loop rate, Hz (default: the board's period; 1000 or 4096)")
      ->check(mrd::app::finite_in(100.0, 65535.0, "Hz"));
  app.add_option("--duration-s", o.duration_s, "Run the record's first seconds only, s")
      ->check(mrd::app::positive_up_to(mrd::app::kMaxProgramTime_s, "s"));
  app.add_option("--scale", o.scale, "Factor on the record's accelerations (the benchmark's 0.4)")
      ->capture_default_str()
      ->check(mrd::app::positive_up_to(100.0, ""));
  app.add_option("--lab-node", o.lab_node, "CAN node id of the laboratory")->capture_default_str()->check(
      CLI::Range(1, 15));
  app.add_option("--can", o.can_interface, "Override the board's CAN interface (e.g. vcan0)");
  app.add_flag("--can-fd", o.can_fd,
               "Command and measurement as 12-byte CAN FD frames with bit-rate switch (for 4096 Hz on one bus; "
               "the interface needs the FD MTU, 72: a CAN FD controller or vcan); the laboratory needs --can-fd too");
  app.add_option("--ready-timeout-s", o.ready_timeout_s, "Wait this long for the laboratory's beacon, s")
      ->capture_default_str()
      ->check(mrd::app::positive_up_to(3600.0, "s"));
  app.add_option("--lab-silent-ms", o.lab_silent_ms, "End the run after this long without a fresh measurement, ms")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  mrd::peers::install_stop_signals();
  if (const auto exit = mrd::peers::parse_options(app, argc, argv, "mrd-rths")) return *exit;
  return run(o);
}
