#include "host_sim/cli/schedule_world_options.hpp"

#include "host_sim/cli/options.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::cli {

schedule::ScheduleOptions schedule_world_options(const ScheduleWorldOptions& o) {
  require_finite_at_least("--years", o.years, 0.0);
  if (!(o.years > 0.0) || o.years > 1000.0) throw io::UsageError("--years: expected a number of years > 0 and <= 1000");
  require_finite_at_least("--threshold", o.threshold, 0.0);
  schedule::check_interval_days(o.interval_days);
  require_finite_at_least("--earthquakes-per-year", o.earthquakes_per_year, 0.0);
  require_finite_at_least("--ambient-litres-per-day", o.ambient_litres_per_day, 0.0);
  require_choice("--actuator", o.actuator, {"yes", "no"});
  schedule::ScheduleOptions so;
  so.world.years = o.years;
  so.world.seed = o.seed;
  so.world.earthquakes_per_year = o.earthquakes_per_year;
  so.world.ambient_median_m3_per_day = o.ambient_litres_per_day * 1e-3;
  so.threshold = o.threshold;
  so.interval_days = o.interval_days;
  so.actuator = o.actuator == "yes";
  return so;
}

}  // namespace mrd::cli
