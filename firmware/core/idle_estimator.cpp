// SettlingModel and the double (reference) build of the idle-time estimator.
#include "firmware/core/idle_estimator.hpp"

#include "firmware/core/idle_estimator_impl.hpp"

#include <cmath>

namespace mrd::fw {
namespace {

double clamp01(double x) noexcept { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }
double max0(double x) noexcept { return x > 0.0 ? x : 0.0; }

}  // namespace

// ---------------------------------------------------------------- SettlingModel

bool SettlingModel::init(const IdleModelConfig& config) noexcept {
  c_ = config;
  const bool ok = config.quiet_close_s > 0.0 && config.max_episode_s > 0.0 && config.pr.flow_area_m2 > 0.0 &&
                  config.pr.volume_unit_m3 > 0.0 && config.reference_velocity_m_s > 0.0 &&
                  config.nominal_current_a >= 0.0 && config.pr.a_initial > config.pr.b_initial &&
                  config.pr.c_initial > 0.0;
  t_max_s_ = physics::max_settling_time_s(config.settling);  // Eq. 5.4
  if (!(t_max_s_ > 0.0) || !std::isfinite(t_max_s_)) t_max_s_ = 1.0;
  force_pr0_n_ = physics::damper_force_n(c_.bingham, c_.nominal_current_a, c_.reference_velocity_m_s, 0.0);
  force_pr1_n_ = physics::damper_force_n(c_.bingham, c_.nominal_current_a, c_.reference_velocity_m_s, 1.0);
  episodes_closed_ = 0;
  assume_settled(0.0);
  return ok && force_pr1_n_ > force_pr0_n_;
}

void SettlingModel::reset(double equivalent_idle_s, double t_s) noexcept {
  base_idle_s_ = equivalent_idle_s < t_max_s_ ? max0(equivalent_idle_s) : t_max_s_;
  base_t_s_ = t_s;
  open_ = false;
  episode_m3_ = 0.0;
  last_motion_s_ = t_s;
}

double SettlingModel::sq_of_idle(double idle_s) const noexcept {
  return physics::settling_quotient(idle_s, t_max_s_);  // Eq. 5.5
}

double SettlingModel::pr_of_idle(double idle_s) const noexcept {
  return physics::pr_coefficients(c_.pr, sq_of_idle(idle_s)).a_pr;  // Eq. 5.6
}

double SettlingModel::idle_of_pr(double pr) const noexcept {
  // Eq. 5.6 solved for SQ: a_PR = b_i + (a_i − b_i)·exp(−c_i·SQ).
  const double span = c_.pr.a_initial - c_.pr.b_initial;
  const double rel = (pr - c_.pr.b_initial) / span;
  if (!(rel > 0.0)) return t_max_s_;
  if (rel >= 1.0) return 0.0;
  return clamp01(-std::log(rel) / c_.pr.c_initial) * t_max_s_;
}

double SettlingModel::capacity_of_pr(double pr) const noexcept {
  // Eq. 5.10–5.12 with the transition function Eq. 4.4.
  return physics::damper_force_n(c_.bingham, c_.nominal_current_a, c_.reference_velocity_m_s, pr) / force_pr1_n_;
}

double SettlingModel::pr_of_capacity(double capacity_fraction) const noexcept {
  // F(PR) = F(0) + PR·(F(1) − F(0)).
  return (capacity_fraction * force_pr1_n_ - force_pr0_n_) / (force_pr1_n_ - force_pr0_n_);
}

double SettlingModel::equivalent_idle_s(double t_s) const noexcept {
  const double tau = open_ ? idle_of_pr(pr_) + max0(t_s - open_t_s_) : base_idle_s_ + max0(t_s - base_t_s_);
  return tau < t_max_s_ ? tau : t_max_s_;
}

double SettlingModel::participant_ratio(double t_s) const noexcept {
  return open_ ? pr_ : pr_of_idle(equivalent_idle_s(t_s));
}

double SettlingModel::predicted_capacity_fraction(double t_s, double horizon_s) const noexcept {
  return capacity_of_pr(pr_of_idle(equivalent_idle_s(t_s) + max0(horizon_s)));
}

physics::PrCoefficients SettlingModel::coefficients_at(double t_s) const noexcept {
  if (open_) return coeff_;
  return physics::pr_coefficients(c_.pr, sq_of_idle(equivalent_idle_s(t_s)));  // Eq. 5.6–5.8
}

double SettlingModel::volume_to_ceiling_m3(double t_s, double gap_fraction) const noexcept {
  // Eq. 5.9: (a − b)·exp(−c·V/unit) = g·b  ⇒  V = unit·ln((a − b)/(g·b))/c.
  const physics::PrCoefficients k = coefficients_at(t_s);
  const double gap = std::fabs(k.a_pr - k.b_pr);
  const double target = gap_fraction * k.b_pr;
  if (!(k.c_pr > 0.0) || !(target > 0.0) || gap <= target) return 0.0;
  const double total_m3 = c_.pr.volume_unit_m3 * std::log(gap / target) / k.c_pr;
  return max0(total_m3 - episode_volume_m3());
}

void SettlingModel::add_motion(double t0_s, double t1_s, double volume_m3) noexcept {
  if (!(volume_m3 > 0.0)) return;
  advance(t0_s);
  if (!open_) {
    const double tau = equivalent_idle_s(t0_s);
    coeff_ = physics::pr_coefficients(c_.pr, sq_of_idle(tau));  // Eq. 5.6–5.8, frozen for the episode
    open_ = true;
    open_t_s_ = t0_s;
    episode_m3_ = 0.0;
  }
  episode_m3_ += volume_m3;
  pr_ = physics::participant_ratio(coeff_, episode_m3_ / c_.pr.volume_unit_m3);  // Eq. 5.9
  last_motion_s_ = t1_s;
  if (t1_s - open_t_s_ >= c_.max_episode_s) close(t1_s);
}

void SettlingModel::advance(double t_s) noexcept {
  if (open_ && t_s - last_motion_s_ >= c_.quiet_close_s) close(last_motion_s_ + c_.quiet_close_s);
}

void SettlingModel::close(double t_close_s) noexcept {
  const double tau = idle_of_pr(pr_) + max0(t_close_s - open_t_s_);
  open_ = false;
  base_idle_s_ = tau < t_max_s_ ? tau : t_max_s_;
  base_t_s_ = t_close_s;
  episode_m3_ = 0.0;
  ++episodes_closed_;
}

template class BasicIdleModel<Float64Policy>;
template class BasicIdleEstimator<Float64Policy>;

}  // namespace mrd::fw
