#include <chrono>
#include <cstdio>
#include <string>

#include "host_sim/cli/command.hpp"
#include "host_sim/cli/damper_option.hpp"
#include "host_sim/cli/fluid_option.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/cli/schedule_world_options.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/schedule/schedule_report.hpp"

namespace mrd::cli {
namespace schedule_command {
namespace {

constexpr CommandHelp kScheduleHelp{
    "schedule", "Preventive mixing over years of service: capacity met by earthquakes under three policies",
    R"(Years of service of the MR damper under three mixing policies, in one simulated world:
idle time settles the fluid (Eq. 5.1-5.5), motion mixes it (Eq. 5.6-5.9, with the onboard
estimator's state model for repeated episodes), earthquakes arrive at random (Poisson) and meet
the fluid as it is. Policies:
  none            never mix
  fixed-interval  a mixing cycle every --interval-days (at least 1 hour; without the option: the
                  longest interval that keeps the capacity at or above --threshold at every
                  moment, found by bisection; 0 is refused, not a search)
  estimator       the firmware's idle-time estimator and mixing scheduler decide, from the
                  measured damper displacement, when to mix (forecast --lead-hours ahead)
Without an actuator (--actuator no) every cycle is a maintenance visit: the fixed policy visits
every interval, the estimator raises a maintenance request --maintenance-days + --lead-hours ahead
and a technician comes --maintenance-days later (and stays away if the request has cleared).
--numeric double|float|fixed picks the numeric build of the estimator and scheduler the
estimator policy runs (double, the reference, by default; float and fixed point are the builds
for a single-precision microcontroller).
Capacity: damper force at its rated current (2.5 A for the thesis damper) and 0.1 m/s with the present
participant ratio over the same
force fully mixed (Eq. 5.10-5.12).
--damper FILE and --fluid FILE put another damper and MR fluid into the world (README "Your damper
and fluid"; defaults dampers/thesis-200kn.toml and fluids/thesis-model-fluid.toml, the same bytes
with or without them): T_max is the fluid's in the damper's cylinder (Eq. 5.4, or the fluid's
measured max_settling_time_s), the participant ratio follows the fluid's Table 5.6 coefficients
(else the damper file's), the capacity is taken at the damper's rated current with its current laws
(Eq. 5.10-5.11 with Eq. 4.4's Bingham form), and the mixing cycle stays within the damper's rated
stroke and velocity.

Fields of DIR/summary.json:
  years, seed, threshold, actuator, earthquakes_per_year, ambient_median_litres_per_day,
  lead_hours, maintenance_days,
  numeric                          the run's inputs
  earthquakes                      number of earthquakes drawn
  max_settling_time_days           T_max, Eq. 5.4, days
  threshold_idle_days              idle time after which a fully mixed fluid is at the threshold, days
  mixing_plan                      the cycle at the threshold: amplitude_m, frequency_hz, cycles,
                                   displaced_volume_l (L), duration_s (s), peak_velocity_m_s (m/s)
  fixed_interval_days, fixed_interval_source ("search" or "option")
  policies[]                       per policy:
    name                           none | fixed-interval | estimator
    mixing_cycles_per_year         mixing cycles completed per year (actuator or technician)
    min_capacity_fraction          worst capacity an earthquake met (null when none occurred)
    min_capacity_fraction_any_time worst capacity at any moment
    mean_capacity_fraction         time average of the daily minimum capacity
    meets_threshold                min_capacity_fraction_any_time >= threshold
    mixing_cycles, aborted_cycles  completed cycles; cycles stopped by an earthquake
    maintenance_requests_per_year  technician visits asked for per year (no actuator)
    earthquakes_met                number of earthquakes
    interval_days                  fixed-interval only
  estimator_meets_threshold        the estimator policy kept the threshold at every moment
  estimator_fewer_cycles_than_fixed  it did so with fewer cycles per year than the fixed interval
Files: DIR/capacity.csv (daily minimum capacity per policy), DIR/earthquakes.csv (capacity each
earthquake met per policy), DIR/capacity.png (capacity over time).)"};

struct ScheduleCliOptions {
  ScheduleWorldOptions world;
  double maintenance_days = 7.0;
  double lead_hours = 2.0;
  std::string numeric = "double";
  std::string damper;
  std::string fluid;
  std::string out_dir;
};

/// A run and the wall-clock time it took.
struct TimedSchedule {
  schedule::ScheduleResult result;
  double seconds = 0.0;
};

TimedSchedule timed_schedule(const schedule::ScheduleOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  TimedSchedule t{schedule::run_schedule(options), 0.0};
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

void print_summary(const TimedSchedule& t) {
  const schedule::ScheduleResult& r = t.result;
  std::printf("mrd schedule: %.4g years, %zu earthquakes (%.3g per year), threshold %.3g, actuator %s, numeric %s\n",
              r.options.world.years, r.world.quake_times_s.size(), r.options.world.earthquakes_per_year,
              r.options.threshold, r.options.actuator ? "yes" : "no", schedule::numeric_build_name(r.options.numeric));
  std::printf("  a fully mixed fluid reaches the threshold after %.2f days idle (T_max %.1f days)\n",
              r.threshold_idle_s / 86400.0, r.max_settling_time_s / 86400.0);
  std::printf("  mixing cycle: +-%.1f mm at %.3g Hz, %u cycle(s), %.2f L, %.1f s\n", r.plan.amplitude_m * 1e3,
              r.plan.frequency_hz, r.plan.cycles, r.plan.volume_m3 * 1e3, r.plan.duration_s);
  std::printf("  fixed interval %.2f days (%s)\n\n", r.search.interval_s / 86400.0,
              r.interval_from_option ? "--interval-days" : "longest that keeps the threshold");
  std::printf("  %-15s %12s %14s %14s %12s %10s\n", "policy", "cycles/year", "min at quake", "min any time",
              "mean", "aborted");
  for (const auto& p : r.policies) {
    std::printf("  %-15s %12.2f %14.4f %14.4f %12.4f %10u\n", p.name.c_str(), p.mixing_cycles_per_year,
                p.min_capacity_at_quakes, p.min_capacity_any_time, p.mean_capacity, p.aborted_cycles);
  }
  std::printf("\n  (%.2f s of computing)\n", t.seconds);
}

/// The run the options ask for; throws io::UsageError for a bad option
/// (schedule::run_schedule checks the threshold, interval and horizons).
schedule::ScheduleOptions schedule_options(const ScheduleCliOptions& o) {
  schedule::ScheduleOptions so = schedule_world_options(o.world);
  require_finite_at_least("--maintenance-days", o.maintenance_days, 0.0);
  require_finite_at_least("--lead-hours", o.lead_hours, 0.0);
  require_choice("--numeric", o.numeric, {"double", "float", "fixed"});
  so.maintenance_days = o.maintenance_days;
  so.lead_hours = o.lead_hours;
  so.numeric = schedule::parse_numeric_build(o.numeric);
  const DamperAndFluid d = load_damper_and_fluid("schedule", o.damper, o.fluid);
  so.damper = d.params;
  so.settling = d.settling;
  return so;
}

void add_options(CLI::App& app, ScheduleCliOptions& o) {
  app.add_option("--years", o.world.years, "Simulated service life, years (> 0, <= 1000)")->capture_default_str();
  app.add_option("--threshold", o.world.threshold, "Capacity fraction to keep, > 0 and <= 0.99")->capture_default_str();
  app.add_option("--interval-days", o.world.interval_days,
                  "Fixed policy's interval, days, at least 1 hour (0.0417); leave it out for the longest that "
                  "keeps the threshold");
  add_seed_option(app, o.world.seed, "Seed of the random world (earthquakes, ambient motion)");
  app.add_option("--earthquakes-per-year", o.world.earthquakes_per_year, "Mean earthquake rate (Poisson), 1/year")
      ->capture_default_str();
  app.add_option("--actuator", o.world.actuator, "Mixing actuator fitted: yes | no")->capture_default_str();
  app.add_option("--ambient-litres-per-day", o.world.ambient_litres_per_day,
                  "Median displaced volume of ambient motion credited per day, L (log-normal, sigma 1)")
      ->capture_default_str();
  app.add_option("--maintenance-days", o.maintenance_days, "Maintenance request to visit, days (no actuator)")
      ->capture_default_str();
  app.add_option("--lead-hours", o.lead_hours, "Scheduler's forecast horizon with an actuator, h")
      ->capture_default_str();
  app.add_option("--numeric", o.numeric,
                  "Numeric build of the estimator and scheduler: double | float | fixed")
      ->capture_default_str();
  add_damper_option(app, o.damper);
  add_fluid_option(app, o.fluid);
  add_out_option(app, o.out_dir, "Folder for summary.json, capacity.csv, earthquakes.csv, capacity.png");
}

void execute(const ScheduleCliOptions& o) {
  const schedule::ScheduleOptions so = schedule_options(o);
  compute_print_write(
      "schedule", o.out_dir, [&] { return timed_schedule(so); }, print_summary,
      [](const std::filesystem::path& dir, const TimedSchedule& t) {
        return schedule::write_schedule_outputs(dir, t.result);
      });
}

}  // namespace
}  // namespace schedule_command

Command add_schedule_command(CLI::App& parent) {
  using namespace schedule_command;
  return make_command(parent, kScheduleHelp, add_options, execute);
}

}  // namespace mrd::cli
