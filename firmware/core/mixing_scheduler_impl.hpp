#pragma once
/// Definitions of BasicMixingScheduler (mixing_scheduler.hpp), included only
/// by the three files that instantiate it.

#include <cmath>

#include "firmware/core/mixing_scheduler.hpp"

namespace mrd::fw {

template <class Policy>
bool BasicMixingScheduler<Policy>::init(const MixingSchedulerConfig& config) noexcept {
  c_ = config;
  const double period_s = c_.period_s > 0.0 ? c_.period_s : 1.0e-3;
  // One cycle, designed in double (plan_mixing's formulas).
  const MixingPlan one = plan_mixing(c_, 0.0);
  const double per_cycle_m3 = 4.0 * one.amplitude_m * c_.flow_area_m2;
  const double cycle_s = one.frequency_hz > 0.0 ? 1.0 / one.frequency_hz : 0.0;
  unit_plan_ = Plan{};
  unit_plan_.amplitude_m = static_cast<Sample>(one.amplitude_m);
  unit_plan_.frequency_hz = static_cast<Sample>(one.frequency_hz);
  unit_plan_.cycles = 1;
  unit_plan_.volume_m3 = A::vol_from_double(per_cycle_m3);
  unit_plan_.duration_s = static_cast<Sample>(cycle_s);
  unit_plan_.peak_velocity_m_s = static_cast<Sample>(one.peak_velocity_m_s);
  unit_plan_.peak_accel_m_s2 = static_cast<Sample>(one.peak_accel_m_s2);
  const double cycle_ticks = cycle_s / period_s;
  cycle_q16_ = static_cast<std::uint64_t>(std::llround(cycle_ticks * 65536.0));
  run_limit_q16_ = static_cast<std::uint64_t>(std::llround(cycle_ticks * c_.run_timeout_factor * 65536.0));
  unit_plan_.duration_ticks = (cycle_q16_ + 32768u) >> 16;
  threshold_ = A::template from<Ratio>(c_.capacity_threshold);
  gap_ = A::template from<Ratio>(c_.ceiling_gap_fraction);
  start_fraction_ = A::template from<Ratio>(c_.start_fraction);
  confirm_fraction_ = A::template from<Ratio>(c_.confirm_fraction);
  ground_trigger_ = A::template from<Accel>(c_.ground_trigger_m_s2);
  base_trigger_ = A::template from<Accel>(c_.base_trigger_m_s2);
  plan_peak_accel_ = A::template from<Accel>(one.peak_accel_m_s2);
  horizon_ = ticks_at_least(forecast_horizon_s(), period_s);
  start_timeout_ = ticks_within(c_.start_timeout_s, period_s);
  run_margin_ = ticks_within(c_.run_margin_s, period_s);
  confirm_hold_ = ticks_at_least(c_.confirm_hold_s, period_s);
  holdoff_ = ticks_at_least(c_.holdoff_s, period_s);
  reset();
  const bool formats_ok = representable<Ratio>(c_.start_fraction) && representable<Ratio>(c_.ceiling_gap_fraction) &&
                          representable<Accel>(c_.ground_trigger_m_s2) &&
                          representable<Accel>(c_.base_trigger_m_s2 + one.peak_accel_m_s2) &&
                          per_cycle_m3 * static_cast<double>(c_.max_cycles) < 1.0e6 &&
                          cycle_ticks * c_.run_timeout_factor * static_cast<double>(c_.max_cycles) < 1.0e12;
  return c_.period_s > 0.0 && c_.capacity_threshold > 0.0 && c_.capacity_threshold < 1.0 && c_.lead_time_s >= 0.0 &&
         c_.maintenance_lead_time_s >= 0.0 && c_.max_amplitude_m > 0.0 && c_.max_velocity_m_s > 0.0 &&
         c_.preferred_frequency_hz > 0.0 && c_.flow_area_m2 > 0.0 && c_.ceiling_gap_fraction > 0.0 &&
         c_.min_cycles >= 1 && c_.min_cycles <= c_.max_cycles && c_.ground_trigger_m_s2 > 0.0 &&
         c_.base_trigger_m_s2 > 0.0 && c_.seismic_samples >= 1 && c_.start_fraction > 0.0 &&
         c_.confirm_fraction > 0.0 && c_.confirm_fraction <= 1.0 && c_.start_timeout_s > 0.0 &&
         c_.run_timeout_factor >= 1.0 && c_.run_margin_s >= 0.0 && c_.confirm_hold_s >= 0.0 &&
         c_.holdoff_s >= 0.0 && c_.max_attempts >= 1 && formats_ok;
}

template <class Policy>
void BasicMixingScheduler<Policy>::reset() noexcept {
  out_ = Output{};
  counters_ = MixingCounters{};
  ground_count_ = 0;
  base_count_ = 0;
  shaking_ever_ = false;
  last_shaking_ = 0;
  state_since_ = 0;
  volume_at_request_ = A::vol_zero();
  start_volume_ = A::vol_zero();
  confirm_volume_ = A::vol_zero();
  run_limit_ = 0;
  failed_in_row_ = 0;
}

template <class Policy>
typename BasicMixingScheduler<Policy>::Plan BasicMixingScheduler<Policy>::plan_for(Volume volume_needed) const noexcept {
  std::uint32_t n = A::cycles_for(volume_needed, unit_plan_.volume_m3, c_.max_cycles);
  if (n < c_.min_cycles) n = c_.min_cycles;
  Plan p = unit_plan_;
  p.cycles = n;
  p.volume_m3 = A::vol_times(unit_plan_.volume_m3, n);
  p.duration_s = static_cast<Sample>(n) / unit_plan_.frequency_hz;
  p.duration_ticks = (cycle_q16_ * n + 32768u) >> 16;
  return p;
}

template <class Policy>
void BasicMixingScheduler<Policy>::end_cycle(SchedulerState next, MixingEndReason why, std::uint64_t t) noexcept {
  if (out_.request_active) out_.abort = why != MixingEndReason::kConfirmed;
  out_.request_active = false;
  out_.reason = why;
  out_.state = next;
  state_since_ = t;
  switch (why) {
    case MixingEndReason::kConfirmed:
      ++counters_.confirmed;
      failed_in_row_ = 0;
      break;
    case MixingEndReason::kSeismic: ++counters_.aborted_seismic; break;
    case MixingEndReason::kSensorFault:
    case MixingEndReason::kStartTimeout:
    case MixingEndReason::kIncomplete:
      ++counters_.failed;
      ++failed_in_row_;
      break;
    default: break;
  }
}

template <class Policy>
bool BasicMixingScheduler<Policy>::transition(const Input& in, std::uint64_t t) noexcept {
  Conditions c;
  c.below = in.forecast_capacity_fraction < threshold_;
  c.quiet = !out_.shaking && (!shaking_ever_ || t - last_shaking_ >= holdoff_);
  c.can_watch = in.ground_accel_valid || in.base_accel_valid;
  c.measured = A::vol_sub0(in.measured_volume_m3, volume_at_request_);
  c.in_state = t > state_since_ ? t - state_since_ : 0;
  const SchedulerState before = out_.state;

  switch (out_.state) {
    case SchedulerState::kIdle:
      if (c.below && c.quiet) enter(SchedulerState::kDue, t);
      break;
    case SchedulerState::kDue: from_due(in, c, t); break;
    case SchedulerState::kRequested: from_requested(in, c, t); break;
    case SchedulerState::kRunning: from_running(c, t); break;
    case SchedulerState::kConfirmed:
      if (c.in_state >= confirm_hold_) enter(SchedulerState::kIdle, t);
      break;
    case SchedulerState::kAborted:
      if (failed_in_row_ >= c_.max_attempts) {
        raise_maintenance(MixingEndReason::kAttemptsExhausted, t);
      } else if (c.quiet && c.in_state >= holdoff_) {
        enter(SchedulerState::kIdle, t);
      }
      break;
    case SchedulerState::kMaintenanceRequired:
      if (!c.below) {
        enter(SchedulerState::kIdle, t);
        failed_in_row_ = 0;
      }
      break;
  }
  return out_.state != before;
}

template <class Policy>
void BasicMixingScheduler<Policy>::enter(SchedulerState next, std::uint64_t t) noexcept {
  out_.state = next;
  state_since_ = t;
}

template <class Policy>
void BasicMixingScheduler<Policy>::raise_maintenance(MixingEndReason why, std::uint64_t t) noexcept {
  out_.reason = why;
  ++counters_.maintenance_raised;
  enter(SchedulerState::kMaintenanceRequired, t);
}

template <class Policy>
void BasicMixingScheduler<Policy>::from_due(const Input& in, const Conditions& c, std::uint64_t t) noexcept {
  if (!c.below) {
    enter(SchedulerState::kIdle, t);
  } else if (!c_.actuator_fitted) {
    raise_maintenance(MixingEndReason::kNoActuator, t);
  } else if (!in.actuator_ready) {
    if (c.in_state > start_timeout_) end_cycle(SchedulerState::kAborted, MixingEndReason::kStartTimeout, t);
  } else if (!out_.shaking && c.can_watch) {
    out_.plan = plan_for(in.volume_needed_m3);
    out_.request_active = true;
    out_.reason = MixingEndReason::kNone;
    ++out_.request_id;
    ++counters_.requested;
    volume_at_request_ = in.measured_volume_m3;
    start_volume_ = A::vol_scale(out_.plan.volume_m3, start_fraction_);
    confirm_volume_ = A::vol_scale(out_.plan.volume_m3, confirm_fraction_);
    run_limit_ = ((run_limit_q16_ * out_.plan.cycles) >> 16) + run_margin_;
    enter(SchedulerState::kRequested, t);
  }
}

template <class Policy>
void BasicMixingScheduler<Policy>::from_requested(const Input& in, const Conditions& c, std::uint64_t t) noexcept {
  if (out_.shaking) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kSeismic, t);
  } else if (!c.can_watch) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kSensorFault, t);
  } else if (in.actuator_busy || !(c.measured < start_volume_)) {
    enter(SchedulerState::kRunning, t);
  } else if (c.in_state > start_timeout_) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kStartTimeout, t);
  }
}

template <class Policy>
void BasicMixingScheduler<Policy>::from_running(const Conditions& c, std::uint64_t t) noexcept {
  if (out_.shaking) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kSeismic, t);
  } else if (!c.can_watch) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kSensorFault, t);
  } else if (!(c.measured < confirm_volume_)) {
    end_cycle(SchedulerState::kConfirmed, MixingEndReason::kConfirmed, t);
  } else if (c.in_state > run_limit_) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kIncomplete, t);
  }
}

template <class Policy>
const typename BasicMixingScheduler<Policy>::Output& BasicMixingScheduler<Policy>::step(const Input& in) noexcept {
  const std::uint64_t t = in.tick;
  out_.abort = false;

  // Seismic trigger: consecutive valid samples above the threshold.
  const bool mixing = out_.state == SchedulerState::kRequested || out_.state == SchedulerState::kRunning;
  const Accel base_trigger = mixing && c_.mixing_moves_base ? base_trigger_ + plan_peak_accel_ : base_trigger_;
  ground_count_ = in.ground_accel_valid && ground_trigger_ < A::abs(A::accel_of(in.ground_accel_m_s2))
                      ? ground_count_ + (ground_count_ < c_.seismic_samples ? 1u : 0u)
                      : 0u;
  base_count_ = in.base_accel_valid && base_trigger < A::abs(A::accel_of(in.base_accel_m_s2))
                    ? base_count_ + (base_count_ < c_.seismic_samples ? 1u : 0u)
                    : 0u;
  out_.shaking = ground_count_ >= c_.seismic_samples || base_count_ >= c_.seismic_samples;
  if (out_.shaking) {
    shaking_ever_ = true;
    last_shaking_ = t;
  }

  // Several transitions may follow each other within one tick (idle → due →
  // requested); seven is more than any chain needs.
  for (int k = 0; k < 7 && transition(in, t); ++k) {
  }
  out_.maintenance_required = out_.state == SchedulerState::kMaintenanceRequired;
  return out_;
}

}  // namespace mrd::fw
