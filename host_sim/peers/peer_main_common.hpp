#pragma once
/// What the peer programs share: signal handling, the board file's node ids
/// and period, and the one-line summary format the emulated-board test reads.

#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <optional>
#include <string>

#include "firmware/app/board_config.hpp"
#include "firmware/app/option_checks.hpp"
#include "firmware/platform/linux/regular_file.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/plant/plant.hpp"

namespace mrd::peers {

inline std::atomic<bool> g_peer_stop{false};
extern "C" inline void peer_on_signal(int) { g_peer_stop.store(true); }

inline void install_stop_signals() {
  std::signal(SIGINT, peer_on_signal);
  std::signal(SIGTERM, peer_on_signal);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
}

/// Parses the command line as `mrd` does: a bad option prints one line
/// "<who>: error: <option>: <problem>" on stderr; returns the exit status to
/// leave with (0 after --help, 2 for a bad option), or nullopt to go on.
inline std::optional<int> parse_options(CLI::App& app, int argc, char** argv, const char* who) {
  try {
    app.parse(argc, argv);
    app::refuse_empty_values(app);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "%s: error: %s\n", who, e.what());
    return 2;
  }
  return std::nullopt;
}

/// The board file `path`, read under the reader policy (a regular file of at
/// most app::kMaxBoardFileBytes, opened without blocking; io::UsageError
/// "<file>: <problem>" otherwise) and parsed, its state path checked as
/// mrd-firmware checks it (app::BoardConfigError naming file, line and field).
inline app::BoardConfig load_board_file(const std::string& path) {
  return app::parse_board_config(io::read_regular_file(path, app::kMaxBoardFileBytes), io::file_label(path),
                                 posix::non_regular_problem);
}

/// The board file's settings when one is given (no --board: `path` empty),
/// else the defaults; throws as load_board_file().
inline app::BoardConfig board_or_defaults(const std::string& path) {
  if (path.empty()) {
    app::BoardConfig b;
    b.name = "defaults";
    b.can_interface = "vcan0";
    return b;
  }
  return load_board_file(path);
}

/// "key=value ..." with every double to 17 significant digits (round-trip).
inline void print_plant_summary(const char* who, const plant::PlantSummary& s) {
  std::printf(
      "%s: summary ticks=%llu duration_s=%.17g peak_base_displacement_m=%.17g peak_damper_force_n=%.17g "
      "peak_superstructure_accel_m_s2=%.17g peak_base_accel_m_s2=%.17g peak_current_a=%.17g "
      "final_participant_ratio=%.17g sq=%.17g peak_isolator_force_n=%.17g peak_story_drift_m=%.17g\n",
      who, static_cast<unsigned long long>(s.ticks), s.duration_s, s.peak_base_displacement_m, s.peak_damper_force_n,
      s.peak_superstructure_accel_m_s2, s.peak_base_accel_m_s2, s.peak_current_a, s.final_participant_ratio, s.sq,
      s.peak_isolator_force_n, s.peak_story_drift_m);
}

}  // namespace mrd::peers
