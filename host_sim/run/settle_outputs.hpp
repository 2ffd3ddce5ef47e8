#pragma once
/// Outputs of `mrd settle`: the settling state as summary.json.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "host_sim/run/settle_study.hpp"

namespace mrd::run {

/// The fields documented in `mrd settle --help`; `idle_years` is the idle
/// time as the user gave it (quoted, not converted back from seconds).
[[nodiscard]] nlohmann::json settle_summary_json(double idle_years, const SettleSummary& s);

/// Writes `dir/summary.json` (the folder must exist).
void write_settle_outputs(const std::filesystem::path& dir, double idle_years, const SettleSummary& s);

}  // namespace mrd::run
