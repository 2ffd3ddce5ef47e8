#pragma once
/// A controller written in Python behind the simulator's run::Controller
/// interface: each tick it receives the sensors the firmware core would get
/// (a Sensors object) and returns the current command, A.

#include <pybind11/pybind11.h>

#include "host_sim/run/controller.hpp"

namespace mrd::python {

/// One tick's controller inputs as Python sees them (control::ControllerInput's values).
struct Sensors {
  std::uint64_t tick = 0;
  double damper_disp_m = 0.0;
  double damper_force_n = 0.0;
  double ground_accel_m_s2 = 0.0;
  double base_accel_m_s2 = 0.0;
  double coil_current_a = 0.0;
};

/// Calls `step(sensors)` (the object's step method, or the object itself when
/// it is a callable) once per tick; the GIL stays held. It returns the
/// current command, A, or a pair (current command, A; desired force, N, the
/// desired_force_n column), each converted to the core's float, the drive
/// enabled; without a pair the desired force is 0. reset() calls the
/// object's reset() when it has one.
class PythonController final : public run::Controller {
 public:
  /// Throws io::UsageError when `controller` is neither callable nor has a step method.
  explicit PythonController(pybind11::object controller);
  void reset() override;
  control::ControllerOutput step(const control::ControllerInput& in) override;

 private:
  pybind11::object controller_;
  pybind11::object step_;
};

}  // namespace mrd::python
