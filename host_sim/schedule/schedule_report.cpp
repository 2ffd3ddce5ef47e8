#include "host_sim/schedule/schedule_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "mrd/units.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/report/plot.hpp"
#include "host_sim/report/summary_json.hpp"
#include "host_sim/report/time_series.hpp"

namespace mrd::schedule {
namespace {

void check(bool ok, const std::string& message) {
  if (!ok) throw io::UsageError(message);
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json policy_json(const PolicyResult& p, double threshold) {
  nlohmann::json j{
      {"name", p.name},
      {"mixing_cycles_per_year", p.mixing_cycles_per_year},
      {"min_capacity_fraction", number_or_null(p.min_capacity_at_quakes)},
      {"min_capacity_fraction_any_time", p.min_capacity_any_time},
      {"mean_capacity_fraction", p.mean_capacity},
      {"meets_threshold", p.min_capacity_any_time >= threshold},
      {"mixing_cycles", p.mixing_cycles},
      {"aborted_cycles", p.aborted_cycles},
      {"maintenance_requests_per_year", p.maintenance_requests_per_year},
      {"earthquakes_met", p.quake_capacity.size()},
  };
  if (p.spec.kind == PolicyKind::kFixedInterval) j["interval_days"] = p.spec.interval_s / units::kSecondsPerDay;
  return j;
}

}  // namespace

void check_interval_days(const std::optional<double>& interval_days) {
  if (!interval_days || (std::isfinite(*interval_days) && *interval_days >= kMinIntervalDays)) return;
  throw io::UsageError("--interval-days: expected a number of days >= 0.0417 (1 hour), got " +
                       io::format_number("%g", *interval_days) +
                       " (leave the option out to search the longest interval that keeps the threshold)");
}

ScheduleResult run_schedule(const ScheduleOptions& o) {
  // Above 0.99 the threshold is reached within hours of a full mixing and
  // the fixed interval falls below the search's resolution of an hour.
  check(std::isfinite(o.threshold) && o.threshold > 0.0 && o.threshold <= 0.99,
        "--threshold: expected a capacity fraction > 0 and <= 0.99");
  check_interval_days(o.interval_days);
  check(std::isfinite(o.maintenance_days) && o.maintenance_days >= 0.0 && o.maintenance_days <= 365.0,
        "--maintenance-days: expected 0 to 365 days");
  check(std::isfinite(o.lead_hours) && o.lead_hours >= 0.0 && o.lead_hours <= 24.0 * 365.0,
        "--lead-hours: expected 0 to 8766 hours");

  ScheduleResult r;
  r.options = o;
  r.world = make_world(o.world);
  ServiceConfig& c = r.config;
  c.numeric = o.numeric;
  c.scheduler.capacity_threshold = o.threshold;
  c.scheduler.actuator_fitted = o.actuator;
  c.scheduler.lead_time_s = o.lead_hours * 3600.0;
  c.maintenance_response_s = o.maintenance_days * units::kSecondsPerDay;
  c.estimator.model.settling = o.settling;
  c.estimator.model.pr = o.damper.pr;
  c.estimator.model.bingham = o.damper.bingham;
  c.estimator.model.nominal_current_a = o.damper.rating.current_a;
  c.scheduler.flow_area_m2 = o.damper.pr.flow_area_m2;
  c.scheduler.max_amplitude_m = std::min(c.scheduler.max_amplitude_m, o.damper.rating.stroke_m);
  c.scheduler.max_velocity_m_s = std::min(c.scheduler.max_velocity_m_s, o.damper.rating.velocity_m_s);
  // A request must come early enough for the visit, plus the same lead as
  // with an actuator (event grid and start of the cycle).
  c.scheduler.maintenance_lead_time_s = c.maintenance_response_s + c.scheduler.lead_time_s;

  fw::SettlingModel m;
  m.init(c.estimator.model);
  r.max_settling_time_s = m.max_settling_time_s();
  r.threshold_idle_s = m.idle_of_pr(m.pr_of_capacity(o.threshold));
  r.plan = plan_at_threshold(c);

  if (o.interval_days) {
    r.interval_from_option = true;
    r.search.interval_s = *o.interval_days * units::kSecondsPerDay;
  } else {
    r.search = longest_fixed_interval(r.world, c);
  }
  r.policies.push_back(simulate_policy(r.world, c, {PolicyKind::kNone, 0.0}));
  r.policies.push_back(simulate_policy(r.world, c, {PolicyKind::kFixedInterval, r.search.interval_s}));
  r.policies.push_back(simulate_policy(r.world, c, {PolicyKind::kEstimator, 0.0}));
  r.search.meets_threshold = r.policies[1].min_capacity_any_time >= o.threshold;
  return r;
}

nlohmann::json summary_json(const ScheduleResult& r) {
  const auto& o = r.options;
  nlohmann::json policies = nlohmann::json::array();
  for (const auto& p : r.policies) policies.push_back(policy_json(p, o.threshold));
  const PolicyResult& fixed = r.policies.at(1);
  const PolicyResult& est = r.policies.at(2);
  return nlohmann::json{
      {"years", o.world.years},
      {"seed", o.world.seed},
      {"threshold", o.threshold},
      {"actuator", o.actuator ? "yes" : "no"},
      {"earthquakes_per_year", o.world.earthquakes_per_year},
      {"earthquakes", r.world.quake_times_s.size()},
      {"ambient_median_litres_per_day", o.world.ambient_median_m3_per_day * 1e3},
      {"max_settling_time_days", r.max_settling_time_s / units::kSecondsPerDay},
      {"threshold_idle_days", r.threshold_idle_s / units::kSecondsPerDay},
      {"lead_hours", o.lead_hours},
      {"maintenance_days", o.maintenance_days},
      {"numeric", numeric_build_name(o.numeric)},
      {"mixing_plan",
       {{"amplitude_m", r.plan.amplitude_m},
        {"frequency_hz", r.plan.frequency_hz},
        {"cycles", r.plan.cycles},
        {"displaced_volume_l", r.plan.volume_m3 * 1e3},
        {"duration_s", r.plan.duration_s},
        {"peak_velocity_m_s", r.plan.peak_velocity_m_s}}},
      {"fixed_interval_days", r.search.interval_s / units::kSecondsPerDay},
      {"fixed_interval_source", r.interval_from_option ? "option" : "search"},
      {"policies", policies},
      {"estimator_meets_threshold", est.min_capacity_any_time >= o.threshold},
      {"estimator_fewer_cycles_than_fixed", est.mixing_cycles_per_year < fixed.mixing_cycles_per_year},
  };
}

std::vector<std::string> write_schedule_outputs(const std::filesystem::path& dir, const ScheduleResult& r) {
  std::vector<std::string> names;
  for (const auto& p : r.policies) names.push_back(p.name);

  // Daily minimum capacity of each policy.
  std::vector<std::string> cols{"time_years"};
  for (const auto& n : names) cols.push_back(n + "_capacity_fraction");
  report::TimeSeries daily(cols);
  const std::size_t days = r.policies.front().daily_min_capacity.size();
  daily.reserve(days);
  std::vector<double> row(cols.size());
  for (std::size_t d = 0; d < days; ++d) {
    row[0] = units::s_to_years(static_cast<double>(d) * units::kSecondsPerDay);
    for (std::size_t k = 0; k < r.policies.size(); ++k) row[k + 1] = r.policies[k].daily_min_capacity[d];
    daily.add_row(row);
  }
  report::write_csv(daily, dir / "capacity.csv", 6);

  // The capacity each earthquake met under each policy.
  report::TimeSeries quakes(cols);
  for (std::size_t q = 0; q < r.world.quake_times_s.size(); ++q) {
    row[0] = units::s_to_years(r.world.quake_times_s[q]);
    for (std::size_t k = 0; k < r.policies.size(); ++k) {
      const auto& qc = r.policies[k].quake_capacity;
      row[k + 1] = q < qc.size() ? qc[q] : std::nan("");
    }
    quakes.add_row(row);
  }
  report::write_csv(quakes, dir / "earthquakes.csv", 6);

  std::vector<std::string> problems;
  report::MultiPlot mp;
  char title[160];
  std::snprintf(title, sizeof title, "Force capacity under three mixing policies, threshold %.3g", r.options.threshold);
  mp.title = title;
  const auto& t = daily.column("time_years");
  const auto threshold_line = [&](double x0, double x1) {
    return report::Series{"threshold", {x0, x1}, {r.options.threshold, r.options.threshold}, "lines"};
  };

  report::PlotSpec life;
  life.x_label = "time [years]";
  life.y_label = "daily minimum capacity [-]";
  for (std::size_t k = 0; k < r.policies.size(); ++k) {
    life.series.push_back(report::column_series(daily, "time_years", cols[k + 1], names[k]));
  }
  life.series.push_back(threshold_line(t.front(), t.back()));
  if (quakes.rows() > 0) {
    life.series.push_back(report::column_series(quakes, "time_years", "estimator_capacity_fraction",
                                                "earthquake met (estimator)"));
    life.series.back().style = "points";
  }
  mp.panels.push_back(life);

  report::PlotSpec detail;
  detail.x_label = "time [days]";
  detail.y_label = "capacity, first year [-]";
  double t_end_days = 0.0;
  for (const auto& p : r.policies) {
    std::vector<double> days_x(p.detail_time_s.size());
    for (std::size_t i = 0; i < days_x.size(); ++i) days_x[i] = p.detail_time_s[i] / units::kSecondsPerDay;
    if (!days_x.empty()) t_end_days = std::max(t_end_days, days_x.back());
    detail.series.push_back(report::Series{p.name, std::move(days_x), p.detail_capacity, "lines"});
  }
  detail.series.push_back(threshold_line(0.0, t_end_days));
  mp.panels.push_back(detail);
  mp.width_px = 1200;
  mp.height_px = 1000;

  const auto png = dir / "capacity.png";
  const report::PlotResult pr = report::plot_png(mp, png);
  if (!pr.ok) problems.push_back(png.filename().string() + ": " + pr.reason);

  report::write_summary_json(dir, summary_json(r));
  return problems;
}

}  // namespace mrd::schedule
