#pragma once
/// The peaks and figures of one closed-loop run (plant::PlantSummary) as
/// named numbers, in one order: what mrd.sim's `peaks` and mrd.batch's
/// arrays hold, one name per field (the coil's figures flattened).

#include <cstdint>
#include <string>
#include <vector>

#include "host_sim/plant/plant.hpp"

namespace mrd::python {

/// The names, in the order peak_values() gives the values.
const std::vector<std::string>& peak_names();

/// plant::PlantSummary's fields in peak_names()' order (ticks as a double:
/// exact below 2^53 ticks).
std::vector<double> peak_values(const plant::PlantSummary& s);

}  // namespace mrd::python
