#pragma once
/// The building file (TOML): a planar shear building, its isolators and its
/// dampers (building_params.hpp). SI units; every key names its unit.
///
/// <pre>
///   [building]          name (required, 1-100 bytes, no control characters)
///                       base = "isolated" (default) | "fixed"
///                       mass_kg, stiffness_n_m: N numbers each, DOF / element 0 first
///                       damping_n_s_m (N numbers) or [building.rayleigh]: exactly one of the two
///                       or, for a frame that is not a shear chain (a condensed frame):
///                       stiffness_matrix_n_m (N rows of N, symmetric, positive definite) instead of
///                       stiffness_n_m, damping_matrix_n_s_m (N rows of N, symmetric, positive
///                       semi-definite) instead of the two damping forms; no isolators with it
///   [building.rayleigh] ratio (0 < ratio < 1), modes = [i, j] (two different modes in 1..N)
///   [[isolator]]        kind = "lead_rubber": count, characteristic_strength_n,
///                         post_yield_stiffness_n_m, yield_displacement_m,
///                         [exponent = 2], [displacement_capacity_m]
///                       kind = "friction_pendulum": count, radius_m, friction_slow,
///                         friction_fast, rate_s_per_m, yield_displacement_m,
///                         [exponent = 2], [weight_n], [displacement_capacity_m]
///   [[damper]]          element (0..N-1), [count = 1]; none given: one damper at element 0
/// </pre>
///
/// With [building.rayleigh] the element dashpots are not used and read as N
/// zeros. The reader never warns: a value is accepted or refused, and the
/// bounds of every refusal (with their reasons) are in building_file.cpp.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "host_sim/structure/building_params.hpp"

namespace mrd::structure {

/// The largest building file read_building_file accepts: 1 MiB (200 DOFs of
/// three arrays take about 20 kB; the rest is room for comments).
inline constexpr std::size_t kMaxBuildingFileBytes = std::size_t{1} << 20;

/// Parses the text of a building file; `origin` names it in messages.
/// Throws io::UsageError "<origin>:<line>: <field>: <what was expected, what
/// was found>" for a TOML syntax error (without the field), an unknown table
/// or key, a missing key, a wrong type, a value out of its physical range,
/// inconsistent array lengths, a contradiction between keys (both damping
/// forms, isolators under a fixed base, two [[damper]] tables for one
/// element, ...) or a building without a restoring force.
[[nodiscard]] BuildingParams parse_building_toml(std::string_view text, const std::string& origin);

/// Reads and parses the building file `path` (a regular file of at most
/// kMaxBuildingFileBytes: FIFOs, folders and larger files are refused).
/// Throws io::UsageError.
[[nodiscard]] BuildingParams read_building_file(const std::filesystem::path& path);

/// The text of a building file that parse_building_toml reads back to the
/// same values (numbers in the shortest form that reads back exactly).
/// Throws std::invalid_argument for a building without a damper, which the
/// format cannot express.
[[nodiscard]] std::string building_toml(const BuildingParams& b);

}  // namespace mrd::structure
