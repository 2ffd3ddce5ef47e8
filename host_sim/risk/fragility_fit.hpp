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
  /// Fitted only when asked for (story_drift, `mrd fragility --drift-m`): its
  /// curves take bootstrap seeds after every other curve's (fit_fragilities),
  /// so asking for it moves no other curve's band.
  bool opt_in = false;
};

/// The damper's stroke, ±0.2921 m (thesis §3.1, the Lord 200 kN damper).
inline constexpr double kDamperStroke_m = 0.2921;
/// Isolation gap (moat clearance) assumed by default, m: no figure in the thesis.
inline constexpr double kDefaultIsolationGap_m = 0.20;
/// Floor acceleration threshold assumed by default, g (acceleration-sensitive contents).
inline constexpr double kDefaultFloorAccel_g = 0.3;

/// The thesis's limit states: stroke, isolation_gap and floor_accel with the
/// given gap (m) and floor acceleration (g).
std::vector<LimitState> default_limit_states(double isolation_gap_m, double floor_accel_g);

/// The opt-in story_drift limit state: peak story drift (any story) reaches
/// `story_drift_m`, m. An absolute drift with no default: a drift limit
/// depends on the story heights, which a building file does not hold.
LimitState story_drift_limit_state(double story_drift_m);

/// The bearing_capacity limit state: peak isolator displacement (the base's,
/// DOF 0 against the ground) reaches the bearings' displacement capacity,
/// `capacity_m` (the smallest a building file's bearings state). Added for
/// a building whose bearings state one, as an opt-in state ahead of
/// story_drift, so that neither moves the thesis's curves' bands nor
/// --drift-m this one's.
LimitState bearing_capacity_limit_state(double capacity_m);

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
///
/// Bootstrap seeds: curve i's resamples are seeded by
/// record_seed(seed ^ "boot", i) with a seed index i that does not depend on
/// which opt-in limit states are present. With M modes, K idle times and C
/// limit states that are not opt-in, the curve (mode m, idle k, c-th such
/// state) takes (m K + k) C + c: the thesis's three states number their curves
/// in (mode, idle, state) order, as when they were the only ones. The o-th
/// opt-in state (o = 0, 1, ... in the order given) takes the next block of M K
/// indices after all of those, M K C + o M K + (m K + k). Adding story_drift
/// therefore leaves every other curve's band as it was.
std::vector<FragilityCurve> fit_fragilities(const FragilityPlan& plan, const std::vector<RunMetrics>& runs,
                                            const std::vector<LimitState>& limit_states,
                                            const BootstrapOptions& bootstrap);

}  // namespace mrd::risk
