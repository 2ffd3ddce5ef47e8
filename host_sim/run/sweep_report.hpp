#pragma once
/// Files of an idle-time sweep: one CSV and the plots of Fig. 6.12–6.20, and
/// the summary.json of `mrd sweep`.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host_sim/run/sweep.hpp"

namespace mrd::run {

/// Writes `dir/sweep.csv` and, per control mode, three PNGs (peak base
/// displacement, peak damper force, peak superstructure acceleration against
/// idle time, one curve per motion). Returns the plot problems (empty when
/// every plot was drawn) and the names of the PNGs written in `pngs`.
std::vector<std::string> write_sweep_outputs(const std::filesystem::path& dir, const SweepSpec& spec,
                                             const std::vector<SweepRow>& rows, std::vector<std::string>* pngs);

/// Where runs of the sweep leave the model's validity (validity_warnings with
/// the damper's rating) or pass the bearings' displacement capacity
/// (bearing_capacity_warnings with the building), as sentences.
std::vector<std::string> sweep_warnings(const std::vector<SweepRow>& rows, const plant::PlantSpec& base);

/// The sweep as CSV text (header + one row per run): the thesis's ten
/// columns and, for another building than the thesis's (is_thesis_building),
/// peak_isolator_force_kn and peak_story_drift_m after them.
std::string sweep_csv(const SweepSpec& spec, const std::vector<SweepRow>& rows);

/// Simulated time summed over the runs, s.
[[nodiscard]] double simulated_seconds(const std::vector<SweepRow>& rows);

/// The fields documented in `mrd sweep --help`: runs, wall time,
/// simulated seconds and their ratio, motions, controls, idle times, files,
/// the building's name and DOFs.
[[nodiscard]] nlohmann::json sweep_summary_json(const SweepSpec& spec, const std::vector<SweepRow>& rows,
                                                double wall_s, const std::vector<std::string>& pngs);

/// What `mrd sweep` writes: write_sweep_outputs, then summary.json. Returns
/// the plot problems and the names of the PNGs written in `pngs`.
std::vector<std::string> write_sweep_report(const std::filesystem::path& dir, const SweepSpec& spec,
                                            const std::vector<SweepRow>& rows, double wall_s,
                                            std::vector<std::string>* pngs);

}  // namespace mrd::run
