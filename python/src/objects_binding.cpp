/// Buildings, dampers, fluids and records from files or from text made in
/// Python (mrd.Building, mrd.Damper, mrd.Fluid, mrd.Record): the file
/// readers parse them, so a value is refused with the reader's message.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "host_sim/cli/options.hpp"
#include "host_sim/damper/damper_file.hpp"
#include "host_sim/excitation/ground_motion.hpp"
#include "host_sim/fluid/fluid_file.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/run/motions.hpp"
#include "host_sim/run/sim_run.hpp"
#include "host_sim/structure/building_file.hpp"
#include "python/src/bindings.hpp"

namespace py = pybind11;

namespace mrd::python {
namespace {

py::dict building_info(const structure::BuildingParams& b) {
  py::dict d;
  d["name"] = b.name;
  d["dofs"] = b.dofs();
  d["base"] = b.base == structure::BaseKind::kFixed ? "fixed" : "isolated";
  d["mass_kg"] = b.mass_kg;
  d["stiffness_n_m"] = b.story_stiffness_n_m;
  d["isolators"] = b.isolators.size();
  d["dampers"] = b.dampers.size();
  return d;
}

py::dict damper_info(const damper::DamperFile& f) {
  py::dict d;
  d["name"] = f.name;
  d["rated_current_a"] = f.params.rating.current_a;
  d["rated_force_n"] = f.params.rating.force_n;
  d["rated_stroke_m"] = f.params.rating.stroke_m;
  d["rated_velocity_m_s"] = f.params.rating.velocity_m_s;
  d["coil_resistance_ohm"] = f.params.coil_heat.resistance_ohm;
  d["coil_thermal_resistance_k_w"] = f.params.coil_heat.thermal_resistance_k_w;
  d["coil_thermal_time_constant_s"] = f.params.coil_heat.time_constant_s;
  d["coil_inductance_1a_h"] = f.params.coil_inductance.inductance_1a_h;
  d["coil_inductance_2a_h"] = f.params.coil_inductance.inductance_2a_h;
  d["warnings"] = f.warnings;
  return d;
}

py::dict fluid_info(const fluid::FluidFile& f) {
  py::dict d;
  d["name"] = f.name;
  d["source"] = f.source;
  d["solid_fraction"] = f.settling.solid_fraction;
  d["warnings"] = f.warnings;
  return d;
}

/// A vector handed to NumPy without a copy: the array owns it.
py::array_t<double> owned_array(std::vector<double>&& values) {
  auto* owner = new std::vector<double>(std::move(values));
  py::capsule free_owner(owner, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>({static_cast<py::ssize_t>(owner->size())}, {static_cast<py::ssize_t>(sizeof(double))},
                             owner->data(), free_owner);
}

py::dict motion(const std::string& record, double pga_g, double step_s, const std::optional<double>& duration_s,
                std::uint64_t seed) {
  // mrd sim's checks of --pga-g, --step-s and --duration-s (host_sim/cli/sim_spec.cpp).
  cli::check_pga_g(pga_g);
  cli::require_step_s(step_s, 0.02, "0.02 s");
  if (duration_s) {
    cli::require_positive("--duration-s", *duration_s, "a duration");
    cli::require_at_most("--duration-s", *duration_s, cli::kMaxDuration_s, "100000 s");
  }
  run::StudyMotion m = record.empty()
                           ? run::synthetic_study_motion(seed, pga_g, step_s,
                                                         duration_s ? *duration_s : run::kSyntheticSimDuration_s)
                           : run::load_study_motion(record, pga_g, step_s, duration_s ? *duration_s : 0.0);
  py::dict d;
  d["name"] = m.name;
  d["source"] = m.source;
  d["synthetic"] = m.synthetic;
  d["scale_factor"] = m.scale_factor;
  d["pga_m_s2"] = m.pga_m_s2;
  d["accel_m_s2"] = owned_array(std::move(m.accel_m_s2));
  return d;
}

}  // namespace

void add_objects(py::module_& m) {
  m.def("_read_building", [](const std::string& path) { return building_info(structure::read_building_file(path)); },
        py::arg("path"));
  m.def("_parse_building",
        [](const std::string& text, const std::string& origin) {
          return building_info(structure::parse_building_toml(text, origin));
        },
        py::arg("text"), py::arg("origin"));
  m.def("_read_damper", [](const std::string& path) { return damper_info(damper::read_damper_file(path)); },
        py::arg("path"));
  m.def("_parse_damper",
        [](const std::string& text, const std::string& origin) {
          return damper_info(damper::parse_damper_toml(text, origin));
        },
        py::arg("text"), py::arg("origin"));
  m.def("_read_fluid", [](const std::string& path) { return fluid_info(fluid::read_fluid_file(path)); },
        py::arg("path"));
  m.def("_parse_fluid",
        [](const std::string& text, const std::string& origin) {
          return fluid_info(fluid::parse_fluid_toml(text, origin));
        },
        py::arg("text"), py::arg("origin"));
  m.def("_read_record",
        [](const std::string& path) {
          excitation::GroundMotion g = excitation::read_ground_motion(path);
          return py::make_tuple(g.name, g.dt_s, owned_array(std::move(g.accel_m_s2)));
        },
        py::arg("path"));
  m.def("_parse_record_csv",
        [](const std::string& text, const std::string& origin, const std::string& name) {
          const excitation::GroundMotion g = excitation::parse_ground_motion_csv(text, origin, name);
          return py::make_tuple(g.dt_s, g.accel_m_s2.size());
        },
        py::arg("text"), py::arg("origin"), py::arg("name"));
  m.def("_motion", &motion, py::arg("record"), py::arg("pga_g"), py::arg("step_s"), py::arg("duration_s"),
        py::arg("seed"));
}

}  // namespace mrd::python
