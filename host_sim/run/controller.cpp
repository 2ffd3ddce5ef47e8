#include "run/controller.hpp"

#include "report/output_dir.hpp"

namespace mrd::run {

control::ControlMode parse_control_mode(const std::string& text) {
  for (auto m : {control::ControlMode::kPassiveOff, control::ControlMode::kPassiveOn,
                 control::ControlMode::kSemiActive}) {
    if (text == control::mode_name(m)) return m;
  }
  throw report::UsageError("--control: expected passive-off, passive-on or semi-active, got '" + text + "'");
}

std::vector<control::ControlMode> available_modes() {
  std::vector<control::ControlMode> modes;
  for (auto m : {control::ControlMode::kPassiveOff, control::ControlMode::kPassiveOn,
                 control::ControlMode::kSemiActive}) {
    try {
      (void)make_controller(m, 1e-3);
      modes.push_back(m);
    } catch (const report::UsageError&) {
    }
  }
  return modes;
}

std::unique_ptr<Controller> make_controller(control::ControlMode mode, double /*period_s*/) {
  switch (mode) {
    case control::ControlMode::kPassiveOff: return std::make_unique<ConstantCurrentController>(0.0);
    case control::ControlMode::kPassiveOn: return std::make_unique<ConstantCurrentController>(kPassiveOnCurrent_a);
    case control::ControlMode::kSemiActive: break;
  }
  throw report::UsageError("--control semi-active: the semi-active firmware core is not in this build yet");
}

}  // namespace mrd::run
