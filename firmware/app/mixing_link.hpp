#pragma once
/// The mixing task on the control task: its sample comes from the control
/// tick that just ran, its request goes out as a MixingCommand, its
/// maintenance output drives the maintenance-due line, and its estimate goes
/// out as the IdleStatus frame. Any numeric build of the task.

#include <cmath>
#include <cstdint>

#include "firmware/app/control_task.hpp"
#include "firmware/app/mixing_task.hpp"
#include "firmware/core/mixing_scheduler.hpp"
#include "firmware/core/mixing_scheduler_can.hpp"
#include "mrd/protocol/messages.hpp"

namespace mrd::app {

/// The mixing task's sample from the control tick that just ran: that tick,
/// the stroke and accelerations the core was given (with their validity),
/// and the actuator as its MixingStatus reports it (fw::apply_mixing_status).
/// The wall clock goes in as seconds (reference build) or milliseconds.
template <class Policy>
BasicMixingTaskInput<Policy> mixing_input(const ControlTaskStatus& status, double rtc_s, bool rtc_valid) noexcept {
  using Sample = typename BasicMixingTaskInput<Policy>::Sample;
  const control::ControllerInput& s = status.last_input;
  BasicMixingTaskInput<Policy> in;
  in.tick = status.ticks > 0 ? status.ticks - 1 : 0;
  if constexpr (requires { in.rtc_s; }) {
    in.rtc_s = rtc_s;
  } else {
    in.rtc_ms = std::llround(rtc_s * 1e3);
  }
  in.rtc_valid = rtc_valid;
  in.damper_disp_m = static_cast<Sample>(s.damper_disp_m);
  in.disp_valid = s.flags.disp_valid;
  in.ground_accel_m_s2 = static_cast<Sample>(s.ground_accel_m_s2);
  in.ground_accel_valid = s.flags.ground_accel_valid;
  in.base_accel_m_s2 = static_cast<Sample>(s.base_accel_m_s2);
  in.base_accel_valid = s.flags.base_accel_valid;
  fw::MixingSchedulerInput actuator;
  fw::apply_mixing_status(status.last_mixing, status.actuator_present, actuator);
  in.actuator_ready = actuator.actuator_ready;
  in.actuator_busy = actuator.actuator_busy;
  return in;
}

/// The reference build's sample (the simulator and the tests).
inline MixingTaskInput mixing_input(const ControlTaskStatus& status, double rtc_s, bool rtc_valid) noexcept {
  return mixing_input<fw::Float64Policy>(status, rtc_s, rtc_valid);
}

/// Watches the scheduler's request: a command is due when a request starts,
/// another one replaces it, or it is withdrawn.
class MixingRequestEdge {
 public:
  /// True, with `cmd` filled (fw::to_mixing_command), when `out`'s request
  /// differs from the last one seen. A plan the frame cannot carry goes out
  /// as a stop.
  template <class Policy>
  bool changed(const fw::BasicMixingSchedulerOutput<Policy>& out, protocol::MixingCommand& cmd) noexcept {
    if (out.request_active == active_ && out.request_id == id_) return false;
    active_ = out.request_active;
    id_ = out.request_id;
    (void)fw::to_mixing_command(out, cmd);
    return true;
  }

 private:
  bool active_ = false;
  std::uint32_t id_ = 0;
};

/// IdleStatus.flags from the estimator's IdleFlag bits.
constexpr std::uint8_t idle_status_flags(std::uint32_t idle_flags) noexcept {
  std::uint8_t f = 0;
  if (idle_flags & fw::kIdleAssumedSettled) f |= protocol::idle_flag::kAssumedSettled;
  if (idle_flags & (fw::kIdleClockInvalid | fw::kIdleClockBackwards)) f |= protocol::idle_flag::kClockInvalid;
  if (idle_flags & fw::kIdleSaveFailed) f |= protocol::idle_flag::kSaveFailed;
  return f;
}

/// The IdleStatus frame's content from the task's estimate and scheduler
/// state (the counter is the control task's). Hours round to nearest and
/// saturate at the frame's 24 bits; fractions are clamped to [0, 1].
template <class Policy>
protocol::IdleStatus idle_status_of(const BasicMixingTask<Policy>& task) noexcept {
  const auto& e = task.estimator().estimate();
  protocol::IdleStatus s;
  const double hours = static_cast<double>(e.equivalent_idle_s) / 3600.0;
  s.equivalent_idle_h = !(hours >= 0.0) ? 0u : hours >= 16777215.0 ? 16777215u : static_cast<std::uint32_t>(std::lround(hours));
  auto unit = [](double x) { return static_cast<float>(x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x); };
  s.participant_ratio = unit(static_cast<double>(e.participant_ratio));
  s.capacity_fraction = unit(static_cast<double>(e.capacity_fraction));
  s.scheduler = static_cast<std::uint8_t>(task.output().state);
  s.flags = idle_status_flags(e.flags);
  return s;
}

static_assert(static_cast<std::uint8_t>(fw::SchedulerState::kMaintenanceRequired) ==
                  protocol::scheduler_state::kMaintenanceRequired &&
              static_cast<std::uint8_t>(fw::SchedulerState::kRequested) == protocol::scheduler_state::kRequested,
              "IdleStatus carries fw::SchedulerState's values");

}  // namespace mrd::app
