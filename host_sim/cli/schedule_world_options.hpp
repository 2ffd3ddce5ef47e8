#pragma once
/// The options `mrd schedule` and `mrd risk` share: the simulated world
/// (service life, seed, earthquake rate, ambient motion) and the policies'
/// threshold, fixed interval and actuator.

#include <cstdint>
#include <optional>
#include <string>

#include "host_sim/schedule/schedule_report.hpp"

namespace mrd::cli {

struct ScheduleWorldOptions {
  double years = 50.0;
  std::uint64_t seed = 1;
  double threshold = 0.8;
  /// Fixed policy's interval, days; none given: the longest interval that
  /// keeps the threshold (searched).
  std::optional<double> interval_days;
  double earthquakes_per_year = 0.5;
  std::string actuator = "yes";
  double ambient_litres_per_day = 0.005;
};

/// Checks the options (io::UsageError naming the option: a number that is not
/// finite or is negative, years outside (0, 1000], a given interval below 1
/// hour (0 included: the search is the option's absence), an actuator other
/// than yes or no) and maps them onto schedule::ScheduleOptions; the other
/// fields keep their defaults. schedule::run_schedule checks the threshold.
[[nodiscard]] schedule::ScheduleOptions schedule_world_options(const ScheduleWorldOptions& o);

}  // namespace mrd::cli
