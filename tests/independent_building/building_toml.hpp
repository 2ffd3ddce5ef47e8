#pragma once
/// Reads a building file (TOML), the format `mrd --building FILE` reads:
///
///   [building]  name, base ("isolated" default | "fixed"), mass_kg = [...],
///               stiffness_n_m = [...], damping_n_s_m = [...] or
///               [building.rayleigh] ratio, modes = [a, b]
///   [[isolator]] kind = "lead_rubber": count, characteristic_strength_n,
///               post_yield_stiffness_n_m, yield_displacement_m, exponent (2)
///   [[isolator]] kind = "friction_pendulum": count, radius_m, friction_slow,
///               friction_fast, rate_s_per_m, yield_displacement_m,
///               exponent (2), weight_n (0: the building's weight / count)
///   [[damper]]  element, count (1)
///
/// displacement_capacity_m of a bearing is accepted and ignored (it only
/// warns). Written with toml++ for the syntax; every meaning here is this
/// folder's own reading of the format. Errors throw std::runtime_error
/// "FILE:LINE: FIELD: problem".

#include <filesystem>
#include <string>

#include "building_model.hpp"

namespace ibuild {

Building read_building_file(const std::filesystem::path& file);

/// The same from TOML text; `origin` names it in errors.
Building parse_building(const std::string& text, const std::string& origin);

}  // namespace ibuild
