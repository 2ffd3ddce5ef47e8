#include "python/src/controller_adapter.hpp"

#include <utility>

#include "host_sim/io/usage_error.hpp"

namespace py = pybind11;

namespace mrd::python {

PythonController::PythonController(py::object controller) : controller_(std::move(controller)) {
  if (py::hasattr(controller_, "step")) {
    step_ = controller_.attr("step");
  } else if (PyCallable_Check(controller_.ptr())) {
    step_ = controller_;
  } else {
    throw io::UsageError("controller: expected a callable or an object with a step(sensors) method");
  }
}

void PythonController::reset() {
  if (py::hasattr(controller_, "reset")) controller_.attr("reset")();
}

control::ControllerOutput PythonController::step(const control::ControllerInput& in) {
  const Sensors sensors{in.tick,          in.damper_disp_m,   in.damper_force_n,
                        in.ground_accel_m_s2, in.base_accel_m_s2, in.coil_current_a};
  const py::object command = step_(py::cast(sensors));
  const double command_a = PyFloat_AsDouble(command.ptr());  // a float, an int or anything with __float__
  if (command_a == -1.0 && PyErr_Occurred()) throw py::error_already_set();
  control::ControllerOutput out;
  out.current_command_a = static_cast<float>(command_a);
  return out;
}

}  // namespace mrd::python
