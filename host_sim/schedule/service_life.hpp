#pragma once
/// Service-life simulation of preventive mixing (`mrd schedule`): years of
/// idle time, ambient motion, mixing cycles and earthquakes, under several
/// mixing policies, recording the force capacity each earthquake meets.
///
/// The world (make_world), drawn once per seed and shared by all policies:
///  - ambient motion (wind, traffic): a displaced volume per day, log-normal
///    with a given median and log-standard deviation, spread evenly over the
///    day. It is the volume the estimator credits, i.e. what is left after
///    its dead band; the simulator feeds it to the estimator without one.
///  - earthquakes: a Poisson process (exponential gaps); each shakes for
///    quake_duration_s, displaces quake_volume_m3 evenly and has a ground
///    acceleration well above the seismic trigger.
///
/// The fluid ("truth") follows the state model of fw::SettlingModel with the
/// exact volumes; it starts fully mixed (commissioning). Time advances from
/// event to event: a grid of step_s (1 h), earthquakes, fixed-interval
/// mixing, maintenance visits. Idle periods are analytic (τ grows linearly),
/// so a step costs the same however long it is. Capacity is sampled after
/// every event; since the model's capacity only falls between motions and
/// only rises during them, the minimum over these samples is the minimum
/// over time.
///
/// Policies:
///  - none: no mixing.
///  - fixed-interval: a mixing cycle every interval, planned like the
///    scheduler's (fw::plan_mixing for the volume that brings PR within the
///    ceiling gap). Without an actuator the cycle is a maintenance visit.
///  - estimator: the firmware's app::MixingTask (fw::IdleEstimator and
///    fw::MixingScheduler composed as the board runtime composes them),
///    fed the damper displacement and ground acceleration as the board would
///    feed them (sampled at the event grid; 20 samples a period while a
///    mixing cycle runs; 4 a second during an earthquake). A request starts
///    the simulated actuator after actuator_start_delay_s; an earthquake
///    during a cycle stops it at once (the scheduler aborts). Without an
///    actuator, a maintenance request brings a technician after
///    maintenance_response_s, who runs the planned cycle unless the request
///    has cleared by then (motion mixed the fluid meanwhile).
/// The estimator policy runs the mixing task in the numeric build
/// ServiceConfig::numeric (double by default; float and fixed point are the
/// builds for a single-precision microcontroller): the float and fixed
/// builds take the stroke and accelerations as float and the wall clock in
/// milliseconds, as a board would give them.
/// The fixed interval, unless given, is the longest one whose capacity never
/// falls below the threshold over the whole simulated life (bisection to
/// search_resolution_s): judged at every moment, not only at the sampled
/// earthquakes, so that it is not tuned to the luck of one draw.

#include <cstdint>
#include <string>
#include <vector>

#include "firmware/core/idle_estimator.hpp"
#include "firmware/core/mixing_scheduler.hpp"

namespace mrd::schedule {

struct WorldConfig {
  double years = 50.0;
  std::uint64_t seed = 1;
  double earthquakes_per_year = 0.5;
  double quake_duration_s = 40.0;
  double quake_volume_m3 = 0.05;              ///< 50 L: ≈ 40 s at 0.12 m/s mean |v| through 0.01062 m²
  double quake_accel_m_s2 = 1.0;              ///< ground acceleration during shaking (> trigger)
  /// Median credited ambient volume, m³ a day: 0.005 L is 0.47 mm of stroke
  /// counted beyond the dead band a day. The thesis has no data on ambient
  /// motion; this is an assumption to vary (0 is the worst case).
  double ambient_median_m3_per_day = 0.005e-3;
  double ambient_sigma_ln = 1.0;              ///< log-standard deviation of the daily volume
};

struct World {
  double duration_s = 0.0;
  std::vector<double> ambient_m3_per_day;  ///< one entry per (started) day
  std::vector<double> quake_times_s;       ///< sorted
  double quake_duration_s = 40.0;
  double quake_volume_m3 = 0.05;
  double quake_accel_m_s2 = 1.0;
};

/// Draws the world. Deterministic for a seed on any platform (own
/// exponential and log-normal draws from std::mt19937_64, not the
/// library-defined std distributions). Throws io::UsageError for
/// non-finite or negative inputs, years ≤ 0 or above 1000.
World make_world(const WorldConfig& config);

enum class PolicyKind { kNone, kFixedInterval, kEstimator };

struct PolicySpec {
  PolicyKind kind = PolicyKind::kNone;
  double interval_s = 0.0;  ///< fixed-interval only
};

const char* policy_name(PolicyKind kind) noexcept;

/// The numeric build of the firmware's mixing task (estimator policy).
enum class NumericBuild { kDouble, kFloat, kFixed };

const char* numeric_build_name(NumericBuild b) noexcept;
/// "double" | "float" | "fixed"; throws io::UsageError naming --numeric otherwise.
NumericBuild parse_numeric_build(const std::string& name);

struct ServiceConfig {
  NumericBuild numeric = NumericBuild::kDouble;  ///< build of the estimator policy's mixing task
  fw::IdleEstimatorConfig estimator{};  ///< its dead band is ignored (see above)
  fw::MixingSchedulerConfig scheduler{};
  double step_s = 3600.0;                       ///< event grid, s
  double actuator_start_delay_s = 5.0;          ///< request to first stroke, s
  double maintenance_response_s = 7.0 * 86400.0;  ///< maintenance request to visit, s
  double quake_sample_s = 0.25;                 ///< sample spacing during an earthquake, s
  double search_resolution_s = 3600.0;          ///< resolution of the fixed-interval search, s
  double detail_s = 365.25 * 86400.0;           ///< keep every sample up to this time (plots), s
};

struct PolicyResult {
  std::string name;
  PolicySpec spec{};
  std::uint32_t mixing_cycles = 0;        ///< cycles run to the end (actuator or technician)
  std::uint32_t aborted_cycles = 0;       ///< cycles stopped by an earthquake
  std::uint32_t maintenance_requests = 0;
  double mixing_cycles_per_year = 0.0;
  double maintenance_requests_per_year = 0.0;
  /// Worst capacity an earthquake met (NaN when no earthquake occurred).
  double min_capacity_at_quakes = 0.0;
  double min_capacity_any_time = 1.0;     ///< worst capacity at any moment
  double mean_capacity = 1.0;             ///< time average of the daily minimum
  std::vector<double> quake_capacity;     ///< capacity met by each earthquake
  std::vector<double> daily_min_capacity; ///< lowest capacity of each day
  std::vector<double> detail_time_s;      ///< every sample up to ServiceConfig::detail_s
  std::vector<double> detail_capacity;
};

/// One policy over the world.
PolicyResult simulate_policy(const World& world, const ServiceConfig& config, const PolicySpec& policy);

struct IntervalSearch {
  double interval_s = 0.0;
  bool meets_threshold = false;  ///< false: even the shortest interval tried fails
  int simulations = 0;
};

/// Longest fixed interval in [search_resolution_s, 2·T_max] whose
/// min_capacity_any_time stays at or above the threshold, by bisection.
IntervalSearch longest_fixed_interval(const World& world, const ServiceConfig& config);

/// The cycle the policies run for a fluid at the threshold (for reports).
fw::MixingPlan plan_at_threshold(const ServiceConfig& config);

}  // namespace mrd::schedule
