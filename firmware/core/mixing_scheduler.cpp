#include "firmware/core/mixing_scheduler.hpp"

#include <cmath>

#include "mrd/units.hpp"

namespace mrd::fw {

MixingPlan plan_mixing(const MixingSchedulerConfig& c, double volume_needed_m3) noexcept {
  MixingPlan p;
  p.amplitude_m = c.max_amplitude_m;
  const double omega_limit = c.max_velocity_m_s / p.amplitude_m;  // rad/s at the velocity limit
  const double f_limit_hz = omega_limit / (2.0 * units::kPi);
  p.frequency_hz = c.preferred_frequency_hz < f_limit_hz ? c.preferred_frequency_hz : f_limit_hz;
  const double per_cycle_m3 = 4.0 * p.amplitude_m * c.flow_area_m2;  // ∫|ẋ|dt over one period is 4A
  double n = volume_needed_m3 > 0.0 ? std::ceil(volume_needed_m3 / per_cycle_m3) : 0.0;
  if (n < static_cast<double>(c.min_cycles)) n = static_cast<double>(c.min_cycles);
  if (n > static_cast<double>(c.max_cycles)) n = static_cast<double>(c.max_cycles);
  p.cycles = static_cast<std::uint32_t>(n);
  p.volume_m3 = static_cast<double>(p.cycles) * per_cycle_m3;
  p.duration_s = static_cast<double>(p.cycles) / p.frequency_hz;
  const double omega = 2.0 * units::kPi * p.frequency_hz;
  p.peak_velocity_m_s = omega * p.amplitude_m;
  p.peak_accel_m_s2 = omega * omega * p.amplitude_m;
  return p;
}

bool MixingScheduler::init(const MixingSchedulerConfig& config) noexcept {
  c_ = config;
  reset();
  return c_.period_s > 0.0 && c_.capacity_threshold > 0.0 && c_.capacity_threshold < 1.0 && c_.lead_time_s >= 0.0 &&
         c_.maintenance_lead_time_s >= 0.0 && c_.max_amplitude_m > 0.0 && c_.max_velocity_m_s > 0.0 &&
         c_.preferred_frequency_hz > 0.0 && c_.flow_area_m2 > 0.0 && c_.ceiling_gap_fraction > 0.0 &&
         c_.min_cycles >= 1 && c_.min_cycles <= c_.max_cycles && c_.ground_trigger_m_s2 > 0.0 &&
         c_.base_trigger_m_s2 > 0.0 && c_.seismic_samples >= 1 && c_.start_fraction > 0.0 &&
         c_.confirm_fraction > 0.0 && c_.confirm_fraction <= 1.0 && c_.start_timeout_s > 0.0 &&
         c_.run_timeout_factor >= 1.0 && c_.run_margin_s >= 0.0 && c_.confirm_hold_s >= 0.0 &&
         c_.holdoff_s >= 0.0 && c_.max_attempts >= 1;
}

void MixingScheduler::reset() noexcept {
  out_ = MixingSchedulerOutput{};
  counters_ = MixingCounters{};
  ground_count_ = 0;
  base_count_ = 0;
  shaking_ever_ = false;
  last_shaking_s_ = 0.0;
  state_since_s_ = 0.0;
  volume_at_request_m3_ = 0.0;
  failed_in_row_ = 0;
}

void MixingScheduler::end_cycle(SchedulerState next, MixingEndReason why, double t_s) noexcept {
  if (out_.request_active) out_.abort = why != MixingEndReason::kConfirmed;
  out_.request_active = false;
  out_.reason = why;
  out_.state = next;
  state_since_s_ = t_s;
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

bool MixingScheduler::transition(const MixingSchedulerInput& in, double t_s) noexcept {
  Conditions c;
  c.below = in.forecast_capacity_fraction < c_.capacity_threshold;
  c.quiet = !out_.shaking && (!shaking_ever_ || t_s - last_shaking_s_ >= c_.holdoff_s);
  c.can_watch = in.ground_accel_valid || in.base_accel_valid;
  c.measured_m3 = in.measured_volume_m3 - volume_at_request_m3_;
  c.in_state_s = t_s - state_since_s_;
  const SchedulerState before = out_.state;

  switch (out_.state) {
    case SchedulerState::kIdle:
      if (c.below && c.quiet) enter(SchedulerState::kDue, t_s);
      break;
    case SchedulerState::kDue: from_due(in, c, t_s); break;
    case SchedulerState::kRequested: from_requested(in, c, t_s); break;
    case SchedulerState::kRunning: from_running(c, t_s); break;
    case SchedulerState::kConfirmed:
      if (c.in_state_s >= c_.confirm_hold_s) enter(SchedulerState::kIdle, t_s);
      break;
    case SchedulerState::kAborted:
      if (failed_in_row_ >= c_.max_attempts) {
        raise_maintenance(MixingEndReason::kAttemptsExhausted, t_s);
      } else if (c.quiet && c.in_state_s >= c_.holdoff_s) {
        enter(SchedulerState::kIdle, t_s);
      }
      break;
    case SchedulerState::kMaintenanceRequired:
      if (!c.below) {
        enter(SchedulerState::kIdle, t_s);
        failed_in_row_ = 0;
      }
      break;
  }
  return out_.state != before;
}

void MixingScheduler::enter(SchedulerState next, double t_s) noexcept {
  out_.state = next;
  state_since_s_ = t_s;
}

void MixingScheduler::raise_maintenance(MixingEndReason why, double t_s) noexcept {
  out_.reason = why;
  ++counters_.maintenance_raised;
  enter(SchedulerState::kMaintenanceRequired, t_s);
}

void MixingScheduler::from_due(const MixingSchedulerInput& in, const Conditions& c, double t_s) noexcept {
  if (!c.below) {
    enter(SchedulerState::kIdle, t_s);
  } else if (!c_.actuator_fitted) {
    raise_maintenance(MixingEndReason::kNoActuator, t_s);
  } else if (!in.actuator_ready) {
    if (c.in_state_s > c_.start_timeout_s) end_cycle(SchedulerState::kAborted, MixingEndReason::kStartTimeout, t_s);
  } else if (!out_.shaking && c.can_watch) {
    out_.plan = plan_mixing(c_, in.volume_needed_m3);
    out_.request_active = true;
    out_.reason = MixingEndReason::kNone;
    ++out_.request_id;
    ++counters_.requested;
    volume_at_request_m3_ = in.measured_volume_m3;
    enter(SchedulerState::kRequested, t_s);
  }
}

void MixingScheduler::from_requested(const MixingSchedulerInput& in, const Conditions& c, double t_s) noexcept {
  if (out_.shaking) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kSeismic, t_s);
  } else if (!c.can_watch) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kSensorFault, t_s);
  } else if (in.actuator_busy || c.measured_m3 >= c_.start_fraction * out_.plan.volume_m3) {
    enter(SchedulerState::kRunning, t_s);
  } else if (c.in_state_s > c_.start_timeout_s) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kStartTimeout, t_s);
  }
}

void MixingScheduler::from_running(const Conditions& c, double t_s) noexcept {
  if (out_.shaking) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kSeismic, t_s);
  } else if (!c.can_watch) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kSensorFault, t_s);
  } else if (c.measured_m3 >= c_.confirm_fraction * out_.plan.volume_m3) {
    end_cycle(SchedulerState::kConfirmed, MixingEndReason::kConfirmed, t_s);
  } else if (c.in_state_s > out_.plan.duration_s * c_.run_timeout_factor + c_.run_margin_s) {
    end_cycle(SchedulerState::kAborted, MixingEndReason::kIncomplete, t_s);
  }
}

const MixingSchedulerOutput& MixingScheduler::step(const MixingSchedulerInput& in) noexcept {
  const double t_s = static_cast<double>(in.tick) * c_.period_s;
  out_.abort = false;

  // Seismic trigger: consecutive valid samples above the threshold.
  const bool mixing = out_.state == SchedulerState::kRequested || out_.state == SchedulerState::kRunning;
  const double base_trigger =
      c_.base_trigger_m_s2 + (mixing && c_.mixing_moves_base ? out_.plan.peak_accel_m_s2 : 0.0);
  ground_count_ = in.ground_accel_valid && std::fabs(in.ground_accel_m_s2) > c_.ground_trigger_m_s2
                      ? ground_count_ + (ground_count_ < c_.seismic_samples ? 1u : 0u)
                      : 0u;
  base_count_ = in.base_accel_valid && std::fabs(in.base_accel_m_s2) > base_trigger
                    ? base_count_ + (base_count_ < c_.seismic_samples ? 1u : 0u)
                    : 0u;
  out_.shaking = ground_count_ >= c_.seismic_samples || base_count_ >= c_.seismic_samples;
  if (out_.shaking) {
    shaking_ever_ = true;
    last_shaking_s_ = t_s;
  }

  // Several transitions may follow each other within one tick (idle → due →
  // requested); seven is more than any chain needs.
  for (int k = 0; k < 7 && transition(in, t_s); ++k) {
  }
  out_.maintenance_required = out_.state == SchedulerState::kMaintenanceRequired;
  return out_;
}

}  // namespace mrd::fw
