#include "host_sim/run/controller.hpp"

#include "host_sim/io/usage_error.hpp"

namespace mrd::run {

control::ControlMode parse_control_mode(const std::string& text) {
  if (const auto m = control::parse_mode_name(text)) return *m;
  throw io::UsageError("--control: expected passive-off, passive-on or semi-active, got '" + text + "'");
}

std::vector<control::ControlMode> available_modes() {
  std::vector<control::ControlMode> modes;
  for (auto m : {control::ControlMode::kPassiveOff, control::ControlMode::kPassiveOn,
                 control::ControlMode::kSemiActive}) {
    try {
      (void)make_controller(m, 1e-3);
      modes.push_back(m);
    } catch (const io::UsageError&) {
    }
  }
  return modes;
}

const char* numeric_name(NumericKind kind) noexcept {
  switch (kind) {
    case NumericKind::kFixed: return "fixed";
    case NumericKind::kDouble: return "double";
    case NumericKind::kFloat: break;
  }
  return "float";
}

NumericKind parse_numeric_kind(const std::string& text) {
  if (text == "float") return NumericKind::kFloat;
  if (text == "fixed") return NumericKind::kFixed;
  if (text == "double") return NumericKind::kDouble;
  throw io::UsageError("--numeric: expected float, fixed or double, got '" + text + "'");
}

namespace {
template <class Policy>
std::unique_ptr<Controller> make_configured(const fw::ControllerConfig& c) {
  auto controller = std::make_unique<FirmwareController<Policy>>(c);
  const fw::ConfigError e = controller->init_error();
  if (e == fw::ConfigError::kNone) return controller;
  std::string why = fw::config_error_name(e);
  if (e == fw::ConfigError::kFixedPointRange) {
    if (const char* misfit = fw::fixed_point_misfit<Policy>(c)) why = misfit;
  }
  throw io::UsageError(std::string("controller: the ") + Policy::kName +
                       " firmware control core rejects its configuration: " + why);
}

template <class Policy>
std::unique_ptr<Controller> make_firmware(const fw::ControllerConfig& c) {
  auto controller = std::make_unique<FirmwareController<Policy>>(c);
  if (controller->init_error() != fw::ConfigError::kNone) {
    const fw::ConfigError e = controller->init_error();
    const bool period = e == fw::ConfigError::kPeriod || e == fw::ConfigError::kFilterFrequency ||
                        e == fw::ConfigError::kVelocityFilter;
    throw io::UsageError(std::string(period ? "--step-s" : "controller") +
                             ": the firmware control core rejects its configuration at a period of " +
                             std::to_string(c.period_s) + " s (" + fw::config_error_name(e) + ")");
  }
  return controller;
}
}  // namespace

std::unique_ptr<Controller> make_controller(control::ControlMode mode, double period_s, NumericKind numeric) {
  const fw::ControllerConfig c = fw::default_controller_config(mode, period_s);
  if (numeric == NumericKind::kFixed) return make_firmware<num::Fixed32Policy>(c);
  if (numeric == NumericKind::kDouble) return make_firmware<fw::Float64Policy>(c);
  return make_firmware<num::Float32Policy>(c);
}

std::unique_ptr<Controller> make_configured_controller(const fw::ControllerConfig& config, NumericKind numeric) {
  if (numeric == NumericKind::kFixed) return make_configured<num::Fixed32Policy>(config);
  if (numeric == NumericKind::kDouble) return make_configured<fw::Float64Policy>(config);
  return make_configured<num::Float32Policy>(config);
}

}  // namespace mrd::run
