#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "host_sim/cli/command.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/cli/schedule_world_options.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/risk/hazard_curve.hpp"
#include "host_sim/risk/lifetime_risk.hpp"

namespace mrd::cli {
namespace risk_command {
namespace {

constexpr CommandHelp kRiskHelp{
    "risk", "Lifetime seismic risk per mixing policy: fragility x hazard x capacity history",
    R"(Combines the fragility curves of `mrd fragility` (--fragility DIR/fragility.csv) with a hazard
curve and the capacity history `mrd schedule` simulates for each mixing policy (the same world and
options), into the mean annual frequency of exceeding each limit state:
  tau(c)          equivalent idle time of the day's lowest capacity fraction c (Eq. 5.5-5.6, 5.10-5.12)
  lambda_LS(tau_k) = integral of P(LS | PGA, tau_k) |d lambda(PGA)|   at the study's idle times
  lambda_LS(policy) = mean over the days of the service life of lambda_LS(tau(c_day)),
                      lambda_LS(tau) interpolated linearly between the tau_k (held beyond them)
against an always-fully-mixed damper (tau = 0).
Hazard (--hazard FILE): CSV with the header pga_g,annual_frequency, then one row per point (PGA in g
increasing, annual frequency of exceedance decreasing, both > 0); '#' lines and blank lines are
skipped. Default: an illustrative site, lambda(PGA) = k0 PGA^-2.5 with 0.3 g at 10 % in 50 years
(k0 = 1.039e-4 g^2.5 per year), 0.01 to 5 g; not a real site.
Extrapolation: a fragility curve is fitted over the study's PGA levels (fragility.csv's pga_g_min,
pga_g_max); where the hazard curve reaches beyond them, lambda_LS uses the curves extrapolated.
A warning (stderr, summary.json warnings, report.md) names each limit state whose annual exceedance
at an idle time takes more than 10 % from PGAs outside the fitted levels, and each limit state whose
ratios to always-fully-mixed rest mainly (more than 50 % of the policy's or the reference's annual
exceedance) on them; a fragility.csv without those columns is named too.
Fields of DIR/summary.json: control, hazard, limit_states, idle_years, annual_exceedance_at_idle
(limit state -> lambda_LS at each idle time), days_beyond_study_fraction, fitted_pga_g (min, max;
null when not known), extrapolated_fraction_at_idle (limit state -> part of lambda_LS from outside
the fitted levels at each idle time), warnings[], reference, schedule (the world's options),
policies[] (none, fixed-interval, estimator, always-fully-mixed): name, cycles_per_year (null for
the reference), annual_exceedance (limit state -> 1/year), relative_to_fully_mixed,
extrapolated_fraction (limit state -> part from outside the fitted levels),
mean_equivalent_idle_years, idle_time_fraction[] (from_years, to_years, fraction of the days).
Files: DIR/risk.csv, DIR/report.md (the table), DIR/risk.png.)"};

struct RiskOptions {
  std::string fragility;
  std::string hazard;
  std::string control;
  ScheduleWorldOptions world;
  std::string out_dir;
};

void print_summary(const risk::RiskResult& r) {
  std::printf("mrd risk: control %s, %.4g years of service (schedule seed %llu)\n  hazard: %s\n\n", r.control.c_str(),
              r.schedule.options.world.years, static_cast<unsigned long long>(r.schedule.options.world.seed),
              r.hazard_source.c_str());
  std::printf("  %-19s %12s %10s", "policy", "cycles/year", "mean idle");
  for (const auto& n : r.limit_states) std::printf(" %16s", (n + " /year").c_str());
  std::printf("\n");
  for (const auto& p : r.policies) {
    std::printf("  %-19s %12s %9.4gy", p.name.c_str(),
                std::isfinite(p.cycles_per_year) ? std::to_string(p.cycles_per_year).substr(0, 8).c_str() : "-",
                p.mean_equivalent_idle_years);
    for (const auto& n : r.limit_states) std::printf(" %16.4e", p.annual_exceedance.at(n));
    std::printf("\n");
  }
  print_warnings("risk", r.warnings);
}

void add_options(CLI::App& app, RiskOptions& o) {
  app.add_option("--fragility", o.fragility, "fragility.csv of mrd fragility, or its folder")->required();
  app.add_option("--hazard", o.hazard, "Hazard curve CSV (default: the illustrative site)");
  app.add_option("--control", o.control, "Control mode of the curves (default: the first in the file)");
  app.add_option("--years", o.world.years, "Service life, years (> 0, <= 1000)")->capture_default_str();
  add_seed_option(app, o.world.seed, "Seed of mrd schedule's world");
  app.add_option("--threshold", o.world.threshold, "Capacity fraction the policies keep")->capture_default_str();
  app.add_option("--interval-days", o.world.interval_days, "Fixed policy's interval, days (default: searched)");
  app.add_option("--earthquakes-per-year", o.world.earthquakes_per_year, "Earthquakes that mix the fluid, 1/year")
      ->capture_default_str();
  app.add_option("--actuator", o.world.actuator, "Mixing actuator fitted: yes | no")->capture_default_str();
  app.add_option("--ambient-litres-per-day", o.world.ambient_litres_per_day, "Median ambient volume credited a day, L")
      ->capture_default_str();
  add_out_option(app, o.out_dir, "Folder for summary.json, risk.csv, report.md, risk.png");
}

void execute(const RiskOptions& o) {
  const schedule::ScheduleOptions so = schedule_world_options(o.world);
  std::filesystem::path fragility_path = o.fragility;
  std::error_code ec;
  if (std::filesystem::is_directory(fragility_path, ec)) fragility_path /= "fragility.csv";
  const auto rows = risk::read_fragility_csv(fragility_path);
  const risk::HazardCurve hazard = o.hazard.empty() ? risk::default_hazard_curve() : risk::read_hazard_csv(o.hazard);
  compute_print_write(
      "risk", o.out_dir, [&] { return risk::compute_risk(rows, o.control, hazard, schedule::run_schedule(so)); },
      print_summary,
      [](const std::filesystem::path& dir, const risk::RiskResult& r) { return risk::write_risk_outputs(dir, r); });
}

}  // namespace
}  // namespace risk_command

Command add_risk_command(CLI::App& parent) {
  using namespace risk_command;
  return make_command(parent, kRiskHelp, add_options, execute);
}

}  // namespace mrd::cli
