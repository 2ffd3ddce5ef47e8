/// The extension module `mrd._mrd`: one closed-loop run as `mrd sim` makes
/// it, its time series lent to NumPy without copies. The pure-Python package
/// (python/mrd/__init__.py) gives it its documented interface.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "host_sim/cli/sim_spec.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/run/run_outputs.hpp"
#include "host_sim/run/sim_run.hpp"
#include "python/src/bindings.hpp"
#include "python/src/controller_adapter.hpp"
#include "python/src/peak_fields.hpp"

namespace py = pybind11;

namespace mrd::python {
namespace {

/// One finished run, shared by the columns lent to NumPy.
struct RunHolder {
  run::SimRun run;
};

/// One time-series column: a read-only 1-D float64 buffer over the run's
/// vector; it keeps the run alive while any view of it exists.
struct Column {
  std::shared_ptr<const RunHolder> owner;
  const std::vector<double>* values;
};

/// What _sim returns: the summary as JSON text (summary.json's), the run's
/// plant::PlantSummary as named numbers (peak_fields.hpp) and the columns.
struct RawResult {
  std::string summary_json;
  std::vector<std::pair<std::string, double>> peaks;
  std::vector<std::pair<std::string, Column>> columns;
};

RawResult sim(const std::string& record, double pga_g, const std::optional<std::string>& control,
              const std::optional<std::string>& numeric, const std::string& board, double idle_years,
              const std::optional<double>& duration_s, const std::optional<double>& step_s, std::uint64_t seed,
              const std::string& plant, std::uint64_t sensor_seed, double offset_mm, const std::string& building,
              const std::string& damper, const std::string& fluid, const std::string& drive,
              const py::object& controller) {
  cli::SimOptions o;
  o.record = record;
  o.pga_g = pga_g;
  if (control) {
    o.control = *control;
    o.control_given = true;
  }
  if (numeric) {
    o.numeric = *numeric;
    o.numeric_given = true;
  }
  if (step_s) {
    o.step_s = *step_s;
    o.step_given = true;
  }
  if (duration_s) {
    o.duration_s = *duration_s;
    o.duration_given = true;
  }
  o.board = board;
  o.idle_years = idle_years;
  o.seed = seed;
  o.plant = plant;
  o.sensor_seed = sensor_seed;
  o.offset_mm = offset_mm;
  o.building = building;
  o.damper = damper;
  o.fluid = fluid;
  o.drive = drive;
  run::SimSpec spec = cli::sim_spec(o);
  spec.keep_record = true;  // the time series is the result's
  std::unique_ptr<run::Controller> c;
  if (controller.is_none()) {
    c = cli::sim_controller(o, spec);
  } else {
    c = std::make_unique<PythonController>(controller);
  }
  auto holder = std::make_shared<RunHolder>(RunHolder{run::run_sim(spec, *c)});
  RawResult result;
  result.summary_json = run::sim_summary_json(holder->run).dump();
  const std::vector<double> values = peak_values(holder->run.summary);
  for (std::size_t i = 0; i < values.size(); ++i) result.peaks.emplace_back(peak_names()[i], values[i]);
  for (const run::ClosedLoopColumn& col : run::closed_loop_columns(holder->run.record)) {
    result.columns.emplace_back(col.name, Column{holder, col.values});
  }
  return result;
}

}  // namespace
}  // namespace mrd::python

PYBIND11_MODULE(_mrd, m) {
  using namespace mrd::python;
  m.doc() = "The mrd simulator's C++ core; use the package mrd (mrd.sim), not this module.";

  // io::UsageError (bad option values, unreadable or malformed files) as
  // mrd.UsageError, a ValueError, with the message `mrd` prints after "mrd: error: ".
  py::register_exception<mrd::io::UsageError>(m, "UsageError", PyExc_ValueError);

  py::class_<Sensors>(m, "Sensors",
                      "One control tick's inputs, as the firmware core receives them (control::ControllerInput).")
      .def_readonly("tick", &Sensors::tick, "Control ticks since the start of the run")
      .def_readonly("damper_disp_m", &Sensors::damper_disp_m, "Damper stroke (base relative to ground), m")
      .def_readonly("damper_force_n", &Sensors::damper_force_n, "Load-cell force, N, positive resisting positive velocity")
      .def_readonly("ground_accel_m_s2", &Sensors::ground_accel_m_s2, "Ground acceleration, m/s^2")
      .def_readonly("base_accel_m_s2", &Sensors::base_accel_m_s2, "Absolute base acceleration, m/s^2")
      .def_readonly("coil_current_a", &Sensors::coil_current_a, "Coil current measured by the drive, A")
      .def("__repr__", [](const Sensors& s) {
        return "Sensors(tick=" + std::to_string(s.tick) + ", damper_disp_m=" + std::to_string(s.damper_disp_m) +
               ", damper_force_n=" + std::to_string(s.damper_force_n) + ")";
      });

  py::class_<Column>(m, "Column", py::buffer_protocol(),
                     "A read-only float64 column of a run's time series (numpy.asarray views it without a copy).")
      .def_buffer([](const Column& c) {
        return py::buffer_info(const_cast<double*>(c.values->data()), sizeof(double),
                               py::format_descriptor<double>::format(), 1,
                               {static_cast<py::ssize_t>(c.values->size())}, {static_cast<py::ssize_t>(sizeof(double))},
                               /*readonly=*/true);
      })
      .def("__len__", [](const Column& c) { return c.values->size(); });

  py::class_<RawResult>(m, "RawResult")
      .def_readonly("summary_json", &RawResult::summary_json)
      .def_readonly("peaks", &RawResult::peaks)
      .def_readonly("columns", &RawResult::columns);

  m.def("_sim", &sim, py::arg("record"), py::arg("pga_g"), py::arg("control"), py::arg("numeric"), py::arg("board"),
        py::arg("idle_years"), py::arg("duration_s"), py::arg("step_s"), py::arg("seed"), py::arg("plant"),
        py::arg("sensor_seed"), py::arg("offset_mm"), py::arg("building"), py::arg("damper"), py::arg("fluid"),
        py::arg("drive"), py::arg("controller"), "One closed-loop run (see mrd.sim).");
  add_batch(m);
  add_objects(m);
}
