#pragma once
/// Outputs of `mrd calibrate`: damper.toml, summary.json, report.md and the
/// measured and calibrated force–velocity loops of every record.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "host_sim/discrepancy/calibrate.hpp"
#include "host_sim/discrepancy/measured_data.hpp"

namespace mrd::discrepancy {

/// Records not used in the fit, judged with each law's calibrated baseline:
/// the check records (which choose the extras and the form) or the test
/// records (which nothing in the calibration sees).
struct HeldOut {
  std::vector<std::string> sources;
  std::vector<std::vector<double>> gaps;  ///< [law index of CalibrationResult::fits][record]
};

/// The chosen form fitted to each record alone (record_floor_gaps): the
/// fitted, check and test records' floors, in their order; all empty when
/// not asked for.
struct RecordFloors {
  std::vector<double> measured, check, test;
  [[nodiscard]] bool empty() const noexcept { return measured.empty() && check.empty() && test.empty(); }
};

/// Floors of the chosen form of `r` on the fitted, check and test records.
[[nodiscard]] RecordFloors record_floors(const CalibrationResult& r, std::span<const MeasuredData> records,
                                         std::span<const MeasuredData> check, std::span<const MeasuredData> test,
                                         const CalibrateOptions& options);

/// Gaps of every fitted law on `records`.
[[nodiscard]] HeldOut held_out_gaps(const CalibrationResult& r, std::span<const MeasuredData> records,
                                    const CalibrateOptions& options);

/// Every form's parameters (value, sigma, fitted, at_bound), rss, n_eff,
/// BIC, per-record gaps, the gaps on the check records (`held_out`) and on
/// the test records (`test`: records no choice saw, with the chosen form's
/// RMS gap over them), the choice and why, the notes, the chosen form's
/// floors when computed (`floors`: null when not), and the plausibility
/// warnings about the records (`warnings`, plausibility.hpp).
[[nodiscard]] nlohmann::json calibration_json(const CalibrationResult& r, const HeldOut& held_out,
                                              const HeldOut& test = {}, const RecordFloors& floors = {},
                                              const std::vector<std::string>& warnings = {});

/// Writes damper.toml, summary.json, report.md and (with `plots`) one
/// loops_<n>.png per record into `dir` (which must exist). Returns the
/// reasons of plots that could not be drawn.
std::vector<std::string> write_calibration_outputs(const std::filesystem::path& dir,
                                                   std::span<const MeasuredData> records, const CalibrationResult& r,
                                                   const HeldOut& held_out, const CalibrateOptions& options,
                                                   bool plots = true, const HeldOut& test = {},
                                                   const RecordFloors& floors = {},
                                                   const std::vector<std::string>& warnings = {});

}  // namespace mrd::discrepancy
