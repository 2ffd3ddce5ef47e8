#pragma once
/// Outputs of `mrd discrepancy` and `mrd synth`: summary.json, the fit as
/// CSV, plots and a Markdown report.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host_sim/discrepancy/synth.hpp"
#include "host_sim/discrepancy/workflow.hpp"

namespace mrd::discrepancy {

/// Parameters of `e` as a JSON object {name_with_unit: value}, plus derived
/// quantities where they help (idle_settling: a_PR, b_PR, c_PR and the idle
/// time that gives the fitted SQ by Eq. 5.5).
[[nodiscard]] nlohmann::json params_json(Effect e, std::span<const double> params);

/// The fields documented in `mrd discrepancy --help`.
[[nodiscard]] nlohmann::json summary_json(const MeasuredData& data, const DiscrepancyResult& r,
                                          const DiscrepancyOptions& options);

/// Writes summary.json, fit.csv, force_time.png, residual.png, loops.png and
/// report.md into `dir` (which must exist). Returns the reasons of plots that
/// could not be drawn (gnuplot missing); files are written atomically.
std::vector<std::string> write_discrepancy_outputs(const std::filesystem::path& dir, const MeasuredData& data,
                                                   const DiscrepancyResult& r, const DiscrepancyOptions& options,
                                                   bool plots = true);

/// The truth of a generated record: effects, parameters, input and noise.
[[nodiscard]] nlohmann::json synth_json(const SynthCase& c, const SynthSpec& spec);

/// File format of a generated record.
enum class RecordFormat { csv, mat };

/// Writes the record as `dir/measured.csv` or `dir/measured.mat`, then the
/// truth as `dir/summary.json`. Returns the record's path.
std::filesystem::path write_synth_outputs(const std::filesystem::path& dir, const SynthCase& c, const SynthSpec& spec,
                                          RecordFormat format);

}  // namespace mrd::discrepancy
