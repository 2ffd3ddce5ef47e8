#pragma once
/// The fluid file of `--fluid FILE`: an MR fluid's settling quantities
/// (Table 5.3, Eq. 5.1–5.4) and its participant-ratio coefficients (Table
/// 5.6, Eq. 5.6–5.8). README "Your damper and fluid".
///
/// <pre>
///   [fluid]              name, source (where the numbers come from)
///                        particle_diameter_m, solid_density_kg_m3, liquid_density_kg_m3,
///                        viscosity_pa_s, solid_fraction, hindered_exponent        Table 5.3
///                        max_settling_time_s (optional: a measured maximum settling time
///                        that replaces Eq. 5.4)
///   [participant_ratio]  a_initial, b_initial, c_initial, a_final, b_final, c_final,
///                        a_rise, b_rise, c_rise                                   Table 5.6
/// </pre>
/// The cylinder the fluid settles in (bore, shaft, length, volume; Eq. 5.3) is
/// the damper's (host_sim/damper), and so are the flow area and volume unit of
/// ∫Q dt (Eq. 5.9): the fluid gives Table 5.6's nine coefficients only.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "mrd/physics/participant_ratio.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::fluid {

/// Largest fluid file read, bytes: a file is well under 2 kB.
inline constexpr std::size_t kMaxFluidFileBytes = std::size_t{1} << 20;

struct FluidFile {
  std::string name = "thesis-model-fluid";
  std::string source = "thesis Table 5.3 and 5.6 (MRX-140ND-like model fluid)";
  /// The fluid's fields of Eq. 5.1–5.4 (and measured_max_settling_time_s);
  /// its geometry fields are the thesis damper's until with_fluid puts the
  /// fluid into a damper's.
  physics::SettlingParams settling{};
  /// Table 5.6's nine coefficients (flow_area_m2 and volume_unit_m3 are the
  /// damper's: with_fluid_coefficients leaves them).
  physics::ParticipantRatioParams participant_ratio{};
  /// What the reader noticed and accepted, one sentence each (printed on
  /// stderr by the commands): a particle Reynolds number beyond Stokes'
  /// law (Eq. 5.1).
  std::vector<std::string> warnings;
};

/// The thesis's model fluid without a file: SettlingParams{} and
/// ParticipantRatioParams{} (what fluids/thesis-model-fluid.toml reads as).
[[nodiscard]] FluidFile thesis_fluid();

/// Parses a fluid file's text. Errors read `origin:LINE: table.key: what was
/// expected` and are thrown as io::UsageError: a syntax error, a missing or
/// unknown table or key, a wrong type, a non-finite number, a number outside
/// its physical range (fluid_ranges.hpp; the message states the range), a
/// solid density not above the liquid's (particles that do not sink).
[[nodiscard]] FluidFile parse_fluid_toml(const std::string& text, const std::string& origin);

/// Reads a fluid file (a regular file of at most kMaxFluidFileBytes).
[[nodiscard]] FluidFile read_fluid_file(const std::filesystem::path& path);

/// `settling` (a damper's geometry) with the fluid's fields of `f`:
/// particle diameter, densities, viscosity, solid fraction, hindered
/// exponent and the measured maximum settling time.
[[nodiscard]] physics::SettlingParams with_fluid(physics::SettlingParams settling, const FluidFile& f);

/// `pr` (a damper's) with Table 5.6's nine coefficients of `f`; its flow
/// area and volume unit are kept.
[[nodiscard]] physics::ParticipantRatioParams with_fluid_coefficients(physics::ParticipantRatioParams pr,
                                                                      const FluidFile& f);

}  // namespace mrd::fluid
