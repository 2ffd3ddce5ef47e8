#pragma once
/// Definitions of BasicIdleModel and BasicIdleEstimator (idle_estimator.hpp),
/// included only by the three files that instantiate them.

#include <cmath>

#include "firmware/core/idle_estimator.hpp"
#include "mrd/physics/bingham.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::fw {

// ---------------------------------------------------------------- BasicIdleModel

template <class Policy>
bool BasicIdleModel<Policy>::init(const IdleModelConfig& config, double period_s) noexcept {
  period_s_ = period_s > 0.0 ? period_s : 1.0e-3;
  const physics::ParticipantRatioParams& p = config.pr;
  bool ok = config.quiet_close_s > 0.0 && config.max_episode_s > 0.0 && p.flow_area_m2 > 0.0 &&
            p.volume_unit_m3 > 0.0 && config.reference_velocity_m_s > 0.0 && config.nominal_current_a >= 0.0 &&
            p.a_initial > p.b_initial && p.c_initial > 0.0 && period_s > 0.0;
  double t_max_s = physics::max_settling_time_s(config.settling);  // Eq. 5.4
  if (!(t_max_s > 0.0) || !std::isfinite(t_max_s)) t_max_s = 1.0;
  t_max_ = ticks_at_least(t_max_s, period_s_);
  if (t_max_ == 0) t_max_ = 1;
  quiet_close_ = ticks_at_least(config.quiet_close_s, period_s_);
  max_episode_ = ticks_at_least(config.max_episode_s, period_s_);
  const double f0 = physics::damper_force_n(config.bingham, config.nominal_current_a, config.reference_velocity_m_s, 0.0);
  const double f1 = physics::damper_force_n(config.bingham, config.nominal_current_a, config.reference_velocity_m_s, 1.0);
  ok = ok && f1 > f0 && f1 > 0.0;
  const double cap0 = f1 > 0.0 ? f0 / f1 : 0.0;
  const double cap1 = f1 > 0.0 ? (f1 - f0) / f1 : 1.0;
  const double per_unit = p.volume_unit_m3 > 0.0 ? 1.0 / p.volume_unit_m3 : 0.0;
  // Every constant must fit its format (fixed point): PR, spans and the
  // capacity terms in Ratio, rates in Coef, c_PR/unit in Rate.
  ok = ok && representable<Ratio>(p.b_initial) && representable<Ratio>(p.a_initial - p.b_initial) &&
       representable<Ratio>(p.b_final) && representable<Ratio>(p.a_final - p.b_final) &&
       representable<Coef>(p.c_initial) && representable<Coef>(p.c_final) && representable<Coef>(p.c_rise) &&
       representable<Coef>(p.b_rise) && representable<Coef>(p.a_rise - p.b_rise) &&
       representable<Coef>(p.a_rise) && representable<Rate>(per_unit) &&
       representable<Rate>(per_unit * (p.a_rise > p.b_rise ? p.a_rise : p.b_rise)) &&
       representable<Ratio>(cap0) && representable<Ratio>(cap1);
  b_init_ = A::template from<Ratio>(p.b_initial);
  span_init_ = A::template from<Ratio>(p.a_initial - p.b_initial);
  c_init_ = A::template from<Coef>(p.c_initial);
  b_final_ = A::template from<Ratio>(p.b_final);
  span_final_ = A::template from<Ratio>(p.a_final - p.b_final);
  c_final_ = A::template from<Coef>(p.c_final);
  b_rise_ = A::template from<Coef>(p.b_rise);
  span_rise_ = A::template from<Coef>(p.a_rise - p.b_rise);
  c_rise_ = A::template from<Coef>(p.c_rise);
  per_unit_ = A::template from<Rate>(per_unit);
  cap0_ = A::template from<Ratio>(cap0);
  cap1_ = A::template from<Ratio>(cap1);
  episodes_closed_ = 0;
  assume_settled(0);
  return ok;
}

template <class Policy>
void BasicIdleModel<Policy>::reset(std::uint64_t equivalent_idle_ticks, std::uint64_t t) noexcept {
  base_idle_ = equivalent_idle_ticks < t_max_ ? equivalent_idle_ticks : t_max_;
  base_t_ = t;
  open_ = false;
  episode_ = A::vol_zero();
  last_motion_ = t;
}

template <class Policy>
typename BasicIdleModel<Policy>::Coefficients BasicIdleModel<Policy>::coefficients_of(Ratio sq) const noexcept {
  // Eq. 5.6–5.8: b + (a − b)·exp(−c·SQ) for each of a_PR, b_PR, c_PR.
  Coefficients k;
  k.a = b_init_ + A::mul(span_init_, A::exp_neg(A::times(c_init_, sq)));
  k.b = b_final_ + A::mul(span_final_, A::exp_neg(A::times(c_final_, sq)));
  k.c = b_rise_ + A::mul_coef(span_rise_, A::exp_neg(A::times(c_rise_, sq)));
  k.rate = A::rate_of(k.c, per_unit_);
  return k;
}

template <class Policy>
typename BasicIdleModel<Policy>::Ratio BasicIdleModel<Policy>::pr_of_idle(std::uint64_t idle_ticks) const noexcept {
  // Eq. 5.6 at SQ(τ) (Eq. 5.5).
  return b_init_ + A::mul(span_init_, A::exp_neg(A::times(c_init_, sq_of_idle(idle_ticks))));
}

template <class Policy>
std::uint64_t BasicIdleModel<Policy>::idle_of_pr(Ratio pr) const noexcept {
  // Eq. 5.6 solved for SQ: SQ = ln((a_i − b_i)/(PR − b_i))/c_i, clamped to [0, 1].
  const Ratio above = pr - b_init_;
  if (!(A::zero() < above)) return t_max_;
  if (!(above < span_init_)) return 0;
  return A::scale_ticks(A::div_clamp01(A::ln_quotient(span_init_, above), c_init_), t_max_);
}

template <class Policy>
std::uint64_t BasicIdleModel<Policy>::equivalent_idle_ticks(std::uint64_t t) const noexcept {
  const std::uint64_t tau = open_ ? idle_of_pr(pr_) + (t > open_t_ ? t - open_t_ : 0)
                                  : base_idle_ + (t > base_t_ ? t - base_t_ : 0);
  return tau < t_max_ ? tau : t_max_;
}

template <class Policy>
typename BasicIdleModel<Policy>::Ratio BasicIdleModel<Policy>::participant_ratio(std::uint64_t t) const noexcept {
  return open_ ? pr_ : pr_of_idle(equivalent_idle_ticks(t));
}

template <class Policy>
typename BasicIdleModel<Policy>::Ratio BasicIdleModel<Policy>::predicted_capacity(
    std::uint64_t t, std::uint64_t horizon_ticks) const noexcept {
  const std::uint64_t tau = equivalent_idle_ticks(t);
  const std::uint64_t later = horizon_ticks < t_max_ - tau ? tau + horizon_ticks : t_max_;
  return capacity_of_pr(pr_of_idle(later));
}

template <class Policy>
typename BasicIdleModel<Policy>::Coefficients BasicIdleModel<Policy>::coefficients_at(std::uint64_t t) const noexcept {
  return open_ ? coeff_ : coefficients_of(sq_of_idle(equivalent_idle_ticks(t)));
}

template <class Policy>
typename BasicIdleModel<Policy>::Volume BasicIdleModel<Policy>::volume_to_ceiling(std::uint64_t t,
                                                                                  Ratio gap_fraction) const noexcept {
  // Eq. 5.9: (a − b)·exp(−c·V/unit) = g·b  ⇒  V = ln((a − b)/(g·b))·unit/c.
  const Coefficients k = coefficients_at(t);
  const Ratio d = k.a - k.b;
  const Ratio gap = d < A::zero() ? A::zero() - d : d;
  const Ratio target = A::mul(gap_fraction, k.b);
  if (!(Rate{} < k.rate) || !(A::zero() < target) || !(target < gap)) return A::vol_zero();
  return A::vol_sub0(A::vol_of_expo(A::ln_quotient(gap, target), k.rate), episode_volume());
}

template <class Policy>
void BasicIdleModel<Policy>::add_motion(std::uint64_t t0, std::uint64_t t1, Volume volume) noexcept {
  if (!A::vol_positive(volume)) return;
  advance(t0);
  if (!open_) {
    coeff_ = coefficients_of(sq_of_idle(equivalent_idle_ticks(t0)));  // Eq. 5.6–5.8, frozen for the episode
    open_ = true;
    open_t_ = t0;
    episode_ = A::vol_zero();
  }
  episode_ = A::vol_add(episode_, volume);
  pr_ = coeff_.b + A::mul(coeff_.a - coeff_.b, A::exp_neg(A::expo_of(coeff_.rate, episode_)));  // Eq. 5.9
  last_motion_ = t1;
  if (t1 - open_t_ >= max_episode_) close(t1);
}

template <class Policy>
void BasicIdleModel<Policy>::advance(std::uint64_t t) noexcept {
  if (open_ && t >= last_motion_ + quiet_close_) close(last_motion_ + quiet_close_);
}

template <class Policy>
void BasicIdleModel<Policy>::close(std::uint64_t t_close) noexcept {
  const std::uint64_t tau = idle_of_pr(pr_) + (t_close > open_t_ ? t_close - open_t_ : 0);
  open_ = false;
  base_idle_ = tau < t_max_ ? tau : t_max_;
  base_t_ = t_close;
  episode_ = A::vol_zero();
  ++episodes_closed_;
}

// ---------------------------------------------------------------- BasicIdleEstimator

template <class Policy>
bool BasicIdleEstimator<Policy>::init(const IdleEstimatorConfig& config) noexcept {
  c_ = config;
  const double us = config.period_s * 1.0e6;
  const double us_round = std::round(us);
  const bool period_ok = config.period_s > 0.0 && us_round >= 1.0 && std::fabs(us - us_round) <= 1e-6 * us_round;
  period_us_ = period_ok ? static_cast<std::uint64_t>(us_round) : 1000u;
  const double period_s = period_ok ? config.period_s : 1.0e-3;
  const bool model_ok = model_.init(config.model, period_s);
  period_s_ = static_cast<Sample>(period_s);
  dead_band_ = A::template from<Disp>(config.dead_band_m);
  area_ = A::template from<typename A::Area>(config.model.pr.flow_area_m2);
  clock_tolerance_ms_ = std::llround(config.clock_tolerance_s * 1000.0);
  save_interval_ = ticks_at_least(config.save_interval_s, period_s);
  est_ = Estimate{};
  lifetime_ = A::vol_zero();
  mixing_ = A::vol_zero();
  booted_ = false;
  rtc_seen_ = false;
  anchored_ = false;
  save_due_ = false;
  save_sequence_ = 0;
  episodes_seen_ = 0;
  t_ = 0;
  return model_ok && period_ok && config.save_interval_s > 0.0 && config.dead_band_m >= 0.0 &&
         config.clock_tolerance_s >= 0.0 && representable<Disp>(config.dead_band_m) &&
         representable<typename A::Area>(config.model.pr.flow_area_m2) && std::isfinite(config.clock_tolerance_s);
}

template <class Policy>
void BasicIdleEstimator<Policy>::start(std::uint64_t tick) noexcept {
  booted_ = true;
  tick0_ = tick;
  last_tick_ = tick;
  t_ = 0;
  anchored_ = false;
  prev_sample_t_ = 0;
  last_save_t_ = 0;
  episodes_seen_ = model_.episodes_closed();
}

template <class Policy>
void BasicIdleEstimator<Policy>::assume_worst(std::uint32_t cause) noexcept {
  est_.flags |= cause | kIdleAssumedSettled;
  model_.assume_settled(t_);
  episodes_seen_ = model_.episodes_closed();
  save_due_ = true;
}

template <class Policy>
void BasicIdleEstimator<Policy>::restore_counters(const PersistedIdleState& s) noexcept {
  lifetime_ = A::vol_from_counts(s.lifetime_volume);
  mixing_ = A::vol_from_counts(s.mixing_volume);
  est_.mixing_cycles = s.mixing_cycles;
  save_sequence_ = s.save_sequence;
}

template <class Policy>
IdleBootReport BasicIdleEstimator<Policy>::boot(hal::StateStore& store, std::uint64_t tick, Rtc rtc,
                                                bool rtc_valid) noexcept {
  IdleBootReport rep;
  start(tick);
  est_.flags = 0;
  std::int64_t rtc_ms = 0;
  rtc_seen_ = rtc_valid && A::rtc_ms_of(rtc, rtc_ms);
  last_rtc_ms_ = rtc_ms;
  last_rtc_t_ = 0;

  hal::StateRecord rec{};
  rep.load = store.load(rec);
  PersistedIdleState s;
  if (rep.load == hal::StoreStatus::kOk) rep.decode = decode_state(rec, s);

  if (rep.load == hal::StoreStatus::kOk && rep.decode == DecodeStatus::kOk) {
    restore_counters(s);
    std::int64_t offline_ms = 0;
    const bool span_ok = !__builtin_sub_overflow(rtc_ms, s.rtc_ms, &offline_ms);
    if (!rtc_seen_) {
      assume_worst(kIdleClockInvalid);
    } else if (!span_ok || offline_ms < -clock_tolerance_ms_) {
      assume_worst(kIdleClockBackwards);
    } else {
      const std::uint64_t off_ms = offline_ms > 0 ? static_cast<std::uint64_t>(offline_ms) : 0;
      rep.offline_s = static_cast<double>(off_ms) * 1e-3;
      const std::uint64_t stored = ticks_of_ms(s.equivalent_idle_ms);
      const std::uint64_t off = ticks_of_ms(off_ms);
      model_.reset(stored < model_.max_settling_ticks() ? stored + off : stored, 0);  // the time off was idle time
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

template <class Policy>
void BasicIdleEstimator<Policy>::boot_with(double equivalent_idle_s, std::uint64_t tick, Rtc rtc) noexcept {
  start(tick);
  est_.flags = 0;
  std::int64_t rtc_ms = 0;
  rtc_seen_ = A::rtc_ms_of(rtc, rtc_ms);
  last_rtc_ms_ = rtc_ms;
  last_rtc_t_ = 0;
  const double idle_ticks = equivalent_idle_s > 0.0 ? equivalent_idle_s / c_.period_s : 0.0;
  model_.reset(idle_ticks < 4.0e18 ? static_cast<std::uint64_t>(std::llround(idle_ticks)) : model_.max_settling_ticks(),
               0);
  episodes_seen_ = model_.episodes_closed();
  refresh();
}

template <class Policy>
void BasicIdleEstimator<Policy>::step(const Input& in) noexcept {
  if (!booted_) {
    start(in.tick);
    est_.flags = 0;
    assume_worst(kIdleNoSavedState);
  }
  if (in.tick < last_tick_) return;  // ticks never go back within a boot; ignore such a sample
  last_tick_ = in.tick;
  t_ = in.tick - tick0_;

  // Wall clock: only checked here; in-boot time comes from the ticks.
  std::int64_t rtc_ms = 0;
  if (in.rtc_valid && A::rtc_ms_of(in, rtc_ms)) {
    const bool back = rtc_ms < last_rtc_ms_ && static_cast<std::uint64_t>(last_rtc_ms_) - static_cast<std::uint64_t>(rtc_ms) >
                                                   static_cast<std::uint64_t>(clock_tolerance_ms_);
    if (rtc_seen_ && back) assume_worst(kIdleClockBackwards);
    rtc_seen_ = true;
    last_rtc_ms_ = rtc_ms;
    last_rtc_t_ = t_;
  }

  // Displacement through the play operator: y follows x within ±dead band.
  if (in.disp_valid && A::sample_ok(in.damper_disp_m)) {
    const Disp x = A::disp_of(in.damper_disp_m);
    if (!anchored_) {
      anchored_ = true;
      play_ = x;
    } else {
      Disp y = play_;
      if (x > y + dead_band_) y = x - dead_band_;
      if (x < y - dead_band_) y = x + dead_band_;
      const Volume dv = A::vol_of_stroke(A::abs(y - play_), area_);  // |Δy|·A, Eq. 5.9's ∫Q dt
      play_ = y;
      if (A::vol_positive(dv)) {
        model_.add_motion(prev_sample_t_, t_, dv);
        lifetime_ = A::vol_add(lifetime_, dv);
        if (in.mixing_active) mixing_ = A::vol_add(mixing_, dv);
      }
    }
    prev_sample_t_ = t_;
  }

  model_.advance(t_);
  if (model_.episodes_closed() != episodes_seen_) {
    episodes_seen_ = model_.episodes_closed();
    save_due_ = true;
  }
  if (t_ - last_save_t_ >= save_interval_) save_due_ = true;
  refresh();
}

template <class Policy>
void BasicIdleEstimator<Policy>::refresh() noexcept {
  const std::uint64_t tau = model_.equivalent_idle_ticks(t_);
  const Ratio pr = model_.participant_ratio(t_);
  est_.equivalent_idle_s = A::seconds(tau, period_s_);
  est_.sq = A::to_sample(model_.sq_of_idle(tau));
  est_.participant_ratio = A::to_sample(pr);
  est_.capacity_fraction = A::to_sample(model_.capacity_of_pr(pr));
  est_.episode_open = model_.episode_open();
  est_.episode_volume_m3 = A::vol_to_sample(model_.episode_volume());
  est_.lifetime_volume_m3 = A::vol_to_sample(lifetime_);
  est_.mixing_volume_m3 = A::vol_to_sample(mixing_);
  const std::uint64_t last = model_.last_motion_tick();
  est_.time_since_motion_s = A::seconds(t_ > last ? t_ - last : 0, period_s_);
}

template <class Policy>
SaveOutcome BasicIdleEstimator<Policy>::save(hal::StateStore& store) noexcept {
  if (!rtc_seen_) return SaveOutcome::kSkippedNoClock;
  PersistedIdleState s;
  s.equivalent_idle_ms = ms_of_ticks(model_.equivalent_idle_ticks(t_));
  s.rtc_ms = last_rtc_ms_ + static_cast<std::int64_t>(ms_of_ticks(t_ - last_rtc_t_));
  s.lifetime_volume = A::vol_to_counts(lifetime_);
  s.mixing_volume = A::vol_to_counts(mixing_);
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
  last_save_t_ = t_;
  return SaveOutcome::kSaved;
}

template <class Policy>
void BasicIdleEstimator<Policy>::note_mixing_confirmed() noexcept {
  ++est_.mixing_cycles;
  save_due_ = true;
}

template <class Policy>
typename BasicIdleEstimator<Policy>::Ratio BasicIdleEstimator<Policy>::predicted_capacity(
    std::uint64_t horizon_ticks) const noexcept {
  return model_.predicted_capacity(t_, horizon_ticks);
}

template <class Policy>
typename BasicIdleEstimator<Policy>::Volume BasicIdleEstimator<Policy>::volume_to_ceiling(
    Ratio gap_fraction) const noexcept {
  return model_.volume_to_ceiling(t_, gap_fraction);
}

template <class Policy>
double BasicIdleEstimator<Policy>::predicted_capacity_fraction(double horizon_s) const noexcept {
  return A::to_double(predicted_capacity(ticks_at_least(horizon_s, c_.period_s)));
}

template <class Policy>
double BasicIdleEstimator<Policy>::volume_to_ceiling_m3(double gap_fraction) const noexcept {
  return A::vol_to_double(volume_to_ceiling(A::template from<Ratio>(gap_fraction)));
}

}  // namespace mrd::fw
