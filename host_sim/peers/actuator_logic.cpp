#include "host_sim/peers/actuator_logic.hpp"

#include <cmath>

#include "mrd/units.hpp"

namespace mrd::peers {

bool ActuatorLogic::on_frame(const hal::CanFrame& f, std::int64_t now_ns) noexcept {
  if (f.extended || f.id != protocol::can_id(protocol::MsgId::kMixingCommand, c_.nodes.controller)) return false;
  protocol::MixingCommand m;
  if (protocol::decode(f, c_.nodes.controller, m) != protocol::DecodeError::kOk ||
      !protocol::counter_ok(counter_.check(m.counter))) {
    ++rejected_;
    return false;
  }
  last_cmd_ns_ = now_ns;
  have_cmd_ = true;
  if (m.action == protocol::MixingAction::kStop) {
    if (state_ == protocol::MixingState::kRunning) state_ = protocol::MixingState::kAborted;
    cmd_ = m;
    return true;
  }
  const bool same = state_ == protocol::MixingState::kRunning && m.amplitude_m == cmd_.amplitude_m &&
                    m.frequency_hz == cmd_.frequency_hz && m.duration_s == cmd_.duration_s;
  cmd_ = m;
  if (same) return true;  // the periodic repeat of the running request
  faults_ = 0;
  if (m.amplitude_m > c_.stroke_limit_m) faults_ |= protocol::mixing_fault::kStrokeLimit;
  if (2.0 * units::kPi * m.frequency_hz * m.amplitude_m > c_.velocity_limit_m_s)
    faults_ |= protocol::mixing_fault::kVelocityLimit;
  if (faults_ != 0) {
    state_ = protocol::MixingState::kFault;
    return true;
  }
  state_ = protocol::MixingState::kRunning;
  start_ns_ = now_ns;
  return true;
}

protocol::MixingStatus ActuatorLogic::tick(std::int64_t now_ns) noexcept {
  now_ns_ = now_ns;
  if (state_ == protocol::MixingState::kRunning) {
    if (now_ns - last_cmd_ns_ > c_.command_timeout_ns) {
      state_ = protocol::MixingState::kAborted;
      faults_ |= protocol::mixing_fault::kCommandTimeout;
    } else if (static_cast<double>(now_ns - start_ns_) * 1e-9 >= static_cast<double>(cmd_.duration_s)) {
      state_ = protocol::MixingState::kDone;
    }
  }
  protocol::MixingStatus s;
  s.state = state_;
  const double elapsed_s =
      state_ == protocol::MixingState::kIdle ? 0.0 : static_cast<double>(now_ns - start_ns_) * 1e-9;
  s.elapsed_s = static_cast<float>(std::floor(std::fmin(elapsed_s, 65535.0)));
  s.amplitude_m = state_ == protocol::MixingState::kRunning ? cmd_.amplitude_m : 0.0f;
  s.faults = faults_;
  return s;
}

double ActuatorLogic::position_m(std::int64_t now_ns) const noexcept {
  if (state_ != protocol::MixingState::kRunning) return 0.0;
  const double t = static_cast<double>(now_ns - start_ns_) * 1e-9;
  return static_cast<double>(cmd_.amplitude_m) * std::sin(2.0 * units::kPi * cmd_.frequency_hz * t);
}

}  // namespace mrd::peers
