#include "firmware/app/mixing_link.hpp"

#include "firmware/core/mixing_scheduler_can.hpp"

namespace mrd::app {

MixingTaskInput mixing_input(const ControlTaskStatus& status, double rtc_s, bool rtc_valid) noexcept {
  const control::ControllerInput& s = status.last_input;
  MixingTaskInput in;
  in.tick = status.ticks > 0 ? status.ticks - 1 : 0;
  in.rtc_s = rtc_s;
  in.rtc_valid = rtc_valid;
  in.damper_disp_m = static_cast<double>(s.damper_disp_m);
  in.disp_valid = s.flags.disp_valid;
  in.ground_accel_m_s2 = static_cast<double>(s.ground_accel_m_s2);
  in.ground_accel_valid = s.flags.ground_accel_valid;
  in.base_accel_m_s2 = static_cast<double>(s.base_accel_m_s2);
  in.base_accel_valid = s.flags.base_accel_valid;
  fw::MixingSchedulerInput actuator;
  fw::apply_mixing_status(status.last_mixing, status.actuator_present, actuator);
  in.actuator_ready = actuator.actuator_ready;
  in.actuator_busy = actuator.actuator_busy;
  return in;
}

bool MixingRequestEdge::changed(const fw::MixingSchedulerOutput& out, protocol::MixingCommand& cmd) noexcept {
  if (out.request_active == active_ && out.request_id == id_) return false;
  active_ = out.request_active;
  id_ = out.request_id;
  (void)fw::to_mixing_command(out, cmd);  // a plan the frame cannot carry goes out as a stop
  return true;
}

}  // namespace mrd::app
