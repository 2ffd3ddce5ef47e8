#pragma once
/// The mixing task on the control task: its sample comes from the control
/// tick that just ran, its request goes out as a MixingCommand and its
/// maintenance output drives the maintenance-due line.

#include <cstdint>

#include "firmware/app/control_task.hpp"
#include "firmware/app/mixing_task.hpp"
#include "firmware/core/mixing_scheduler.hpp"
#include "mrd/protocol/messages.hpp"

namespace mrd::app {

/// The mixing task's sample from the control tick that just ran: that tick,
/// the stroke and accelerations the core was given (with their validity),
/// and the actuator as its MixingStatus reports it (fw::apply_mixing_status).
MixingTaskInput mixing_input(const ControlTaskStatus& status, double rtc_s, bool rtc_valid) noexcept;

/// Watches the scheduler's request: a command is due when a request starts,
/// another one replaces it, or it is withdrawn.
class MixingRequestEdge {
 public:
  /// True, with `cmd` filled (fw::to_mixing_command), when `out`'s request
  /// differs from the last one seen.
  bool changed(const fw::MixingSchedulerOutput& out, protocol::MixingCommand& cmd) noexcept;

 private:
  bool active_ = false;
  std::uint32_t id_ = 0;
};

}  // namespace mrd::app
