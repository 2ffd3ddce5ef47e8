#pragma once
/// The parts of the extension module mrd._mrd, each registered by its own
/// file (mrd_module.cpp calls them).

#include <pybind11/pybind11.h>

namespace mrd::python {

/// _batch, _lane_isa (batch_binding.cpp).
void add_batch(pybind11::module_& m);

/// _read_building, _parse_building, _read_damper, _parse_damper,
/// _read_fluid, _parse_fluid, _parse_record_csv, _motion (objects_binding.cpp).
void add_objects(pybind11::module_& m);

}  // namespace mrd::python
