#include "host_sim/schedule/service_life.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <type_traits>

#include "firmware/app/mixing_task.hpp"
#include "firmware/core/numeric_formats.hpp"
#include "host_sim/excitation/synthetic_motion.hpp"
#include "mrd/units.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::schedule {
namespace {

constexpr double kRtc0_s = 1.7e9;  // wall-clock stamp of commissioning, s (any value works)
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kSamplesPerMixingPeriod = 20;  // hits the stroke's peaks: 4A per period exactly

void require(bool ok, const std::string& what) {
  if (!ok) throw io::UsageError(what);
}

/// Uniform in (0, 1] from the top 53 bits of one draw.
double uniform_open0(std::mt19937_64& g) {
  return (static_cast<double>(g() >> 11) + 1.0) * (1.0 / 9007199254740992.0);
}

void set_rtc(fw::RtcSeconds& in, double rtc_s) { in.rtc_s = rtc_s; }
void set_rtc(fw::RtcMillis& in, double rtc_s) { in.rtc_ms = std::llround(rtc_s * 1e3); }

/// The wall clock in the build's boot argument: s (double) or ms.
template <class Rtc>
Rtc rtc_of(double rtc_s) {
  if constexpr (std::is_same_v<Rtc, double>) {
    return rtc_s;
  } else {
    return std::llround(rtc_s * 1e3);
  }
}

/// A build's plan in double, for the simulated actuator.
template <class Policy>
fw::MixingPlan reference_plan(const fw::BasicMixingPlan<Policy>& p) {
  fw::MixingPlan r;
  r.amplitude_m = static_cast<double>(p.amplitude_m);
  r.frequency_hz = static_cast<double>(p.frequency_hz);
  r.cycles = p.cycles;
  r.volume_m3 = fw::IdleArith<Policy>::vol_to_double(p.volume_m3);
  r.duration_s = static_cast<double>(p.duration_s);
  r.duration_ticks = p.duration_ticks;
  r.peak_velocity_m_s = static_cast<double>(p.peak_velocity_m_s);
  r.peak_accel_m_s2 = static_cast<double>(p.peak_accel_m_s2);
  return r;
}

/// One policy over one world: the event loop described in the header, with
/// the mixing task in the numeric build `Policy`.
template <class Policy>
class Run {
 public:
  Run(const World& w, const ServiceConfig& c, const PolicySpec& p) : w_(w), c_(c), p_(p) {
    fw::IdleModelConfig model = c.estimator.model;
    truth_.init(model);
    truth_.reset(0.0, 0.0);  // commissioned fully mixed
    area_m2_ = model.pr.flow_area_m2;
    fixed_ = p.kind == PolicyKind::kFixedInterval;
    estimator_ = p.kind == PolicyKind::kEstimator;
    if (estimator_) {
      app::MixingTaskConfig mc{c.estimator, c.scheduler};
      mc.estimator.dead_band_m = 0.0;  // the world's ambient volume is already the credited volume
      firmware_.init(mc);
      firmware_.boot_with(0.0, 0, rtc_of<typename app::BasicMixingTask<Policy>::Rtc>(kRtc0_s));
      period_s_ = mc.estimator.period_s;
    }
    next_fixed_s_ = fixed_ ? p.interval_s : kInf;
    const auto days = static_cast<std::size_t>(std::ceil(w.duration_s / units::kSecondsPerDay));
    r_.daily_min_capacity.assign(std::max<std::size_t>(days, 1), kInf);
    r_.name = policy_name(p.kind);
    r_.spec = p;
    r_.min_capacity_any_time = kInf;
  }

  PolicyResult go() {
    sample();
    for (;;) {
      process_due_events();
      if (t_ >= w_.duration_s) break;
      double t1 = (std::floor(t_ / c_.step_s) + 1.0) * c_.step_s;
      if (next_quake_ < w_.quake_times_s.size()) t1 = std::min(t1, w_.quake_times_s[next_quake_]);
      t1 = std::min({t1, next_fixed_s_, next_visit_s_, w_.duration_s});
      advance_to(t1, ambient_m3(t_, t1), x_mix_m_, 0.0, false);
    }
    const double years = units::s_to_years(w_.duration_s);
    r_.mixing_cycles_per_year = r_.mixing_cycles / years;
    if (estimator_) r_.maintenance_requests = firmware_.scheduler().counters().maintenance_raised;
    r_.maintenance_requests_per_year = r_.maintenance_requests / years;
    r_.min_capacity_at_quakes = r_.quake_capacity.empty()
                                    ? std::numeric_limits<double>::quiet_NaN()
                                    : *std::min_element(r_.quake_capacity.begin(), r_.quake_capacity.end());
    double sum = 0.0;
    for (double& d : r_.daily_min_capacity) {
      if (!std::isfinite(d)) d = r_.min_capacity_any_time;  // cannot happen with a grid ≤ 1 day
      sum += d;
    }
    r_.mean_capacity = sum / static_cast<double>(r_.daily_min_capacity.size());
    return std::move(r_);
  }

 private:
  /// Credited ambient volume during [t0, t1], m³.
  double ambient_m3(double t0, double t1) const {
    double v = 0.0;
    while (t0 < t1) {
      const auto day = static_cast<std::size_t>(t0 / units::kSecondsPerDay);
      if (day >= w_.ambient_m3_per_day.size()) break;
      const double end = std::min(t1, (static_cast<double>(day) + 1.0) * units::kSecondsPerDay);
      v += w_.ambient_m3_per_day[day] * (end - t0) / units::kSecondsPerDay;
      t0 = end;
    }
    return v;
  }

  void sample() {
    const double cap = truth_.capacity_fraction(t_);
    r_.min_capacity_any_time = std::min(r_.min_capacity_any_time, cap);
    const auto day = std::min(static_cast<std::size_t>(t_ / units::kSecondsPerDay), r_.daily_min_capacity.size() - 1);
    r_.daily_min_capacity[day] = std::min(r_.daily_min_capacity[day], cap);
    if (t_ <= c_.detail_s) {
      r_.detail_time_s.push_back(t_);
      r_.detail_capacity.push_back(cap);
    }
  }

  /// Moves time to t1. The damper moves by `ambient_m3` (back and forth,
  /// alternating direction) or by the mixing stroke to `x_mix_m` — never
  /// both in one call — and the ground shakes with `accel_m_s2`.
  void advance_to(double t1, double ambient_m3, double x_mix_m, double accel_m_s2, bool mixing) {
    const double stroke_m3 = std::fabs(x_mix_m - x_mix_m_) * area_m2_;
    const double dv_m3 = ambient_m3 + stroke_m3;
    if (dv_m3 > 0.0) truth_.add_motion(t_, t1, dv_m3);
    truth_.advance(t1);
    if (ambient_m3 > 0.0) {
      x_amb_m_ += amb_sign_ * ambient_m3 / area_m2_;
      amb_sign_ = -amb_sign_;
    }
    x_mix_m_ = x_mix_m;
    t_ = t1;
    if (estimator_) step_firmware(accel_m_s2, mixing);
    sample();
  }

  /// The board's mixing task on the sampled stroke and ground acceleration.
  void step_firmware(double accel_m_s2, bool mixing) {
    using Sample = typename fw::IdleArith<Policy>::Sample;
    app::BasicMixingTaskInput<Policy> in;
    in.tick = static_cast<std::uint64_t>(std::llround(t_ / period_s_));
    set_rtc(in, kRtc0_s + t_);
    in.damper_disp_m = static_cast<Sample>(x_amb_m_ + x_mix_m_);
    in.ground_accel_m_s2 = static_cast<Sample>(accel_m_s2);
    in.base_accel_m_s2 = Sample(0);
    in.actuator_ready = c_.scheduler.actuator_fitted;
    in.actuator_busy = mixing;
    const auto& o = firmware_.step(in);
    if (o.state == fw::SchedulerState::kRequested && o.request_active && o.request_id != started_id_) {
      pending_request_ = true;
    }
    // A new maintenance request brings one technician visit.
    const std::uint32_t raised = firmware_.scheduler().counters().maintenance_raised;
    if (raised != maintenance_seen_) {
      maintenance_seen_ = raised;
      if (!std::isfinite(next_visit_s_)) next_visit_s_ = t_ + c_.maintenance_response_s;
    }
  }

  bool quake_due() const {
    return next_quake_ < w_.quake_times_s.size() && w_.quake_times_s[next_quake_] <= t_;
  }

  void process_due_events() {
    for (;;) {
      if (quake_due()) {
        ++next_quake_;
        quake();
      } else if (next_fixed_s_ <= t_) {
        next_fixed_s_ += p_.interval_s;
        if (t_ < w_.duration_s) mix(plan_for_truth());
      } else if (next_visit_s_ <= t_) {
        // The technician checks the maintenance output before starting: if
        // motion since the request (wind, an earthquake) mixed the fluid
        // enough, the visit is called off.
        next_visit_s_ = kInf;
        if (t_ < w_.duration_s && firmware_.output().maintenance_required) {
          const double volume_m3 = firmware_.estimator().volume_to_ceiling_m3(c_.scheduler.ceiling_gap_fraction);
          mix(fw::plan_mixing(firmware_.scheduler().config(), volume_m3));
        }
      } else if (pending_request_) {
        pending_request_ = false;
        started_id_ = firmware_.output().request_id;
        mix(reference_plan(firmware_.output().plan));
      } else {
        break;
      }
    }
  }

  fw::MixingPlan plan_for_truth() const {
    return fw::plan_mixing(c_.scheduler, truth_.volume_to_ceiling_m3(t_, c_.scheduler.ceiling_gap_fraction));
  }

  /// The earthquake meets the fluid as it is now, then shakes it.
  void quake() {
    r_.quake_capacity.push_back(truth_.capacity_fraction(t_));
    const auto n = static_cast<int>(std::ceil(w_.quake_duration_s / c_.quake_sample_s));
    const double dv = w_.quake_volume_m3 / n;
    const double t0 = t_;
    for (int k = 1; k <= n; ++k) advance_to(t0 + k * c_.quake_sample_s, dv, x_mix_m_, w_.quake_accel_m_s2, false);
  }

  /// Runs `plan` on the damper after the actuator's start delay, 20 samples
  /// a period. An earthquake stops it at once: the stroke holds where it is.
  void mix(const fw::MixingPlan& plan) {
    const double t_start = t_ + c_.actuator_start_delay_s;
    const double x0 = x_mix_m_;
    if (quake_before(t_start)) {
      ++r_.aborted_cycles;
      return;
    }
    advance_to(t_start, ambient_m3(t_, t_start), x_mix_m_, 0.0, false);
    const int n = kSamplesPerMixingPeriod * static_cast<int>(plan.cycles);
    const double dt = 1.0 / (kSamplesPerMixingPeriod * plan.frequency_hz);
    for (int k = 1; k <= n; ++k) {
      const double s = t_start + k * dt;
      if (quake_before(s)) {
        ++r_.aborted_cycles;
        return;
      }
      const double x = x0 + plan.amplitude_m * std::sin(2.0 * units::kPi * plan.frequency_hz * (k * dt));
      advance_to(s, 0.0, k == n ? x0 : x, 0.0, true);
    }
    ++r_.mixing_cycles;
    if (!estimator_ && !c_.scheduler.actuator_fitted) ++r_.maintenance_requests;  // a fixed visit
  }

  bool quake_before(double t) const {
    return next_quake_ < w_.quake_times_s.size() && w_.quake_times_s[next_quake_] <= t;
  }

  const World& w_;
  const ServiceConfig& c_;
  const PolicySpec p_;
  fw::SettlingModel truth_;
  app::BasicMixingTask<Policy> firmware_;
  PolicyResult r_;
  bool fixed_ = false;
  bool estimator_ = false;
  double period_s_ = 1e-3;
  double area_m2_ = 0.01062;
  double t_ = 0.0;
  double x_amb_m_ = 0.0;
  double amb_sign_ = 1.0;
  double x_mix_m_ = 0.0;
  std::size_t next_quake_ = 0;
  double next_fixed_s_ = kInf;
  double next_visit_s_ = kInf;
  bool pending_request_ = false;
  std::uint32_t started_id_ = 0;
  std::uint32_t maintenance_seen_ = 0;
};

}  // namespace

const char* numeric_build_name(NumericBuild b) noexcept {
  switch (b) {
    case NumericBuild::kDouble: return "double";
    case NumericBuild::kFloat: return "float";
    case NumericBuild::kFixed: return "fixed";
  }
  return "unknown";
}

NumericBuild parse_numeric_build(const std::string& name) {
  if (name == "double") return NumericBuild::kDouble;
  if (name == "float") return NumericBuild::kFloat;
  if (name == "fixed") return NumericBuild::kFixed;
  throw io::UsageError("--numeric: expected one of double, float, fixed; got '" + name + "'");
}

const char* policy_name(PolicyKind kind) noexcept {
  switch (kind) {
    case PolicyKind::kNone: return "none";
    case PolicyKind::kFixedInterval: return "fixed-interval";
    case PolicyKind::kEstimator: return "estimator";
  }
  return "unknown";
}

World make_world(const WorldConfig& c) {
  require(std::isfinite(c.years) && c.years > 0.0 && c.years <= 1000.0,
          "--years: expected a number of years > 0 and <= 1000");
  require(std::isfinite(c.earthquakes_per_year) && c.earthquakes_per_year >= 0.0 && c.earthquakes_per_year <= 1000.0,
          "--earthquakes-per-year: expected a rate >= 0 and <= 1000 per year");
  require(std::isfinite(c.ambient_median_m3_per_day) && c.ambient_median_m3_per_day >= 0.0,
          "--ambient-litres-per-day: expected a volume >= 0");
  require(std::isfinite(c.ambient_sigma_ln) && c.ambient_sigma_ln >= 0.0, "ambient log-standard deviation must be >= 0");
  require(std::isfinite(c.quake_duration_s) && c.quake_duration_s > 0.0, "earthquake duration must be > 0 s");
  require(std::isfinite(c.quake_volume_m3) && c.quake_volume_m3 >= 0.0, "earthquake volume must be >= 0");

  World w;
  w.duration_s = units::years_to_s(c.years);
  w.quake_duration_s = c.quake_duration_s;
  w.quake_volume_m3 = c.quake_volume_m3;
  w.quake_accel_m_s2 = c.quake_accel_m_s2;

  // Ambient: log-normal daily volume, exp(ln(median) + σ·z).
  const auto days = static_cast<std::size_t>(std::ceil(w.duration_s / units::kSecondsPerDay));
  w.ambient_m3_per_day.resize(days, 0.0);
  excitation::StandardNormal z(c.seed * 2 + 1);
  if (c.ambient_median_m3_per_day > 0.0) {
    const double mu = std::log(c.ambient_median_m3_per_day);
    for (double& v : w.ambient_m3_per_day) v = std::exp(mu + c.ambient_sigma_ln * z.next());
  }

  // Earthquakes: Poisson process, exponential gaps with mean 1/rate.
  if (c.earthquakes_per_year > 0.0) {
    std::mt19937_64 g(c.seed * 2);
    const double rate_per_s = c.earthquakes_per_year / units::kSecondsPerYear;
    double t = 0.0;
    for (;;) {
      t += -std::log(uniform_open0(g)) / rate_per_s;
      if (t >= w.duration_s) break;
      w.quake_times_s.push_back(t);
    }
  }
  return w;
}

PolicyResult simulate_policy(const World& world, const ServiceConfig& config, const PolicySpec& policy) {
  if (policy.kind == PolicyKind::kFixedInterval) {
    require(std::isfinite(policy.interval_s) && policy.interval_s > 0.0, "--interval-days: expected an interval > 0");
  }
  if (policy.kind != PolicyKind::kEstimator) return Run<fw::Float64Policy>(world, config, policy).go();
  switch (config.numeric) {
    case NumericBuild::kFloat: return Run<num::Float32Policy>(world, config, policy).go();
    case NumericBuild::kFixed: return Run<num::Fixed32Policy>(world, config, policy).go();
    case NumericBuild::kDouble: break;
  }
  return Run<fw::Float64Policy>(world, config, policy).go();
}

IntervalSearch longest_fixed_interval(const World& world, const ServiceConfig& config) {
  IntervalSearch s;
  const double threshold = config.scheduler.capacity_threshold;
  const auto meets = [&](double interval_s) {
    ++s.simulations;
    return simulate_policy(world, config, {PolicyKind::kFixedInterval, interval_s}).min_capacity_any_time >= threshold;
  };
  fw::SettlingModel m;
  m.init(config.estimator.model);
  double lo = config.search_resolution_s;
  double hi = 2.0 * m.max_settling_time_s();
  if (meets(hi)) return {hi, true, s.simulations};
  if (!meets(lo)) return {lo, false, s.simulations};
  while (hi - lo > config.search_resolution_s) {
    const double mid = 0.5 * (lo + hi);
    (meets(mid) ? lo : hi) = mid;
  }
  s.interval_s = lo;
  s.meets_threshold = true;
  return s;
}

fw::MixingPlan plan_at_threshold(const ServiceConfig& config) {
  fw::SettlingModel m;
  m.init(config.estimator.model);
  const double pr = m.pr_of_capacity(config.scheduler.capacity_threshold);
  m.reset(m.idle_of_pr(pr), 0.0);
  return fw::plan_mixing(config.scheduler, m.volume_to_ceiling_m3(0.0, config.scheduler.ceiling_gap_fraction));
}

}  // namespace mrd::schedule
