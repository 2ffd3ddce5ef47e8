#include "host_sim/peers/drive_logic.hpp"

#include <cmath>

namespace mrd::peers {

bool DriveLogic::on_frame(const hal::CanFrame& f, std::int64_t now_ns) noexcept {
  using protocol::MsgId;
  if (f.extended || protocol::msg_of(f.id) != static_cast<std::uint8_t>(MsgId::kCurrentCommand)) return false;
  if (protocol::node_of(f.id) != c_.nodes.controller) {
    ++n_.foreign;
    return false;
  }
  protocol::CurrentCommand cmd;
  if (protocol::decode(f, c_.nodes.controller, cmd) != protocol::DecodeError::kOk) {
    ++n_.rejected;
    rejected_since_status_ = true;
    return false;
  }
  switch (counter_.check(cmd.counter)) {
    case protocol::CounterVerdict::kRepeated:
      ++n_.repeated;
      rejected_since_status_ = true;
      return false;
    case protocol::CounterVerdict::kStale:
      ++n_.stale;
      rejected_since_status_ = true;
      return false;
    default: break;
  }
  cmd_ = cmd;
  have_command_ = true;
  last_valid_ns_ = now_ns;
  ++n_.accepted;
  return true;
}

DriveOutput DriveLogic::tick(std::int64_t now_ns, bool fault, float measured_current_a) noexcept {
  DriveOutput o;
  const bool timed_out = !have_command_ || now_ns - last_valid_ns_ > c_.command_timeout_ns;
  if (std::fabs(measured_current_a) > c_.peak_limit_a) o.faults |= protocol::drive_fault::kOverCurrent;
  if (fault) o.faults |= protocol::drive_fault::kFaultLine;
  if (o.faults != 0) {
    o.state = protocol::DriveState::kFault;
  } else if (timed_out) {
    o.state = protocol::DriveState::kSafe;
    o.applied_current_a = c_.safe_current_a;
    o.output_on = true;
    o.faults |= protocol::drive_fault::kCommandTimeout;
    if (out_.state != protocol::DriveState::kSafe) {
      ++n_.fallbacks;
      n_.last_fallback_latency_ns = have_command_ ? now_ns - last_valid_ns_ : -1;
      n_.last_fallback_tick_gap_ns = last_tick_ns_ >= 0 ? now_ns - last_tick_ns_ : -1;
    }
    counter_.desync();  // the controller's next command starts a new sequence
  } else if (!cmd_.enable) {
    o.state = protocol::DriveState::kDisabled;
  } else {
    o.state = protocol::DriveState::kFollowing;
    o.applied_current_a = cmd_.current_a;
    o.output_on = true;
  }
  if (rejected_since_status_) o.faults |= protocol::drive_fault::kCommandRejected;
  out_ = o;
  last_tick_ns_ = now_ns;
  return o;
}

protocol::DriveStatus DriveLogic::status(float measured_current_a, std::uint8_t counter) const noexcept {
  protocol::DriveStatus s;
  s.measured_current_a = std::fabs(measured_current_a) <= 30.0f ? measured_current_a : std::copysign(30.0f, measured_current_a);
  s.setpoint_a = out_.applied_current_a;
  s.faults = out_.faults;
  s.state = out_.state;
  s.counter = counter;
  return s;
}

DriveConfig drive_config(const app::BoardConfig& board) noexcept {
  DriveConfig c;
  c.nodes = board.nodes;
  c.safe_current_a = static_cast<float>(board.controller.nominal_current_a);
  c.peak_limit_a = static_cast<float>(board.drive ? board.drive->peak_current_a : board.controller.drive_peak_limit_a);
  return c;
}

}  // namespace mrd::peers
