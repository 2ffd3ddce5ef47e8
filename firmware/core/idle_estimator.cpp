#include "firmware/core/idle_estimator.hpp"

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

// ---------------------------------------------------------------- IdleEstimator

bool IdleEstimator::init(const IdleEstimatorConfig& config) noexcept {
  c_ = config;
  const bool model_ok = model_.init(config.model);
  est_ = IdleEstimate{};
  booted_ = false;
  rtc_seen_ = false;
  anchored_ = false;
  save_due_ = false;
  save_sequence_ = 0;
  episodes_seen_ = 0;
  t_s_ = 0.0;
  return model_ok && config.period_s > 0.0 && config.save_interval_s > 0.0 && config.dead_band_m >= 0.0 &&
         config.clock_tolerance_s >= 0.0;
}

void IdleEstimator::start(std::uint64_t tick) noexcept {
  booted_ = true;
  tick0_ = tick;
  last_tick_ = tick;
  t_s_ = 0.0;
  anchored_ = false;
  prev_sample_t_s_ = 0.0;
  last_save_t_s_ = 0.0;
  episodes_seen_ = model_.episodes_closed();
}

void IdleEstimator::assume_worst(std::uint32_t cause) noexcept {
  est_.flags |= cause | kIdleAssumedSettled;
  model_.assume_settled(t_s_);
  episodes_seen_ = model_.episodes_closed();
  save_due_ = true;
}

IdleBootReport IdleEstimator::boot(hal::StateStore& store, std::uint64_t tick, double rtc_s,
                                   bool rtc_valid) noexcept {
  IdleBootReport rep;
  start(tick);
  est_.flags = 0;
  rtc_seen_ = rtc_valid && std::isfinite(rtc_s);
  last_rtc_s_ = rtc_s;
  last_rtc_t_s_ = 0.0;

  hal::StateRecord rec{};
  rep.load = store.load(rec);
  PersistedIdleState s;
  if (rep.load == hal::StoreStatus::kOk) rep.decode = decode_state(rec, s);

  if (rep.load == hal::StoreStatus::kOk && rep.decode == DecodeStatus::kOk) {
    est_.lifetime_volume_m3 = s.lifetime_volume_m3;
    est_.mixing_volume_m3 = s.mixing_volume_m3;
    est_.mixing_cycles = s.mixing_cycles;
    save_sequence_ = s.save_sequence;
    const double offline_s = rtc_s - s.rtc_s;
    if (!rtc_seen_) {
      assume_worst(kIdleClockInvalid);
    } else if (offline_s < -c_.clock_tolerance_s) {
      assume_worst(kIdleClockBackwards);
    } else {
      rep.offline_s = max0(offline_s);
      model_.reset(s.equivalent_idle_s + rep.offline_s, 0.0);  // the time off was idle time
      episodes_seen_ = model_.episodes_closed();
    }
  } else if (rep.load == hal::StoreStatus::kMissing) {
    assume_worst(kIdleNoSavedState);
  } else if (rep.load == hal::StoreStatus::kIoError) {
    assume_worst(kIdleStoreIoError);
  } else {
    assume_worst(kIdleCorruptState);  // wrong size or refused by decode_state
  }
  refresh();
  rep.flags = est_.flags;
  return rep;
}

void IdleEstimator::boot_with(double equivalent_idle_s, std::uint64_t tick, double rtc_s) noexcept {
  start(tick);
  est_.flags = 0;
  rtc_seen_ = std::isfinite(rtc_s);
  last_rtc_s_ = rtc_s;
  last_rtc_t_s_ = 0.0;
  model_.reset(equivalent_idle_s, 0.0);
  episodes_seen_ = model_.episodes_closed();
  refresh();
}

double IdleEstimator::time_of(std::uint64_t tick) const noexcept {
  return static_cast<double>(tick - tick0_) * c_.period_s;
}

void IdleEstimator::step(const IdleEstimatorInput& in) noexcept {
  if (!booted_) {
    start(in.tick);
    est_.flags = 0;
    assume_worst(kIdleNoSavedState);
  }
  if (in.tick < last_tick_) return;  // ticks never go back within a boot; ignore such a sample
  last_tick_ = in.tick;
  t_s_ = time_of(in.tick);

  // Wall clock: only checked here; in-boot time comes from the ticks.
  if (in.rtc_valid && std::isfinite(in.rtc_s)) {
    if (rtc_seen_ && in.rtc_s < last_rtc_s_ - c_.clock_tolerance_s) {
      assume_worst(kIdleClockBackwards);
    }
    rtc_seen_ = true;
    last_rtc_s_ = in.rtc_s;
    last_rtc_t_s_ = t_s_;
  }

  // Displacement through the play operator: y follows x within ±dead band.
  if (in.disp_valid && std::isfinite(in.damper_disp_m)) {
    const double x = in.damper_disp_m;
    if (!anchored_) {
      anchored_ = true;
      play_m_ = x;
    } else {
      double y = play_m_;
      if (x > y + c_.dead_band_m) y = x - c_.dead_band_m;
      if (x < y - c_.dead_band_m) y = x + c_.dead_band_m;
      const double dv_m3 = std::fabs(y - play_m_) * c_.model.pr.flow_area_m2;  // |Δy|·A, Eq. 5.9's ∫Q dt
      play_m_ = y;
      if (dv_m3 > 0.0) {
        model_.add_motion(prev_sample_t_s_, t_s_, dv_m3);
        est_.lifetime_volume_m3 += dv_m3;
        if (in.mixing_active) est_.mixing_volume_m3 += dv_m3;
      }
    }
    prev_sample_t_s_ = t_s_;
  }

  model_.advance(t_s_);
  if (model_.episodes_closed() != episodes_seen_) {
    episodes_seen_ = model_.episodes_closed();
    save_due_ = true;
  }
  if (t_s_ - last_save_t_s_ >= c_.save_interval_s) save_due_ = true;
  refresh();
}

void IdleEstimator::refresh() noexcept {
  est_.equivalent_idle_s = model_.equivalent_idle_s(t_s_);
  est_.sq = model_.sq_of_idle(est_.equivalent_idle_s);
  est_.participant_ratio = model_.participant_ratio(t_s_);
  est_.capacity_fraction = model_.capacity_of_pr(est_.participant_ratio);
  est_.episode_open = model_.episode_open();
  est_.episode_volume_m3 = model_.episode_volume_m3();
  est_.time_since_motion_s = max0(t_s_ - model_.last_motion_s());
}

SaveOutcome IdleEstimator::save(hal::StateStore& store) noexcept {
  if (!rtc_seen_) return SaveOutcome::kSkippedNoClock;
  PersistedIdleState s;
  s.equivalent_idle_s = model_.equivalent_idle_s(t_s_);
  s.rtc_s = last_rtc_s_ + (t_s_ - last_rtc_t_s_);
  s.lifetime_volume_m3 = est_.lifetime_volume_m3;
  s.mixing_volume_m3 = est_.mixing_volume_m3;
  s.mixing_cycles = est_.mixing_cycles;
  s.save_sequence = save_sequence_ + 1;
  s.flags = est_.flags;
  if (store.save(encode_state(s)) != hal::StoreStatus::kOk) {
    est_.flags |= kIdleSaveFailed;
    return SaveOutcome::kFailed;  // still due: the caller retries later
  }
  save_sequence_ = s.save_sequence;
  est_.flags &= ~static_cast<std::uint32_t>(kIdleSaveFailed);
  save_due_ = false;
  last_save_t_s_ = t_s_;
  return SaveOutcome::kSaved;
}

void IdleEstimator::note_mixing_confirmed() noexcept {
  ++est_.mixing_cycles;
  save_due_ = true;
}

double IdleEstimator::predicted_capacity_fraction(double horizon_s) const noexcept {
  return model_.predicted_capacity_fraction(t_s_, horizon_s);
}

double IdleEstimator::volume_to_ceiling_m3(double gap_fraction) const noexcept {
  return model_.volume_to_ceiling_m3(t_s_, gap_fraction);
}

}  // namespace mrd::fw
