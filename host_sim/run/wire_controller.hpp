#pragma once
/// The controller as a board runs it: its inputs and output passed through
/// the frames a board's CAN run uses (codec encode → decode, with their
/// quantization), so that run::run_closed_loop with it differs from a run
/// over CAN (mrd-sim-board, an emulated or real board) only by the bus
/// itself. `mrd sim --board` runs it; the board tests use it as their
/// in-process reference. Sensors: DaqMotion, DaqAccel; coil current:
/// SimCoilState then DriveStatus (plant → drive → controller); command:
/// CurrentCommand then SimCoilDrive (controller → drive → plant).

#include <memory>

#include "mrd/protocol/codec.hpp"
#include "host_sim/run/controller.hpp"

namespace mrd::run {

class WireQuantizedController final : public Controller {
 public:
  explicit WireQuantizedController(std::unique_ptr<Controller> inner) : inner_(std::move(inner)) {}
  void reset() override { inner_->reset(); }

  control::ControllerOutput step(const control::ControllerInput& in) override {
    control::ControllerInput q = in;
    hal::CanFrame f;
    protocol::DaqMotion m{in.damper_disp_m, true, in.damper_force_n, true, 0};
    if (protocol::encode(m, 3, f) && protocol::decode(f, 3, m) == protocol::DecodeError::kOk) {
      q.damper_disp_m = m.damper_disp_m;
      q.damper_force_n = m.damper_force_n;
    }
    protocol::DaqAccel a{in.ground_accel_m_s2, true, in.base_accel_m_s2, true, 0};
    if (protocol::encode(a, 3, f) && protocol::decode(f, 3, a) == protocol::DecodeError::kOk) {
      q.ground_accel_m_s2 = a.ground_accel_m_s2;
      q.base_accel_m_s2 = a.base_accel_m_s2;
    }
    protocol::SimCoilState s{in.coil_current_a, 0};
    protocol::DriveStatus d{};
    if (protocol::encode(s, 3, f) && protocol::decode(f, 3, s) == protocol::DecodeError::kOk) {
      d.measured_current_a = s.coil_current_a;
      if (protocol::encode(d, 2, f) && protocol::decode(f, 2, d) == protocol::DecodeError::kOk)
        q.coil_current_a = d.measured_current_a;
    }
    control::ControllerOutput out = inner_->step(q);
    protocol::CurrentCommand c{out.current_command_a, out.drive_enable, control::ControlMode::kPassiveOff, 0};
    if (!protocol::encode(c, 1, f) || protocol::decode(f, 1, c) != protocol::DecodeError::kOk) c = {};
    protocol::SimCoilDrive sd{c.enable ? c.current_a : 0.0f, c.enable, 0};
    if (protocol::encode(sd, 2, f) && protocol::decode(f, 2, sd) == protocol::DecodeError::kOk) {
      out.current_command_a = sd.applied_current_a;
      out.drive_enable = sd.output_on;
    }
    return out;
  }

 private:
  std::unique_ptr<Controller> inner_;
};

}  // namespace mrd::run
