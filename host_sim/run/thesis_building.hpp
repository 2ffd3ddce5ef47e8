#pragma once
/// Whether a building is the thesis building (§6.1, Table 6.1), whatever its
/// name. The thesis's tables (sweep.csv, the study's report) keep exactly
/// their columns and words for it, so that a run of the thesis building from
/// its file (buildings/thesis-6dof.toml) writes the same bytes as a run
/// without a building file; any other building adds its own columns.

#include "host_sim/structure/building_params.hpp"

namespace mrd::run {

/// True when `b` has the thesis building's masses, elements, damping and
/// single damper on element 0, and no isolators (BuildingParams' defaults).
[[nodiscard]] inline bool is_thesis_building(const structure::BuildingParams& b) {
  const structure::BuildingParams thesis;
  return b.base == thesis.base && b.mass_kg == thesis.mass_kg &&
         b.story_stiffness_n_m == thesis.story_stiffness_n_m &&
         b.story_damping_n_s_m == thesis.story_damping_n_s_m && !b.rayleigh.has_value() && b.isolators.empty() &&
         b.dampers.size() == 1 && b.dampers.front().element == 0 && b.dampers.front().count == 1;
}

}  // namespace mrd::run
