// Service-life simulation of preventive mixing: the world's draws, the
// fixed interval and the estimator-driven policy against periods derived
// by hand from Eq. 5.4–5.9 and Table 4.1, earthquakes meeting the fluid as
// it is, aborts, maintenance, and the requirement that the estimator keeps
// the threshold with fewer cycles than the fixed interval that does.
#include "host_sim/schedule/service_life.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "mrd/physics/settling.hpp"
#include "mrd/units.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/schedule/schedule_report.hpp"

namespace mrd::schedule {
namespace {

constexpr double kDay = 86400.0;
constexpr double kHour = 3600.0;
// One thesis cycle (±76.2 mm) through the calibrated area 0.01062 m²:
// 4·0.0762·0.01062 m³ = 3.2370 L.
constexpr double kCycleLitres = 4.0 * 0.0762 * 0.01062 * 1e3;

/// The thesis model written out independently of the code under test.
struct Hand {
  double t_max = physics::max_settling_time_s(physics::SettlingParams{});  // Eq. 5.4
  double sq(double tau) const { return std::min(tau / t_max, 1.0); }         // Eq. 5.5
  static double a(double s) { return 0.10 + 0.90 * std::exp(-7.0 * s); }     // Eq. 5.6
  static double b(double s) { return 0.605 + 0.395 * std::exp(-4.5 * s); }   // Eq. 5.7
  static double c(double s) { return 5.474 * std::exp(-3.65 * s); }          // Eq. 5.8, 1/L
  double inv_a(double pr) const { return -std::log((pr - 0.1) / 0.9) / 7.0 * t_max; }
  /// Force at 2.5 A and 0.1 m/s, Table 4.1 and Eq. 5.10–5.12 (transition factor 1).
  static double force(double pr) {
    const double e1 = std::exp(-0.7 * 2.5), e2 = std::exp(-1.15 * 2.5);
    return pr * 170e3 * (1 - e1) + 4.1e3 * e1 + 0.1 * (pr * 365e3 * (1 - e2) + 82.5e3 * e2);
  }
  static double cap(double pr) { return force(pr) / force(1.0); }
  static double pr_of_cap(double k) { return (k * force(1.0) - force(0.0)) / (force(1.0) - force(0.0)); }
  double cap_of_idle(double tau) const { return cap(a(sq(tau))); }
  /// τ after one mixing episode of `litres` started at τ (Eq. 5.9, then a_PR⁻¹).
  double after_mixing(double tau, double litres) const {
    const double s = sq(tau);
    return inv_a(b(s) + (a(s) - b(s)) * std::exp(-c(s) * litres));
  }
  /// Idle time at which a fully mixed fluid reaches capacity `k`.
  double idle_at(double k) const { return inv_a(pr_of_cap(k)); }
};

World quiet_world(double days) {
  World w;
  w.duration_s = days * kDay;
  w.ambient_m3_per_day.assign(static_cast<std::size_t>(std::ceil(days)), 0.0);
  return w;
}

// ------------------------------------------------------------ world

TEST(ScheduleWorld, SameSeedSameWorld) {
  WorldConfig c;
  c.years = 20;
  const World a = make_world(c), b = make_world(c);
  EXPECT_EQ(a.quake_times_s, b.quake_times_s);
  EXPECT_EQ(a.ambient_m3_per_day, b.ambient_m3_per_day);
  c.seed = 2;
  EXPECT_NE(make_world(c).ambient_m3_per_day, a.ambient_m3_per_day);
}

// Poisson: over 1000 years at 0.5 a year, N ≈ 500 ± 4·√500 (= ±89); gaps
// have mean 2 years and, being exponential, a standard deviation equal to
// their mean. The daily volume is log-normal: half the days lie below the
// median (±4·√(0.25/n)).
TEST(ScheduleWorld, PoissonEarthquakesAndLogNormalAmbient) {
  WorldConfig c;
  c.years = 1000;
  c.earthquakes_per_year = 0.5;
  c.ambient_median_m3_per_day = 0.01e-3;
  const World w = make_world(c);
  const auto n = static_cast<double>(w.quake_times_s.size());
  EXPECT_NEAR(n, 500.0, 4.0 * std::sqrt(500.0));
  ASSERT_TRUE(std::is_sorted(w.quake_times_s.begin(), w.quake_times_s.end()));
  std::vector<double> gaps;
  double last = 0.0;
  for (double t : w.quake_times_s) gaps.push_back(units::s_to_years(t - last)), last = t;
  double mean = 0.0, var = 0.0;
  for (double g : gaps) mean += g / n;
  for (double g : gaps) var += (g - mean) * (g - mean) / (n - 1);
  EXPECT_NEAR(mean, 2.0, 0.3);
  EXPECT_NEAR(std::sqrt(var) / mean, 1.0, 0.15);

  const auto days = static_cast<double>(w.ambient_m3_per_day.size());
  EXPECT_NEAR(days, 1000 * 365.25, 1.0);
  const auto below = std::count_if(w.ambient_m3_per_day.begin(), w.ambient_m3_per_day.end(),
                                   [](double v) { return v < 0.01e-3; });
  EXPECT_NEAR(static_cast<double>(below) / days, 0.5, 4.0 * std::sqrt(0.25 / days));
}

TEST(ScheduleWorld, BadInputIsAUsageError) {
  WorldConfig c;
  c.years = -1;
  EXPECT_THROW(make_world(c), io::UsageError);
  c = {};
  c.years = std::nan("");
  EXPECT_THROW(make_world(c), io::UsageError);
  c = {};
  c.earthquakes_per_year = -0.1;
  EXPECT_THROW(make_world(c), io::UsageError);
  c = {};
  c.ambient_median_m3_per_day = -1;
  EXPECT_THROW(make_world(c), io::UsageError);
  EXPECT_THROW(simulate_policy(quiet_world(10), {}, {PolicyKind::kFixedInterval, 0.0}), io::UsageError);
}

// ------------------------------------------------------------ policies, by hand

// With neither ambient motion nor earthquakes the only motion is mixing.
// One cycle at τ (3.237 L, started 5 s after the scheduled time; the episode
// closes 60 s after the 5-s stroke and counts those 65 s as idle time)
// leaves g(τ) = a_PR⁻¹(PR after the cycle); the next cycle starts P later at
// τ = g(τ) + P. From τ = 0 this climbs to the fixed point τ* = g(τ*) + P,
// and the capacity is lowest just before a cycle. So P keeps the threshold
// iff P ≤ P* = τ_th − g(τ_th). The search, by bisection to 1 h, must land
// within an hour below P*.
TEST(SchedulePolicies, FixedIntervalSearchFindsTheAnalyticPeriod) {
  const Hand h;
  const ServiceConfig cfg;
  const double tau_th = h.idle_at(0.8);
  EXPECT_NEAR(tau_th / kDay, 11.27, 0.01);  // by hand: SQ = 0.03617 of T_max = 311.7 days
  const double p_star = tau_th - h.after_mixing(tau_th, kCycleLitres);
  const World w = quiet_world(2 * 365.25);
  const IntervalSearch s = longest_fixed_interval(w, cfg);
  ASSERT_TRUE(s.meets_threshold);
  EXPECT_LE(s.interval_s, p_star + 60.0);
  EXPECT_GE(s.interval_s, p_star - kHour - 60.0);

  // At P the capacity before each cycle approaches cap(a(τ*)); two years are
  // enough for the fixed point (g has slope ≈ 0.3).
  const PolicyResult r = simulate_policy(w, cfg, {PolicyKind::kFixedInterval, s.interval_s});
  double tau = 0.0;
  for (int k = 0; k < 200; ++k) tau = h.after_mixing(tau, kCycleLitres) + s.interval_s;
  EXPECT_NEAR(r.min_capacity_any_time, h.cap_of_idle(tau), 1e-6);
  EXPECT_NEAR(r.mixing_cycles, std::floor(w.duration_s / s.interval_s), 1.0);
}

// The estimator-driven policy in the same world mixes at the first hourly
// evaluation at which the forecast 2 h ahead falls below the threshold, i.e.
// the first whole hour with τ > τ_l = τ_th − 2 h: τ_m ∈ (τ_l, τ_l + 1 h], and
// the stroke starts 5 s later. The period τ_{k+1} − g(τ_k) then lies in
// (τ_l − g(τ_l + 1 h), τ_l + 1 h − g(τ_l)]. It keeps the threshold, and with
// no variability to exploit it cannot mix less often than the best fixed
// interval P* = τ_th − g(τ_th): its period is shorter by about
// 1 h − 2 h·g′ ≈ 0.4 h at most.
TEST(SchedulePolicies, WithoutVariabilityTheEstimatorMatchesTheBestFixedInterval) {
  const Hand h;
  ServiceConfig cfg;
  const World w = quiet_world(2 * 365.25);
  const PolicyResult est = simulate_policy(w, cfg, {PolicyKind::kEstimator, 0.0});
  const double tau_th = h.idle_at(0.8);
  const double tau_l = tau_th - cfg.scheduler.lead_time_s;
  EXPECT_GE(est.min_capacity_any_time, 0.8);
  EXPECT_GE(est.min_capacity_any_time, h.cap_of_idle(tau_l + kHour + 60.0));
  EXPECT_LE(est.min_capacity_any_time, h.cap_of_idle(tau_l));
  const double p_hi = tau_l + kHour - h.after_mixing(tau_l, kCycleLitres);
  const double p_lo = tau_l - h.after_mixing(tau_l + kHour, kCycleLitres);
  const double years = units::s_to_years(w.duration_s);
  EXPECT_GE(est.mixing_cycles_per_year, units::kSecondsPerYear / p_hi - 1.0 / years);
  EXPECT_LE(est.mixing_cycles_per_year, units::kSecondsPerYear / p_lo + 1.0 / years);
  const double p_star = tau_th - h.after_mixing(tau_th, kCycleLitres);
  EXPECT_GE(est.mixing_cycles_per_year, units::kSecondsPerYear / p_star - 1.0 / years);
}

// Two seasons a year: half a year of wind crediting 0.1 L a day, half a year
// of calm. The wind alone holds the fluid above the threshold: near τ_th a
// litre moves SQ back by (b − a)·c/|da/dSQ| = 0.142·4.80/4.89 = 0.139, and a
// day of idling adds 1/311.7 = 0.0032, so 0.023 L a day breaks even; 0.1 L
// is four times that. In the calm half-year cycles are needed every P*. The
// fixed interval must be short enough for the calm season all year round
// (≥ 365.25/P* cycles a year); the estimator mixes only when calm, about
// half as often.
TEST(SchedulePolicies, SeasonalWindLetsTheEstimatorSkipHalfTheCycles) {
  const Hand h;
  const ServiceConfig cfg;
  World w = quiet_world(4 * 365.25);
  for (std::size_t d = 0; d < w.ambient_m3_per_day.size(); ++d) {
    const bool windy = std::fmod(static_cast<double>(d), 365.25) < 182.6;
    w.ambient_m3_per_day[d] = windy ? 0.1e-3 : 0.0;
  }
  const IntervalSearch s = longest_fixed_interval(w, cfg);
  ASSERT_TRUE(s.meets_threshold);
  const PolicyResult fixed = simulate_policy(w, cfg, {PolicyKind::kFixedInterval, s.interval_s});
  const PolicyResult est = simulate_policy(w, cfg, {PolicyKind::kEstimator, 0.0});
  const PolicyResult none = simulate_policy(w, cfg, {PolicyKind::kNone, 0.0});

  const double tau_th = h.idle_at(0.8);
  const double p_star = tau_th - h.after_mixing(tau_th, kCycleLitres);
  EXPECT_GE(fixed.mixing_cycles_per_year, units::kSecondsPerYear / p_star - 0.5);
  EXPECT_GE(fixed.min_capacity_any_time, 0.8);
  EXPECT_GE(est.min_capacity_any_time, 0.8);
  EXPECT_LT(est.mixing_cycles_per_year, 0.6 * fixed.mixing_cycles_per_year);
  // Without mixing the calm seasons take the fluid far below the threshold.
  EXPECT_LT(none.min_capacity_any_time, 0.5);
}

// Earthquakes meet the fluid as it is. Without ambient motion or mixing:
// the first, at 20 days, meets cap(a_PR(SQ(20 d))); its 50 L take PR to
// b_PR(SQ(20 d)) (c_PR·50 L ≈ 216); the second, 80 days later, meets
// cap(a_PR(SQ(a_PR⁻¹(b_PR) + 80 d))) (the quake's 100 s of motion and quiet
// count as idle time, as in the estimator's model).
TEST(SchedulePolicies, EarthquakesMeetTheCapacityOfTheMoment) {
  const Hand h;
  World w = quiet_world(200);
  w.quake_times_s = {20 * kDay, 100 * kDay};
  const PolicyResult none = simulate_policy(w, {}, {PolicyKind::kNone, 0.0});
  ASSERT_EQ(none.quake_capacity.size(), 2u);
  EXPECT_NEAR(none.quake_capacity[0], h.cap_of_idle(20 * kDay), 1e-9);
  const double tau2 = h.inv_a(Hand::b(h.sq(20 * kDay))) + 80 * kDay;
  EXPECT_NEAR(none.quake_capacity[1], h.cap_of_idle(tau2), 1e-9);
  EXPECT_DOUBLE_EQ(none.min_capacity_at_quakes, none.quake_capacity[1]);
  EXPECT_EQ(none.mixing_cycles, 0u);
}

TEST(SchedulePolicies, NoEarthquakeMeansNoQuakeMinimum) {
  const PolicyResult none = simulate_policy(quiet_world(30), {}, {PolicyKind::kNone, 0.0});
  EXPECT_TRUE(std::isnan(none.min_capacity_at_quakes));
  EXPECT_TRUE(none.quake_capacity.empty());
}

// A fixed cycle at P strokes during [P + 5 s, P + 10 s]; an earthquake at
// P + 7 s stops it. For the estimator the first request comes at the first
// whole hour t with t + 2 h > τ_th (forecast below 0.8); an earthquake 7 s
// into its stroke (start + 5 s delay + 2 s) aborts it, and no retry follows
// because the earthquake mixed the fluid (and the next cycle would come
// only about P* ≈ 8 days after it, past the end of this 15-day world).
TEST(SchedulePolicies, EarthquakeDuringACycleAbortsIt) {
  const Hand h;
  const ServiceConfig cfg;
  const double p = 5 * kDay;
  World w = quiet_world(14);
  w.quake_times_s = {p + 7.0};
  const PolicyResult fixed = simulate_policy(w, cfg, {PolicyKind::kFixedInterval, p});
  EXPECT_EQ(fixed.aborted_cycles, 1u);
  EXPECT_EQ(fixed.mixing_cycles, 1u);  // the one at 10 days

  const double tau_th = h.idle_at(0.8);
  const double t_request = (std::floor((tau_th - cfg.scheduler.lead_time_s) / kHour) + 1.0) * kHour;
  w = quiet_world(15);
  w.quake_times_s = {t_request + cfg.actuator_start_delay_s + 2.0};
  const PolicyResult est = simulate_policy(w, cfg, {PolicyKind::kEstimator, 0.0});
  EXPECT_EQ(est.aborted_cycles, 1u);
  EXPECT_EQ(est.mixing_cycles, 0u);
  ASSERT_EQ(est.quake_capacity.size(), 1u);
  EXPECT_GE(est.quake_capacity[0], 0.8);
}

// Without an actuator the estimator raises a maintenance request when the
// forecast maintenance_response + 1 day ahead falls below the threshold; the
// technician comes maintenance_response later, a day before the threshold.
TEST(SchedulePolicies, NoActuatorMeansMaintenanceVisitsThatKeepTheThreshold) {
  ServiceConfig cfg;
  cfg.scheduler.actuator_fitted = false;
  cfg.maintenance_response_s = 3 * kDay;
  cfg.scheduler.maintenance_lead_time_s = 4 * kDay;
  const World w = quiet_world(365.25);
  const PolicyResult est = simulate_policy(w, cfg, {PolicyKind::kEstimator, 0.0});
  EXPECT_GT(est.maintenance_requests, 0u);
  // Every request brings a visit, except perhaps one raised in the last days.
  EXPECT_GE(est.maintenance_requests, est.mixing_cycles);
  EXPECT_LE(est.maintenance_requests, est.mixing_cycles + 1);
  EXPECT_GE(est.min_capacity_any_time, 0.8);
  const PolicyResult fixed = simulate_policy(w, cfg, {PolicyKind::kFixedInterval, 7 * kDay});
  EXPECT_EQ(fixed.maintenance_requests, fixed.mixing_cycles);
  EXPECT_EQ(fixed.mixing_cycles, 52u);  // 365.25 days / 7, the last one on day 364
}

// ------------------------------------------------------------ the requirement

// On the command's default world (log-normal ambient motion, Poisson
// earthquakes) the estimator keeps the threshold at every moment with fewer
// cycles a year than the longest fixed interval that does: the fixed
// interval has to be short enough for the calmest stretch of days, the
// estimator mixes later whenever wind or an earthquake has mixed the fluid.
TEST(ScheduleRequirement, EstimatorKeepsTheThresholdWithFewerCycles) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    ScheduleOptions o;
    o.world.years = 10;
    o.world.seed = seed;
    const ScheduleResult r = run_schedule(o);
    ASSERT_EQ(r.policies.size(), 3u);
    const PolicyResult& fixed = r.policies[1];
    const PolicyResult& est = r.policies[2];
    EXPECT_TRUE(r.search.meets_threshold) << seed;
    EXPECT_GE(fixed.min_capacity_any_time, o.threshold) << seed;
    EXPECT_GE(est.min_capacity_any_time, o.threshold) << seed;
    if (!est.quake_capacity.empty()) {
      EXPECT_GE(est.min_capacity_at_quakes, o.threshold) << seed;
    }
    EXPECT_LT(est.mixing_cycles_per_year, fixed.mixing_cycles_per_year) << seed;
    const auto j = summary_json(r);
    EXPECT_TRUE(j["estimator_meets_threshold"].get<bool>());
    EXPECT_TRUE(j["estimator_fewer_cycles_than_fixed"].get<bool>());
  }
}

TEST(ScheduleRequirement, PlanAtThresholdIsOneThesisCycle) {
  const fw::MixingPlan p = plan_at_threshold({});
  EXPECT_DOUBLE_EQ(p.amplitude_m, 0.0762);
  EXPECT_DOUBLE_EQ(p.frequency_hz, 0.2);
  EXPECT_EQ(p.cycles, 1u);
}

}  // namespace
}  // namespace mrd::schedule
