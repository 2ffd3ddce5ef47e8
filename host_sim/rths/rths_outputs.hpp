#pragma once
/// What `mrd rths` writes into its folder:
///
/// - summary.json: the set-up (rate, compensator, plant, laboratory, record)
///   and the result (status, J1–J9, peak force against the limit);
/// - tracking.csv: time_s, target_m, measured_m, command_m, force_n, then
///   floor_<i>_m and reference_floor_<i>_m for every DOF, at most 1 kHz;
/// - coefficients.csv: time_s and the compensator's coefficients every
///   10 ms (only a compensator that has coefficients);
/// - tracking.png (target and measured displacement, their difference) and
///   floors.png (each floor against the all-numerical reference), drawn by
///   gnuplot when present.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_sim/rths/rths_run.hpp"

namespace mrd::rths {

/// The set-up as the summary records it.
struct RthsDescription {
  std::string building;  ///< its name
  std::string record;    ///< the file
  double record_scale = 0.0;
  bool plant_drawn = false;
  std::uint64_t plant_seed = 0;
};

nlohmann::json rths_summary_json(const RthsSpec& spec, const RthsDescription& d, const RthsResult& r);

/// Writes the files above; returns the plots that could not be drawn, one
/// line each.
std::vector<std::string> write_rths_outputs(const std::filesystem::path& dir, const RthsSpec& spec,
                                            const RthsDescription& d, const RthsResult& r);

}  // namespace mrd::rths
