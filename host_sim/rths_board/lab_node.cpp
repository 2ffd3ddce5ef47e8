#include "host_sim/rths_board/lab_node.hpp"

#include <stdexcept>

namespace mrd::rths_board {
namespace {

LabStopReason reason_of(rths::LabStop s) noexcept {
  switch (s) {
    case rths::LabStop::kNone: return LabStopReason::kNone;
    case rths::LabStop::kForceLimit: return LabStopReason::kForceLimit;
    case rths::LabStop::kTrackingLimit: return LabStopReason::kTrackingLimit;
    case rths::LabStop::kNotFinite: return LabStopReason::kNotFinite;
  }
  return LabStopReason::kNotFinite;
}

hal::CanFdBus* lab_fd_bus(hal::CanBus& bus, bool can_fd) {
  if (!can_fd) return nullptr;
  auto* fd = dynamic_cast<hal::CanFdBus*>(&bus);
  if (fd == nullptr || !fd->fd_enabled())
    throw std::invalid_argument("laboratory: CAN FD asked for, but the bus does not carry CAN FD frames");
  return fd;
}

double checked_dt(double rate_hz) {
  if (!(rate_hz >= 100.0 && rate_hz <= 65535.0))
    throw std::invalid_argument("laboratory rate outside 100..65535 Hz");
  return 1.0 / rate_hz;
}

}  // namespace

LabNode::LabNode(hal::CanBus& bus, const LabNodeConfig& config)
    : bus_(bus),
      fd_bus_(lab_fd_bus(bus, config.can_fd)),
      config_(config),
      lab_(config.plant, config.spec, checked_dt(config.rate_hz)) {
  now_ = lab_.measure();
}

void LabNode::send(const hal::CanFrame& f) noexcept {
  if (bus_.send(f) != hal::CanResult::kOk) ++tx_errors_;
}

void LabNode::send_measurement() noexcept {
  if (fd_bus_ != nullptr) {
    RthsFdMeasurement m;
    m.displacement_m = now_.displacement_m;
    m.force_n = now_.force_n;
    m.counter = static_cast<std::uint16_t>(steps_ & 0xFFFF);
    hal::CanFdFrame f;
    if (!encode_fd(m, config_.lab_node, f) || fd_bus_->send_fd(f) != hal::CanResult::kOk) ++tx_errors_;
    return;
  }
  RthsMeasurement m;
  m.displacement_m = now_.displacement_m;
  m.force_n = now_.force_n;
  m.counter = static_cast<std::uint8_t>(steps_ & 0xFF);
  hal::CanFrame f;
  if (encode(m, config_.lab_node, f)) {
    send(f);
  } else {
    ++tx_errors_;
  }
}

void LabNode::send_status() noexcept {
  RthsLabStatus s;
  s.state = state_;
  s.stop = stop_;
  s.rate_hz = static_cast<std::uint16_t>(config_.rate_hz + 0.5);
  s.counter = status_counter_++;
  hal::CanFrame f;
  if (encode(s, config_.lab_node, f)) send(f);
}

void LabNode::send_beacon() noexcept {
  send_measurement();
  send_status();
}

void LabNode::take(double command_m, double target_m, bool in_sequence) noexcept {
  if (!in_sequence) ++sequence_gaps_;
  if (state_ == LabState::kWaiting) state_ = LabState::kRunning;
  lab_.step(command_m, target_m);
  ++steps_;
  if (state_ == LabState::kRunning && lab_.stopped() != rths::LabStop::kNone) {
    state_ = LabState::kStopped;
    stop_ = reason_of(lab_.stopped());
    stop_step_ = steps_;
  }
  now_ = lab_.measure();
  send_measurement();
  if (state_ == LabState::kStopped) send_status();
}

int LabNode::serve() noexcept {
  int taken = 0;
  for (;;) {
    hal::CanFrame f;
    if (fd_bus_ != nullptr) {
      hal::CanFdFrame g;
      if (fd_bus_->receive_fd(g) != hal::CanResult::kOk) break;
      if (g.fd) {
        RthsFdCommand c;
        if (decode_fd(g, config_.runtime_node, c) != protocol::DecodeError::kOk) {
          ++rejected_;
        } else if (!finished_) {
          take(c.command_m, c.target_m, c.counter == static_cast<std::uint16_t>(steps_ & 0xFFFF));
          ++taken;
        }
        continue;
      }
      f = hal::as_classic(g);
    } else if (bus_.receive(f) != hal::CanResult::kOk) {
      break;
    }
    RthsCommand c;
    RthsRunStatus r;
    if (fd_bus_ == nullptr && decode(f, config_.runtime_node, c) == protocol::DecodeError::kOk) {
      if (!finished_) {
        take(c.command_m, c.target_m, c.counter == static_cast<std::uint8_t>(steps_ & 0xFF));
        ++taken;
      }
    } else if (decode(f, config_.runtime_node, r) == protocol::DecodeError::kOk) {
      finished_ = true;
      run_state_ = r.state;
    } else {
      ++rejected_;
    }
  }
  return taken;
}

void LabNode::stop_for_command_timeout() noexcept {
  if (state_ == LabState::kStopped) return;
  state_ = LabState::kStopped;
  stop_ = LabStopReason::kCommandTimeout;
  stop_step_ = steps_;
  send_status();
}

}  // namespace mrd::rths_board
