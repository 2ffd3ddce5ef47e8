/// mrd.batch: many closed-loop runs on one plant stepped in SIMD lanes
/// (batch::run_closed_loop_batch), the GIL released while they run.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <exception>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "host_sim/batch/batch_run.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/cli/sim_spec.hpp"
#include "host_sim/excitation/ground_motion.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "mrd/units.hpp"
#include "python/src/bindings.hpp"
#include "python/src/peak_fields.hpp"

namespace py = pybind11;

namespace mrd::python {
namespace {

using Accel = py::array_t<double, py::array::c_style | py::array::forcecast>;

batch::LaneIsa parse_isa(const std::string& text) {
  cli::require_choice("isa", text, {"auto", "generic", "x86-64-v3", "x86-64-v4"});
  for (batch::LaneIsa isa : {batch::LaneIsa::kAuto, batch::LaneIsa::kGeneric, batch::LaneIsa::kX86_64V3,
                             batch::LaneIsa::kX86_64V4}) {
    if (text != batch::lane_isa_name(isa)) continue;
    if (isa != batch::LaneIsa::kAuto && !batch::lane_isa_available(isa))
      throw io::UsageError("isa: " + text + " is not available on this CPU");
    return isa;
  }
  return batch::LaneIsa::kAuto;
}

/// CPU time of the calling thread, s.
double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::string item(const char* name, std::size_t i) { return std::string(name) + "[" + std::to_string(i) + "]"; }

/// The plant of the batch, made by `mrd sim`'s option checks and files.
plant::PlantSpec batch_plant(const std::string& building, const std::string& damper, const std::string& fluid,
                             const std::optional<double>& step_s, const std::optional<std::string>& numeric,
                             run::NumericKind& numeric_out) {
  cli::SimOptions o;
  o.building = building;
  o.damper = damper;
  o.fluid = fluid;
  if (step_s) {
    o.step_s = *step_s;
    o.step_given = true;
  }
  if (numeric) {
    o.numeric = *numeric;
    o.numeric_given = true;
  }
  const run::SimSpec spec = cli::sim_spec(o);
  numeric_out = spec.numeric;
  plant::PlantSpec p;
  p.step_s = spec.step_s;
  p.kind = spec.plant;
  p.building = spec.building;
  p.damper = spec.damper;
  p.settling = spec.settling;
  return p;
}

struct BatchOut {
  std::vector<std::string> names;
  py::array_t<double> values;  ///< [field][run]
  double cpp_seconds = 0.0;      ///< wall time of the batch::run_closed_loop_batch calls
  double cpp_cpu_seconds = 0.0;  ///< their CPU time, summed over the worker threads
};

BatchOut run_batch(const std::vector<Accel>& records, const std::vector<double>& scale,
                   const std::vector<double>& idle_years, const std::vector<std::string>& control,
                   const std::string& building, const std::string& damper, const std::string& fluid,
                   const std::optional<double>& step_s, const std::optional<std::string>& numeric, bool story_drift,
                   unsigned threads, const std::string& isa) {
  const std::size_t n = records.size();
  if (scale.size() != n || idle_years.size() != n || control.size() != n)
    throw io::UsageError("scale, idle_years, control: expected one value per record (" + std::to_string(n) +
                         "), got " + std::to_string(scale.size()) + ", " + std::to_string(idle_years.size()) +
                         ", " + std::to_string(control.size()));
  if (threads > cli::kMaxThreads)
    throw io::UsageError("threads: expected at most " + std::to_string(cli::kMaxThreads) + ", got " +
                         std::to_string(threads));
  batch::BatchOptions options;
  options.isa = parse_isa(isa);
  options.story_drift = story_drift;
  const plant::PlantSpec plant = batch_plant(building, damper, fluid, step_s, numeric, options.numeric);
  std::vector<batch::BatchRun> runs(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Accel& a = records[i];
    if (a.ndim() != 1) throw io::UsageError(item("records", i) + ": expected a 1-D array of m/s^2 at step_s");
    if (a.size() == 0) throw io::UsageError(item("records", i) + ": expected at least one sample");
    const double* v = a.data();
    // A record shared by many runs (one array) is checked once.
    const bool seen = i > 0 && records[i - 1].data() == v && records[i - 1].size() == a.size();
    for (py::ssize_t k = 0; !seen && k < a.size(); ++k) {
      if (!(std::fabs(v[k]) <= excitation::kMaxRecordAccel_m_s2))
        throw io::UsageError(item("records", i) + "[" + std::to_string(k) + "]: expected a finite acceleration of at most " +
                             io::format_number("%g", excitation::kMaxRecordAccel_m_s2) + " m/s^2 in magnitude, got " +
                             io::format_number("%g", v[k]));
    }
    if (!std::isfinite(scale[i])) throw io::UsageError(item("scale", i) + ": expected a finite number");
    cli::check_idle_years(idle_years[i]);
    runs[i].ground_accel_m_s2 = std::span<const double>(v, static_cast<std::size_t>(a.size()));
    runs[i].ground_scale = scale[i];
    runs[i].idle_time_s = units::years_to_s(idle_years[i]);
    runs[i].mode = run::parse_control_mode(control[i]);
  }
  std::vector<plant::PlantSummary> summaries(n);
  double seconds = 0.0;
  std::vector<double> cpu_s;
  {
    py::gil_scoped_release release;
    const unsigned workers = std::max(1u, std::min<unsigned>(threads == 0 ? std::thread::hardware_concurrency() : threads,
                                                             static_cast<unsigned>(std::max<std::size_t>(n, 1))));
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<std::exception_ptr> errors(workers);
    cpu_s.assign(workers, 0.0);
    auto work = [&](unsigned w) {
      const double cpu0 = thread_cpu_s();
      try {
        const std::size_t begin = n * w / workers, end = n * (w + 1) / workers;
        const std::vector<plant::PlantSummary> part = batch::run_closed_loop_batch(
            plant, std::span<const batch::BatchRun>(runs.data() + begin, end - begin), options);
        std::copy(part.begin(), part.end(), summaries.begin() + static_cast<std::ptrdiff_t>(begin));
      } catch (...) {
        errors[w] = std::current_exception();
      }
      cpu_s[w] = thread_cpu_s() - cpu0;
    };
    if (workers == 1) {
      work(0);
    } else {
      std::vector<std::thread> pool;
      for (unsigned w = 0; w < workers; ++w) pool.emplace_back(work, w);
      for (std::thread& t : pool) t.join();
    }
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (const std::exception_ptr& e : errors)
      if (e) std::rethrow_exception(e);
  }
  BatchOut out;
  out.names = peak_names();
  out.values = py::array_t<double>({static_cast<py::ssize_t>(out.names.size()), static_cast<py::ssize_t>(n)});
  auto w = out.values.mutable_unchecked<2>();
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<double> v = peak_values(summaries[i]);
    for (std::size_t f = 0; f < v.size(); ++f) w(static_cast<py::ssize_t>(f), static_cast<py::ssize_t>(i)) = v[f];
  }
  out.cpp_seconds = seconds;
  for (double c : cpu_s) out.cpp_cpu_seconds += c;
  return out;
}

}  // namespace

void add_batch(py::module_& m) {
  py::class_<BatchOut>(m, "BatchOut")
      .def_readonly("names", &BatchOut::names)
      .def_readonly("values", &BatchOut::values)
      .def_readonly("cpp_seconds", &BatchOut::cpp_seconds)
      .def_readonly("cpp_cpu_seconds", &BatchOut::cpp_cpu_seconds);
  m.def("_batch", &run_batch, py::arg("records"), py::arg("scale"), py::arg("idle_years"), py::arg("control"),
        py::arg("building"), py::arg("damper"), py::arg("fluid"), py::arg("step_s"), py::arg("numeric"),
        py::arg("story_drift"), py::arg("threads"), py::arg("isa"), "Many closed-loop runs in lanes (see mrd.batch).");
  m.def("_lane_isa", [] { return std::string(batch::lane_isa_name(batch::auto_lane_isa())); },
        "The lane kernel 'auto' picks on this CPU.");
}

}  // namespace mrd::python
