#pragma once
/// `mrd schedule` as a library call: runs the three policies over one world
/// and writes summary.json, capacity.csv, earthquakes.csv and capacity.png.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "host_sim/schedule/service_life.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::schedule {

struct ScheduleOptions {
  WorldConfig world{};
  double threshold = 0.8;             ///< capacity fraction to keep
  std::optional<double> interval_days; ///< fixed policy, days; none: search the longest that keeps the threshold
  bool actuator = true;
  double maintenance_days = 7.0;      ///< request to visit without an actuator, days
  double lead_hours = 2.0;            ///< forecast horizon with an actuator, h
  NumericBuild numeric = NumericBuild::kDouble;  ///< build of the estimator policy's mixing task
  /// The damper (a damper file's; the thesis's by default): its current laws
  /// and rated current define the capacity, its participant ratio the
  /// fluid's recovery, its flow area the mixing volume, and its rated stroke
  /// and velocity cap the mixing actuator's (§6.6's ±76.2 mm, 0.1 m/s).
  physics::MrDamperParams damper{};
  /// The fluid in the damper's cylinder (Eq. 5.1–5.4, or a measured T_max).
  physics::SettlingParams settling{};
};

struct ScheduleResult {
  ScheduleOptions options{};
  World world{};
  ServiceConfig config{};
  IntervalSearch search{};            ///< the fixed interval used (searched or given)
  bool interval_from_option = false;
  fw::MixingPlan plan{};              ///< the cycle at the threshold
  double threshold_idle_s = 0.0;      ///< idle time that takes a fully mixed fluid to the threshold
  double max_settling_time_s = 0.0;   ///< Eq. 5.4
  std::vector<PolicyResult> policies; ///< none, fixed-interval, estimator
};

/// Shortest fixed interval, days: the search's resolution of an hour.
inline constexpr double kMinIntervalDays = 1.0 / 24.0;

/// Checks a given fixed interval: finite and at least kMinIntervalDays (0
/// and negative values included: the search is asked for by giving no
/// interval). Throws io::UsageError naming --interval-days otherwise.
void check_interval_days(const std::optional<double>& interval_days);

/// Checks the options (io::UsageError naming the option) and runs.
ScheduleResult run_schedule(const ScheduleOptions& options);

nlohmann::json summary_json(const ScheduleResult& r);

/// Writes capacity.csv, earthquakes.csv, capacity.png and summary.json
/// (last) into `dir`, each atomically. Returns the reasons plots were not
/// drawn (empty when all were).
std::vector<std::string> write_schedule_outputs(const std::filesystem::path& dir, const ScheduleResult& r);

}  // namespace mrd::schedule
