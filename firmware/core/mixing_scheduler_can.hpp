#pragma once
/// The mixing scheduler on the CAN bus (common/protocol/CAN_PROTOCOL.md):
/// its request as a MixingCommand, and the actuator's MixingStatus as the
/// scheduler's actuator inputs. Header-only, no heap, no exceptions.
///
/// The command carries amplitude in 0.01 mm, frequency in 0.01 Hz and
/// duration in whole seconds. Amplitude and frequency are rounded *down* to
/// those steps, so the stroke and the peak velocity 2πfA never exceed the
/// plan's (which are within the actuator's limits); the duration is rounded
/// up, so the actuator runs at least the planned number of cycles.

#include <cmath>

#include "firmware/core/mixing_scheduler.hpp"
#include "mrd/protocol/messages.hpp"

namespace mrd::fw {

inline constexpr double kCanAmplitudeStep_m = 1.0e-5;  ///< MixingCommand resolution, 0.01 mm
inline constexpr double kCanFrequencyStep_hz = 0.01;   ///< 0.01 Hz
inline constexpr double kCanDurationStep_s = 1.0;      ///< 1 s

/// Fills `cmd` from the scheduler's output: start with the plan while a
/// request is active, stop otherwise (the scheduler withdrew the request,
/// e.g. on shaking). Returns false, with a stop command, when the plan
/// cannot be represented (frequency below 0.01 Hz). Any numeric build: the
/// plan's numbers are read as double.
template <class Policy>
bool to_mixing_command(const BasicMixingSchedulerOutput<Policy>& o, protocol::MixingCommand& cmd) noexcept {
  cmd.action = protocol::MixingAction::kStop;
  cmd.amplitude_m = 0.0f;
  cmd.frequency_hz = 0.0f;
  cmd.duration_s = 0.0f;
  if (!o.request_active) return true;
  // The small offset keeps values already on the grid (0.2 Hz = 20 steps)
  // from falling one step by their binary rounding.
  const double amp_m =
      std::floor(static_cast<double>(o.plan.amplitude_m) / kCanAmplitudeStep_m + 1e-6) * kCanAmplitudeStep_m;
  const double f_hz =
      std::floor(static_cast<double>(o.plan.frequency_hz) / kCanFrequencyStep_hz + 1e-6) * kCanFrequencyStep_hz;
  if (!(f_hz > 0.0) || !(amp_m > 0.0)) return false;
  const double duration_s =
      std::ceil(static_cast<double>(o.plan.cycles) / f_hz / kCanDurationStep_s - 1e-6) * kCanDurationStep_s;
  cmd.action = protocol::MixingAction::kStart;
  cmd.amplitude_m = static_cast<float>(amp_m);
  cmd.frequency_hz = static_cast<float>(f_hz);
  cmd.duration_s = static_cast<float>(duration_s);
  return true;
}

/// The actuator as the scheduler sees it: ready when its status arrived
/// within the protocol's timeout (`heard`) and reports no fault; busy while
/// it reports running.
inline void apply_mixing_status(const protocol::MixingStatus& s, bool heard, MixingSchedulerInput& in) noexcept {
  in.actuator_ready = heard && s.state != protocol::MixingState::kFault && s.faults == 0;
  in.actuator_busy = heard && s.state == protocol::MixingState::kRunning;
}

}  // namespace mrd::fw
