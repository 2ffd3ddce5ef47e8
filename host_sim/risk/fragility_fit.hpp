#pragma once
/// Fragility curves of a study: for each control mode, idle time and limit
/// state, the lognormal P(LS | PGA) fitted by maximum likelihood to the runs
/// at every PGA level (lognormal_fit.hpp), with bootstrap bands over records.

#include <string>
#include <vector>

#include "host_sim/risk/fragility_plan.hpp"
#include "host_sim/risk/lognormal_fit.hpp"

namespace mrd::risk {

/// The quantity a limit state watches.
enum class Metric { kBaseDisplacement, kFloorAccel, kStoryDrift };

/// A limit state: exceeded when the run's metric reaches the threshold.
struct LimitState {
  std::string name;
  Metric metric = Metric::kBaseDisplacement;
  double threshold = 0.0;  ///< in the metric's SI unit (m, m/s²)
  std::string description;
};

/// The damper's stroke, ±0.2921 m (thesis §3.1, the Lord 200 kN damper).
inline constexpr double kDamperStroke_m = 0.2921;
/// Isolation gap (moat clearance) assumed by default, m: no figure in the thesis.
inline constexpr double kDefaultIsolationGap_m = 0.20;
/// Floor acceleration threshold assumed by default, g (acceleration-sensitive contents).
inline constexpr double kDefaultFloorAccel_g = 0.3;
/// Story drift threshold assumed by default, m: an absolute drift, since a
/// building file gives no story heights (0.02 m is 0.5 % of a 4 m story).
inline constexpr double kDefaultStoryDrift_m = 0.02;

/// stroke, isolation_gap, floor_accel and story_drift with the given gap (m),
/// floor acceleration (g) and story drift (m).
std::vector<LimitState> default_limit_states(double isolation_gap_m, double floor_accel_g,
                                             double story_drift_m = kDefaultStoryDrift_m);

double metric_value(const RunMetrics& m, Metric metric) noexcept;

struct FragilityCurve {
  std::size_t mode = 0, idle = 0, limit_state = 0;  ///< indices into the plan and the limit states
  std::vector<LevelCounts> levels;
  LognormalFit fit;
  FragilityBand band;
};

/// Bootstrap settings.
struct BootstrapOptions {
  unsigned resamples = 200;
  std::uint64_t seed = 1;
  int eval_points =
      41;  ///< band and curve evaluated at log-spaced PGAs from half the lowest level to twice the highest
};

/// Every curve, ordered mode-major, then idle time, then limit state.
std::vector<FragilityCurve> fit_fragilities(const FragilityPlan& plan, const std::vector<RunMetrics>& runs,
                                            const std::vector<LimitState>& limit_states,
                                            const BootstrapOptions& bootstrap);

}  // namespace mrd::risk
