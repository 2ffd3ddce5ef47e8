#pragma once
/// A controller as the simulator sees it: the same step signature and the
/// same input/output values (`mrd::control::ControllerInput/Output`) that the
/// firmware core uses on the board.

#include <memory>
#include <string>
#include <vector>

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

/// Nominal current of passive-on (thesis §6.4: 2.5 A).
inline constexpr double kPassiveOnCurrent_a = 2.5;

/// Parses "passive-off" | "passive-on" | "semi-active"; throws
/// report::UsageError naming the option otherwise.
control::ControlMode parse_control_mode(const std::string& text);

/// The modes this build can run, in the order reports list them.
std::vector<control::ControlMode> available_modes();

/// The controller for a mode at the given control period. Throws
/// report::UsageError for a mode this build cannot run.
std::unique_ptr<Controller> make_controller(control::ControlMode mode, double period_s);

}  // namespace mrd::run
