#pragma once
/// The three sine tests of Table 5.1 run through the model, next to what
/// Table 5.2 (a) measured.

#include <vector>

#include "host_sim/run/sine_rig.hpp"

namespace mrd::run {

/// One case of Table 5.1: the test and measurements, and what the model gave.
struct ThesisSineResult {
  ThesisSineCase thesis;
  SineMetrics model;
};

/// Runs every case of thesis_sine_cases() with the default damper and
/// settling parameters, in the table's order.
std::vector<ThesisSineResult> run_thesis_sine_cases();

}  // namespace mrd::run
