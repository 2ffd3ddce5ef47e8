#pragma once
/// What `mrd-rths` leaves in its output folder, each file written whole under
/// a temporary name (NAME.tmp) and renamed into place, so a run that ends
/// early or a power cut leaves either the complete file or none:
///
/// - a run that finished: summary.json (status "ok", the set-up, J1–J9, the
///   loop's timing, the compensator's coefficients at the end) and
///   tracking.csv (time, target, measured, command, force at every tick) and
///   coefficients.csv (the compensator's coefficients every 10 ms);
/// - a run the laboratory stopped (or that ended otherwise early): stop.json
///   only (the status, the tick and time of the end, the timing), never a
///   summary.
///
/// prepare_out_dir() removes those files (and their temporaries) from an
/// earlier run first, so no old summary can be taken for this run's.

#include <filesystem>
#include <string>

#include "host_sim/rths_board/board_loop.hpp"
#include "host_sim/rths_board/damper_loop.hpp"

namespace mrd::rths_board {

/// The run's set-up as the files name it.
struct RunDescription {
  std::string board;
  std::string record;
  std::string structure;     ///< "benchmark case N"
  std::string compensator;
  double record_scale = 0.4;
  double rate_hz = 1000.0;
};

/// The thesis set-up's run as the files name it.
struct DamperRunDescription {
  std::string board;
  std::string record;
  double pga_g = 0.1127;
  std::string building;      ///< its name (the thesis building's or the file's)
  std::string control;       ///< passive-off | passive-on | semi-active
  std::string compensation;  ///< model | none
  double delay_s = 0.015, lag_s = 0.002, rate_hz = 1000.0;
};

/// Creates `dir` when missing and removes this program's files of an earlier
/// run. Throws std::runtime_error naming the folder when it cannot.
void prepare_out_dir(const std::filesystem::path& dir);

/// Writes `text` to `dir/name` through `dir/name.tmp` and a rename. Throws
/// std::runtime_error naming the file.
void write_atomically(const std::filesystem::path& dir, const std::string& name, const std::string& text);

/// The files of a finished run (status "ok").
void write_finished_run(const std::filesystem::path& dir, const RunDescription& d, const BoardLoop& loop,
                        const rths::Criteria& criteria);

/// stop.json of a run that ended early.
void write_stopped_run(const std::filesystem::path& dir, const RunDescription& d, const BoardLoop& loop);

/// The thesis set-up's files: tracking.csv (time, target, measured stroke,
/// command, force, coil current command stage, base displacement) and
/// summary.json (status "ok", the set-up, the peak base displacement, the
/// peak force, the tracking error, the timing); stop.json for a run that
/// ended early.
void write_finished_damper_run(const std::filesystem::path& dir, const DamperRunDescription& d, const DamperLoop& loop);
void write_stopped_damper_run(const std::filesystem::path& dir, const DamperRunDescription& d, const DamperLoop& loop);

/// "ticks=… overruns=… worst_late_us=… worst_tick_us=… stale_ticks=… rejected=… tx_errors=…"
std::string timing_fields(const BoardLoop& loop);
std::string timing_fields(const DamperLoop& loop);

}  // namespace mrd::rths_board
