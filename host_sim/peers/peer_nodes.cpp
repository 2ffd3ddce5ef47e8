#include "host_sim/peers/peer_nodes.hpp"

namespace mrd::peers {

using protocol::can_id;
using protocol::MsgId;

std::vector<hal::CanFilter> plant_filters(const protocol::NodeIds& n) {
  return {{can_id(MsgId::kSimCoilDrive, n.drive), 0x7FF}};
}
std::vector<hal::CanFilter> drive_filters(const protocol::NodeIds& n) {
  // All current commands, whatever the sender, so that foreign ones are counted.
  return {{can_id(MsgId::kCurrentCommand, 0), 0x7F0}, {can_id(MsgId::kSimCoilState, n.daq), 0x7FF}};
}
std::vector<hal::CanFilter> actuator_filters(const protocol::NodeIds& n) {
  return {{can_id(MsgId::kMixingCommand, n.controller), 0x7FF}};
}

// ---- Plant -----------------------------------------------------------------

PlantNode::PlantNode(hal::CanBus& bus, const protocol::NodeIds& nodes, const plant::PlantSpec& spec)
    : bus_(bus), nodes_(nodes) {
  plant_.init(spec);
}

void PlantNode::send_sensors(const plant::PlantSensors& s, std::uint8_t counter) noexcept {
  hal::CanFrame f;
  // A value the protocol cannot carry goes out as "not available".
  protocol::DaqMotion m{s.damper_disp_m, true, s.damper_force_n, true, counter};
  if (!protocol::encode(m, nodes_.daq, f)) {
    ++encode_errors_;
    protocol::DaqMotion probe = m;
    probe.force_valid = false;
    m.disp_valid = protocol::encode(probe, nodes_.daq, f);
    probe = m;
    probe.disp_valid = false;
    m.force_valid = protocol::encode(probe, nodes_.daq, f);
    (void)protocol::encode(m, nodes_.daq, f);
  }
  bus_.send(f);
  protocol::DaqAccel a{s.ground_accel_m_s2, true, s.base_accel_m_s2, true, counter};
  if (!protocol::encode(a, nodes_.daq, f)) {
    ++encode_errors_;
    a.ground_valid = a.base_valid = false;
    (void)protocol::encode(a, nodes_.daq, f);
  }
  bus_.send(f);
}

void PlantNode::begin_tick(double ground_accel_m_s2) noexcept {
  const plant::PlantSensors s = plant_.sense(ground_accel_m_s2);
  const auto counter = static_cast<std::uint8_t>(tick_ & 0xFFu);
  hal::CanFrame f;
  // The coil first: the drive answers it with its status in the same tick.
  if (protocol::encode(protocol::SimCoilState{s.coil_current_a, counter}, nodes_.daq, f)) {
    bus_.send(f);
  } else {
    ++encode_errors_;
  }
  send_sensors(s, counter);
  pending_ = true;
  got_drive_ = false;
}

void PlantNode::drain(bool lockstep) noexcept {
  hal::CanFrame f;
  while (bus_.receive(f) == hal::CanResult::kOk) {
    protocol::SimCoilDrive d;
    if (protocol::decode(f, nodes_.drive, d) != protocol::DecodeError::kOk) {
      ++rejected_;
      continue;
    }
    if (lockstep && d.counter != static_cast<std::uint8_t>(tick_ & 0xFFu)) {
      ++rejected_;  // not this tick's answer
      continue;
    }
    if (!protocol::counter_ok(drive_counter_.check(d.counter)) && lockstep) {
      ++rejected_;
      continue;
    }
    drive_ = d;
    got_drive_ = true;
  }
}

bool PlantNode::try_finish_tick() noexcept {
  if (!pending_) return true;
  drain(true);
  if (!got_drive_) return false;
  plant_.advance({static_cast<double>(drive_.applied_current_a), drive_.output_on});
  pending_ = false;
  ++tick_;
  return true;
}

void PlantNode::force_finish_tick() noexcept {
  if (!pending_) return;
  plant_.advance({static_cast<double>(drive_.applied_current_a), drive_.output_on});
  pending_ = false;
  ++tick_;
}

void PlantNode::free_tick(double ground_accel_m_s2) noexcept {
  drain(false);
  const plant::PlantSensors s = plant_.sense(ground_accel_m_s2);
  const auto counter = static_cast<std::uint8_t>(tick_ & 0xFFu);
  hal::CanFrame f;
  if (protocol::encode(protocol::SimCoilState{s.coil_current_a, counter}, nodes_.daq, f)) bus_.send(f);
  send_sensors(s, counter);
  plant_.advance({static_cast<double>(drive_.applied_current_a), got_drive_ && drive_.output_on});
  ++tick_;
}

// ---- Drive -----------------------------------------------------------------

DriveNode::DriveNode(hal::CanBus& bus, const DriveConfig& config, double period_s)
    : bus_(bus), c_(config), logic_(config), period_ns_(static_cast<std::int64_t>(period_s * 1e9 + 0.5)) {}

void DriveNode::decide(std::int64_t now_ns, std::uint8_t counter) noexcept {
  const DriveOutput o = logic_.tick(now_ns, fault_, measured_a_);
  hal::CanFrame f;
  if (protocol::encode(protocol::SimCoilDrive{o.applied_current_a, o.output_on, counter}, c_.nodes.drive, f))
    bus_.send(f);
  ++ticks_;
}

bool DriveNode::poll() noexcept {
  hal::CanFrame f;
  bool decided = false;
  while (bus_.receive(f) == hal::CanResult::kOk) {
    protocol::SimCoilState s;
    if (protocol::decode(f, c_.nodes.daq, s) == protocol::DecodeError::kOk) {
      if (!protocol::counter_ok(coil_counter_.check(s.counter))) continue;
      if (awaiting_) decide_without_command();
      measured_a_ = s.coil_current_a;
      pending_counter_ = s.counter;
      awaiting_ = true;
      hal::CanFrame out;
      if (protocol::encode(logic_.status(measured_a_, s.counter), c_.nodes.drive, out)) bus_.send(out);
      continue;
    }
    const bool valid = logic_.on_frame(f, sim_now_ns_);
    if (valid && awaiting_) {
      decide(sim_now_ns_, pending_counter_);
      awaiting_ = false;
      sim_now_ns_ += period_ns_;
      decided = true;
    }
  }
  return decided;
}

void DriveNode::decide_without_command() noexcept {
  if (!awaiting_) return;
  decide(sim_now_ns_, pending_counter_);
  awaiting_ = false;
  sim_now_ns_ += period_ns_;
}

void DriveNode::free_tick(std::int64_t now_ns) noexcept {
  hal::CanFrame f;
  while (bus_.receive(f) == hal::CanResult::kOk) {
    protocol::SimCoilState s;
    if (protocol::decode(f, c_.nodes.daq, s) == protocol::DecodeError::kOk) {
      measured_a_ = s.coil_current_a;
      continue;
    }
    logic_.on_frame(f, now_ns);
  }
  const std::uint8_t counter = status_counter_++;
  decide(now_ns, counter);
  if (protocol::encode(logic_.status(measured_a_, counter), c_.nodes.drive, f)) bus_.send(f);
}

// ---- Actuator --------------------------------------------------------------

ActuatorNode::ActuatorNode(hal::CanBus& bus, const ActuatorConfig& config, std::int64_t status_period_ns)
    : bus_(bus), c_(config), logic_(config), status_period_ns_(status_period_ns) {}

void ActuatorNode::free_tick(std::int64_t now_ns) noexcept {
  hal::CanFrame f;
  while (bus_.receive(f) == hal::CanResult::kOk) logic_.on_frame(f, now_ns);
  const protocol::MixingStatus s = logic_.tick(now_ns);
  if (now_ns >= next_status_ns_) {
    protocol::MixingStatus out = s;
    out.counter = counter_++;
    if (protocol::encode(out, c_.nodes.actuator, f)) bus_.send(f);
    next_status_ns_ = now_ns + status_period_ns_;
  }
}

void RestingDaqNode::sample(double stroke_m) noexcept {
  protocol::DaqMotion m;
  m.damper_disp_m = static_cast<float>(stroke_m);
  m.force_valid = false;
  m.counter = counter_;
  protocol::DaqAccel a;
  a.ground_accel_m_s2 = 0.0f;
  a.base_accel_m_s2 = 0.0f;
  a.counter = counter_++;
  hal::CanFrame f;
  if (!protocol::encode(m, nodes_.daq, f) || bus_.send(f) != hal::CanResult::kOk) ++send_errors_;
  if (!protocol::encode(a, nodes_.daq, f) || bus_.send(f) != hal::CanResult::kOk) ++send_errors_;
}

}  // namespace mrd::peers
