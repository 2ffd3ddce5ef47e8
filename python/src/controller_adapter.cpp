#include "python/src/controller_adapter.hpp"

#include <string>
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
  const py::object result = step_(py::cast(sensors));
  // A number (the current command, A) or a pair (current command, A; desired force, N).
  py::object command = result;
  double desired_force_n = 0.0;
  if (PyTuple_Check(result.ptr())) {
    const py::tuple pair = py::reinterpret_borrow<py::tuple>(result);
    if (pair.size() != 2)
      throw io::UsageError("controller: step returned a tuple of " + std::to_string(pair.size()) +
                           " values; expected a current command, A, or (current command A, desired force N)");
    command = pair[0];
    desired_force_n = PyFloat_AsDouble(pair[1].ptr());
    if (desired_force_n == -1.0 && PyErr_Occurred()) throw py::error_already_set();
  }
  const double command_a = PyFloat_AsDouble(command.ptr());  // a float, an int or anything with __float__
  if (command_a == -1.0 && PyErr_Occurred()) throw py::error_already_set();
  control::ControllerOutput out;
  out.current_command_a = static_cast<float>(command_a);
  out.desired_force_n = static_cast<float>(desired_force_n);
  return out;
}

}  // namespace mrd::python
