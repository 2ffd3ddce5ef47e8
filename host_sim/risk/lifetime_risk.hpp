#pragma once
/// Lifetime risk per mixing policy (`mrd risk`): the fragility curves of
/// `mrd fragility`, a hazard curve and the capacity history `mrd schedule`
/// simulates for each policy, combined into the mean annual frequency of
/// exceeding each limit state:
/// <pre>
///   τ(c)      = a_PR⁻¹(PR(c))                equivalent idle time of capacity fraction c (Eq. 5.5–5.6, 5.10–5.12)
///   λ_LS(τ_k) = ∫ P(LS | IM, τ_k) |dλ(IM)|   at each idle time τ_k of the fragility study
///   λ_LS(τ)   = linear interpolation in τ between the τ_k (the end values outside them)
///   λ_LS(policy) = (1/D) Σ_d λ_LS(τ(c_d))    over the D days of the service life,
///                                            c_d = the day's lowest capacity under the policy
/// </pre>
/// Interpolating λ_LS(τ) linearly is the same as interpolating the fragility
/// curves P(LS | IM, τ) linearly in τ (the integral is linear in P), i.e.
/// mixing the curves of the neighbouring idle times in proportion. The
/// reference, always fully mixed, is λ_LS(0).

#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "host_sim/risk/hazard_curve.hpp"
#include "host_sim/risk/lognormal_fit.hpp"
#include "host_sim/schedule/schedule_report.hpp"

namespace mrd::risk {

/// One row of fragility.csv.
struct FragilityRow {
  std::string control, limit_state;
  double threshold = 0.0, idle_years = 0.0;
  LognormalFit fit;
  /// The PGA levels the curve was fitted over, g (NaN when the file does not
  /// say: written before the columns pga_g_min, pga_g_max existed).
  double pga_min_g = std::numeric_limits<double>::quiet_NaN();
  double pga_max_g = std::numeric_limits<double>::quiet_NaN();
};

/// Parses fragility.csv as `mrd fragility` writes it (kFragilityCsvHeader,
/// then optionally kFragilityCsvRangeColumns; other columns after them are
/// ignored). Errors: io::UsageError "<file>:<line>: field '<column>': ...".
std::vector<FragilityRow> parse_fragility_csv(std::string_view text, const std::string& file);
std::vector<FragilityRow> read_fragility_csv(const std::filesystem::path& path);

struct IdleBin {
  double from_years = 0.0, to_years = 0.0;  ///< [from, to) of equivalent idle time
  double fraction = 0.0;                    ///< of the days
};

struct PolicyRisk {
  std::string name;
  double cycles_per_year = 0.0;  ///< NaN for the always-fully-mixed reference
  double mean_equivalent_idle_years = 0.0;
  std::map<std::string, double> annual_exceedance;  ///< limit state → 1/year
  /// limit state → the part of annual_exceedance from PGAs outside the fitted
  /// levels (empty when they are not known).
  std::map<std::string, double> extrapolated_fraction;
  std::vector<IdleBin> idle_fraction;
};

struct RiskResult {
  std::string control;
  std::string hazard_source;
  std::vector<std::string> limit_states;                         ///< in fragility.csv order
  std::vector<double> idle_years;                                ///< τ_k of the fragility study
  std::map<std::string, std::vector<double>> frequency_at_idle;  ///< λ_LS(τ_k), limit state → per τ_k
  double days_beyond_study_fraction = 0.0;  ///< days whose τ exceeds the last τ_k (λ held there)
  std::vector<PolicyRisk> policies;         ///< the schedule's policies, then always-fully-mixed
  schedule::ScheduleResult schedule;
  /// The PGA levels the control's curves were fitted over, g (NaN: not known).
  double fitted_pga_min_g = std::numeric_limits<double>::quiet_NaN();
  double fitted_pga_max_g = std::numeric_limits<double>::quiet_NaN();
  /// limit state → per τ_k, the part of λ_LS(τ_k) that Eq. (1) of
  /// hazard_curve.hpp takes at PGAs outside the fitted levels, where the
  /// curve is extrapolated (empty when the levels are not known).
  std::map<std::string, std::vector<double>> extrapolated_fraction_at_idle;
  std::vector<std::string> warnings;  ///< risk_warnings
};

/// Part of a result resting on extrapolated fragility curves above which the
/// hazard curve is said to reach materially beyond the fitted PGA levels.
inline constexpr double kMaterialExtrapolation = 0.10;
/// Part above which a ratio to the fully mixed reference is said to rest
/// mainly on extrapolation.
inline constexpr double kMainlyExtrapolation = 0.5;

/// What the result cannot vouch for, one sentence each: days idler than the
/// study's longest idle time; a fragility.csv that does not give its PGA
/// levels; for each limit state whose annual exceedance at some idle time
/// takes more than kMaterialExtrapolation from PGAs outside the fitted levels,
/// the hazard's range, the levels and the worst part; for each limit state
/// whose ratios to the reference rest mainly (more than kMainlyExtrapolation
/// of the reference's or a policy's annual exceedance) on extrapolation, the
/// ratios and the parts.
std::vector<std::string> risk_warnings(const RiskResult& r, const HazardCurve& hazard);

/// Equivalent idle time of a capacity fraction under the schedule's settling
/// model, s, within [0, T_max].
double equivalent_idle_s(const fw::SettlingModel& model, double capacity_fraction);

/// λ_LS(τ) from the tabulated λ_LS(τ_k).
double frequency_at(const std::vector<double>& idle_years, const std::vector<double>& frequency, double tau_years);

/// Combines: `control` picks the rows (empty: the first control in the file).
/// Throws io::UsageError for a control not in the rows or a limit state whose
/// idle times differ from the others'.
RiskResult compute_risk(const std::vector<FragilityRow>& rows, const std::string& control, const HazardCurve& hazard,
                        schedule::ScheduleResult schedule);

nlohmann::json risk_summary(const RiskResult& r);

/// risk.csv, risk.png, report.md, summary.json (last), each atomically;
/// returns the reasons plots were not drawn.
std::vector<std::string> write_risk_outputs(const std::filesystem::path& dir, const RiskResult& r);

}  // namespace mrd::risk
