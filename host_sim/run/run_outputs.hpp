#pragma once
/// Files written for one closed-loop run: the time series (CSV) and plots in
/// the style of thesis Fig. 6.9–6.11, and the outputs of `mrd sim`.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/sim_run.hpp"

namespace mrd::run {

/// One column of a run's time series: its name in the CSV header (units in
/// the name) and its values, one per step, owned by the record.
struct ClosedLoopColumn {
  std::string name;
  const std::vector<double>* values;
};

/// The columns of `rec` in the order `<stem>.csv` writes them: the eleven
/// fixed ones, isolator_force_n with isolators, then story_<element>_drift_m.
[[nodiscard]] std::vector<ClosedLoopColumn> closed_loop_columns(const ClosedLoopRecord& rec);

/// Writes `dir/<stem>.csv` (every step) and `dir/<stem>_response.png` (base
/// displacement, damper force and peak floor acceleration over time) and
/// `dir/<stem>_loop.png` (damper force against stroke). Returns the reasons
/// for plots that could not be drawn (empty when all were).
std::vector<std::string> write_closed_loop_outputs(const std::filesystem::path& dir, const std::string& stem,
                                                   const std::string& title, const ClosedLoopRecord& rec);

/// Response time histories of two runs on one figure (e.g. fully mixed
/// against 2.5 years idle, as Fig. 6.9–6.11 compare them).
std::vector<std::string> write_comparison_plot(const std::filesystem::path& png, const std::string& title,
                                               const std::string& label_a, const ClosedLoopRecord& a,
                                               const std::string& label_b, const ClosedLoopRecord& b);

/// The peaks of a run, SQ, final participant ratio and duration, in the
/// units their names say (force in kN).
[[nodiscard]] nlohmann::json closed_loop_summary_json(const plant::PlantSummary& s);

/// The fields documented in `mrd sim --help`: closed_loop_summary_json, the
/// run's inputs, the plant and the coil figures (plant::CoilFigures).
[[nodiscard]] nlohmann::json sim_summary_json(const SimRun& run);

/// Writes the outputs of `mrd sim` into `dir` (which must exist):
/// timeseries.csv and its plots (write_closed_loop_outputs, from
/// run.record), then summary.json. Returns the reasons for plots that could
/// not be drawn.
/// Where the run leaves the model's validity (validity_warnings), as sentences.
std::vector<std::string> sim_warnings(const SimRun& run);

std::vector<std::string> write_sim_outputs(const std::filesystem::path& dir, const SimRun& run);

}  // namespace mrd::run
