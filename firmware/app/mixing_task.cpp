#include "firmware/app/mixing_task.hpp"

namespace mrd::app {

bool MixingTask::init(const MixingTaskConfig& config) noexcept {
  fw::MixingSchedulerConfig sc = config.scheduler;
  sc.period_s = config.estimator.period_s;
  sc.flow_area_m2 = config.estimator.model.pr.flow_area_m2;
  const bool estimator_ok = estimator_.init(config.estimator);
  const bool scheduler_ok = scheduler_.init(sc);
  confirmed_id_ = 0;
  return estimator_ok && scheduler_ok;
}

fw::IdleBootReport MixingTask::boot(hal::StateStore& store, std::uint64_t tick, double rtc_s,
                                    bool rtc_valid) noexcept {
  return estimator_.boot(store, tick, rtc_s, rtc_valid);
}

void MixingTask::boot_with(double equivalent_idle_s, std::uint64_t tick, double rtc_s) noexcept {
  estimator_.boot_with(equivalent_idle_s, tick, rtc_s);
}

const fw::MixingSchedulerOutput& MixingTask::step(const MixingTaskInput& in) noexcept {
  fw::IdleEstimatorInput ei;
  ei.tick = in.tick;
  ei.rtc_s = in.rtc_s;
  ei.rtc_valid = in.rtc_valid;
  ei.damper_disp_m = in.damper_disp_m;
  ei.disp_valid = in.disp_valid;
  ei.mixing_active = in.actuator_busy;
  estimator_.step(ei);

  const fw::MixingSchedulerConfig& sc = scheduler_.config();
  fw::MixingSchedulerInput si;
  si.tick = in.tick;
  si.ground_accel_m_s2 = in.ground_accel_m_s2;
  si.ground_accel_valid = in.ground_accel_valid;
  si.base_accel_m_s2 = in.base_accel_m_s2;
  si.base_accel_valid = in.base_accel_valid;
  si.actuator_ready = in.actuator_ready;
  si.actuator_busy = in.actuator_busy;
  si.forecast_capacity_fraction = estimator_.predicted_capacity_fraction(scheduler_.forecast_horizon_s());
  si.volume_needed_m3 = estimator_.volume_to_ceiling_m3(sc.ceiling_gap_fraction);
  si.measured_volume_m3 = estimator_.estimate().lifetime_volume_m3;
  const fw::MixingSchedulerOutput& out = scheduler_.step(si);
  if (out.state == fw::SchedulerState::kConfirmed && out.request_id != confirmed_id_) {
    confirmed_id_ = out.request_id;
    estimator_.note_mixing_confirmed();
  }
  return out;
}

}  // namespace mrd::app
