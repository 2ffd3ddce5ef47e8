#pragma once
/// A controller as the simulator sees it: the same step signature and the
/// same input/output values (`mrd::control::ControllerInput/Output`) that the
/// firmware core uses on the board.

#include <memory>
#include <string>
#include <vector>

#include "firmware/core/damper_controller.hpp"
#include "mrd/control/io.hpp"

namespace mrd::run {

class Controller {
 public:
  virtual ~Controller() = default;
  virtual void reset() = 0;
  virtual control::ControllerOutput step(const control::ControllerInput& in) = 0;
};

/// Passive modes: a constant current command.
class ConstantCurrentController final : public Controller {
 public:
  explicit ConstantCurrentController(double current_a) : current_a_(static_cast<float>(current_a)) {}
  void reset() override {}
  control::ControllerOutput step(const control::ControllerInput&) override {
    control::ControllerOutput out;
    out.current_command_a = current_a_;
    return out;
  }

 private:
  float current_a_;
};

/// Which numeric build of the firmware control core runs.
/// The control core's build: single-precision float (the boards' default),
/// 32-bit fixed point, or the host's double-precision reference.
enum class NumericKind { kFloat, kFixed, kDouble };

/// "float" | "fixed" | "double".
const char* numeric_name(NumericKind kind) noexcept;

/// Parses "float" | "fixed" | "double"; throws io::UsageError naming --numeric otherwise.
NumericKind parse_numeric_kind(const std::string& text);

/// The firmware control core (firmware/core) behind the simulator's
/// Controller interface: it gets exactly the ControllerInput values a board
/// runtime hands it and returns its ControllerOutput unchanged.
template <class Policy>
class FirmwareController final : public Controller {
 public:
  /// `config` must be valid (see fw::default_controller_config()).
  explicit FirmwareController(const fw::ControllerConfig& config) noexcept { error_ = core_.init(config); }
  fw::ConfigError init_error() const noexcept { return error_; }
  void reset() override { core_.reset(); }
  control::ControllerOutput step(const control::ControllerInput& in) override { return core_.step(in); }
  const fw::DamperControllerStatus& status() const noexcept { return core_.status(); }

 private:
  fw::DamperController<Policy> core_{};
  fw::ConfigError error_ = fw::ConfigError::kNone;
};

/// control::parse_mode_name() for the command line: throws
/// io::UsageError naming --control for an unknown mode.
control::ControlMode parse_control_mode(const std::string& text);

/// The modes this build can run, in the order reports list them.
std::vector<control::ControlMode> available_modes();

/// The controller for a mode at the given control period: the firmware
/// control core in the chosen numeric build, configured by
/// fw::default_controller_config() as on a board, for every mode. Throws
/// io::UsageError naming --step-s when the core rejects the period.
std::unique_ptr<Controller> make_controller(control::ControlMode mode, double period_s,
                                            NumericKind numeric = NumericKind::kFloat);

/// The firmware control core in the chosen numeric build with `config` as
/// given (another damper's or building's, e.g. from a board file). Throws
/// io::UsageError when the core rejects it, naming the rule; for the
/// fixed-point build's kFixedPointRange, the constant that does not fit and
/// its format's limit (fw::fixed_point_misfit).
std::unique_ptr<Controller> make_configured_controller(const fw::ControllerConfig& config, NumericKind numeric);

}  // namespace mrd::run
