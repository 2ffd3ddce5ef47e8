#pragma once
/// Definitions of BasicMixingTask (mixing_task.hpp), included only by the
/// three files that instantiate it.

#include "firmware/app/mixing_task.hpp"

namespace mrd::app {

template <class Policy>
bool BasicMixingTask<Policy>::init(const MixingTaskConfig& config) noexcept {
  fw::MixingSchedulerConfig sc = config.scheduler;
  sc.period_s = config.estimator.period_s;
  sc.flow_area_m2 = config.estimator.model.pr.flow_area_m2;
  const bool estimator_ok = estimator_.init(config.estimator);
  const bool scheduler_ok = scheduler_.init(sc);
  confirmed_id_ = 0;
  return estimator_ok && scheduler_ok;
}

template <class Policy>
const typename BasicMixingTask<Policy>::Output& BasicMixingTask<Policy>::step(const Input& in) noexcept {
  typename Estimator::Input ei;
  static_cast<typename fw::IdleArith<Policy>::RtcInput&>(ei) = in;  // the wall-clock field
  ei.tick = in.tick;
  ei.rtc_valid = in.rtc_valid;
  ei.damper_disp_m = in.damper_disp_m;
  ei.disp_valid = in.disp_valid;
  ei.mixing_active = in.actuator_busy;
  estimator_.step(ei);

  typename Scheduler::Input si;
  si.tick = in.tick;
  si.ground_accel_m_s2 = in.ground_accel_m_s2;
  si.ground_accel_valid = in.ground_accel_valid;
  si.base_accel_m_s2 = in.base_accel_m_s2;
  si.base_accel_valid = in.base_accel_valid;
  si.actuator_ready = in.actuator_ready;
  si.actuator_busy = in.actuator_busy;
  si.forecast_capacity_fraction = estimator_.predicted_capacity(scheduler_.forecast_horizon_ticks());
  si.volume_needed_m3 = estimator_.volume_to_ceiling(scheduler_.ceiling_gap());
  si.measured_volume_m3 = estimator_.lifetime_volume();
  const Output& out = scheduler_.step(si);
  if (out.state == fw::SchedulerState::kConfirmed && out.request_id != confirmed_id_) {
    confirmed_id_ = out.request_id;
    estimator_.note_mixing_confirmed();
  }
  return out;
}

}  // namespace mrd::app
