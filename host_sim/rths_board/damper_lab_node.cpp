#include "host_sim/rths_board/damper_lab_node.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrd::rths_board {
namespace {

double checked_damper_lab_dt(double rate_hz) {
  if (!(rate_hz >= 100.0 && rate_hz <= 65535.0)) throw std::invalid_argument("laboratory rate outside 100..65535 Hz");
  return 1.0 / rate_hz;
}

peers::DriveConfig drive_on_nodes(peers::DriveConfig d, const protocol::NodeIds& n) {
  d.nodes = n;
  return d;
}

}  // namespace

DamperLabNode::DamperLabNode(hal::CanBus& bus, const DamperLabConfig& config)
    : bus_(bus),
      config_(config),
      period_ns_(std::llround(1e9 * checked_damper_lab_dt(config.rate_hz))),
      servo_(config.delay_s, config.lag_s, checked_damper_lab_dt(config.rate_hz)),
      drive_(drive_on_nodes(config.drive, config.nodes)) {
  damper_.init(config.damper, checked_damper_lab_dt(config.rate_hz), config.settling_quotient);
  force_n_ = damper_.force_n(0.0, 0.0);
}

void DamperLabNode::send(const hal::CanFrame& f) noexcept {
  if (bus_.send(f) != hal::CanResult::kOk) ++tx_errors_;
}

void DamperLabNode::send_sample() noexcept {
  // DriveStatus first: DaqMotion, the frame the runtime waits for, is the
  // tick's last, so the control task has both once the runtime goes on.
  const auto counter = static_cast<std::uint8_t>(steps_ & 0xFF);
  hal::CanFrame f;
  if (protocol::encode(drive_.status(static_cast<float>(damper_.current_a()), counter), config_.nodes.drive, f)) {
    send(f);
  } else {
    ++tx_errors_;
  }
  protocol::DaqMotion m;
  m.damper_disp_m = static_cast<float>(servo_.position_m());
  m.damper_force_n = static_cast<float>(force_n_);
  m.counter = counter;
  if (protocol::encode(m, config_.nodes.daq, f)) {
    send(f);
  } else {
    ++tx_errors_;
  }
}

void DamperLabNode::send_status() noexcept {
  RthsLabStatus s;
  s.state = state_;
  s.stop = stop_;
  s.rate_hz = static_cast<std::uint16_t>(config_.rate_hz + 0.5);
  s.counter = status_counter_++;
  hal::CanFrame f;
  if (encode(s, config_.lab_node, f)) send(f);
}

void DamperLabNode::send_beacon() noexcept {
  send_sample();
  send_status();
}

void DamperLabNode::take(const RthsCommand& c) noexcept {
  const auto tick = static_cast<std::uint8_t>(steps_ & 0xFF);
  if (c.counter != tick) ++sequence_gaps_;
  if (!have_current_ || current_counter_ != tick) ++current_late_;
  if (state_ == LabState::kWaiting) state_ = LabState::kRunning;
  // The drive's output over this step (its timeout rule on the clock of the steps).
  const std::int64_t now_ns = static_cast<std::int64_t>(steps_) * period_ns_;
  const peers::DriveOutput o = drive_.tick(now_ns, false, static_cast<float>(damper_.current_a()));
  const double current_a = o.output_on ? static_cast<double>(o.applied_current_a) : 0.0;
  const double x_a = servo_.position_m(), v_a = servo_.velocity_m_s();
  damper_.step(current_a, v_a, x_a);
  if (state_ == LabState::kRunning) held_command_m_ = c.command_m;  // a stopped actuator holds
  servo_.step(held_command_m_);
  ++steps_;
  force_n_ = damper_.force_n(servo_.velocity_m_s(), servo_.position_m());
  peak_force_n_ = std::max(peak_force_n_, std::fabs(force_n_));
  if (state_ == LabState::kRunning) {
    LabStopReason r = LabStopReason::kNone;
    if (!std::isfinite(force_n_) || !std::isfinite(servo_.position_m()) || !std::isfinite(c.command_m))
      r = LabStopReason::kNotFinite;
    else if (std::fabs(force_n_) > config_.force_limit_n)
      r = LabStopReason::kForceLimit;
    else if (std::fabs(servo_.position_m() - c.target_m) > config_.tracking_limit_m)
      r = LabStopReason::kTrackingLimit;
    if (r != LabStopReason::kNone) {
      state_ = LabState::kStopped;
      stop_ = r;
      stop_step_ = steps_;
    }
  }
  send_sample();
  if (state_ == LabState::kStopped) send_status();
}

int DamperLabNode::serve() noexcept {
  int taken = 0;
  hal::CanFrame f;
  while (bus_.receive(f) == hal::CanResult::kOk) {
    RthsCommand c;
    RthsRunStatus r;
    protocol::CurrentCommand i;
    if (protocol::decode(f, config_.nodes.controller, i) == protocol::DecodeError::kOk) {
      const std::int64_t now_ns = static_cast<std::int64_t>(steps_) * period_ns_;
      if (drive_.on_frame(f, now_ns)) {
        have_current_ = true;
        current_counter_ = i.counter;
      }
    } else if (decode(f, config_.nodes.controller, c) == protocol::DecodeError::kOk) {
      if (!finished_) {
        if (config_.own_clock) {
          latest_ = c;
          have_latest_ = latest_new_ = true;
        } else {
          take(c);
        }
        ++taken;
      }
    } else if (decode(f, config_.nodes.controller, r) == protocol::DecodeError::kOk) {
      finished_ = true;
      run_state_ = r.state;
    } else {
      ++rejected_;
    }
  }
  return taken;
}

void DamperLabNode::step_on_clock() noexcept {
  if (!have_latest_ || finished_) return;
  RthsCommand c = latest_;
  if (!latest_new_) ++held_steps_;
  c.counter = static_cast<std::uint8_t>(steps_ & 0xFF);  // the clock's step, not the runtime's tick
  latest_new_ = false;
  take(c);
}

void DamperLabNode::stop_for_command_timeout() noexcept {
  if (state_ == LabState::kStopped) return;
  state_ = LabState::kStopped;
  stop_ = LabStopReason::kCommandTimeout;
  stop_step_ = steps_;
  send_status();
}

}  // namespace mrd::rths_board
