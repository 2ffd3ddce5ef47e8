#pragma once
/// Outputs of `mrd sine`: one test as CSV, plots and summary.json; the
/// thesis cases as a Markdown table and summary.json.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host_sim/run/sine_cases.hpp"
#include "host_sim/run/sine_rig.hpp"

namespace mrd::run {

/// One sine test as run: the amplitude and idle time as the user gave them
/// (outputs quote them as given), the test, its metrics and its time series.
struct SineRun {
  double amplitude_mm = 0.0;
  double idle_years = 0.0;
  SineRigSpec spec;
  SineMetrics metrics;
  SineRecord record;
  physics::DamperRating rating{};  ///< the damper's (its validity limits)
};

/// Where the test leaves the model's validity (validity_warnings): stroke the
/// amplitude, velocity 2πf times it, the coil current and the largest force.
[[nodiscard]] std::vector<std::string> sine_warnings(const SineRun& run);

/// The fields documented in `mrd sine --help`.
[[nodiscard]] nlohmann::json sine_summary_json(const SineRun& run);

/// Writes sine.csv, force_time.png, force_displacement.png and summary.json
/// (last) into `dir` (which must exist). Returns the reasons for plots that
/// could not be drawn.
std::vector<std::string> write_sine_outputs(const std::filesystem::path& dir, const SineRun& run);

/// Model against measured for every case: a Markdown table with the errors
/// in %, one row per metric of Table 5.2.
[[nodiscard]] std::string thesis_cases_markdown(const std::vector<ThesisSineResult>& results);

/// {"thesis_cases": [{name, model, measured}]}, forces in kN, times in s.
[[nodiscard]] nlohmann::json thesis_cases_json(const std::vector<ThesisSineResult>& results);

/// Writes thesis_cases.md and summary.json into `dir` (which must exist).
void write_thesis_cases_outputs(const std::filesystem::path& dir, const std::vector<ThesisSineResult>& results);

}  // namespace mrd::run
