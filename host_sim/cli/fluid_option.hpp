#pragma once
/// `--fluid FILE`: the MR fluid in the damper (a fluid file,
/// host_sim/fluid/fluid_file.hpp; README "Your damper and fluid"). Without
/// it, the thesis's model fluid (fluids/thesis-model-fluid.toml). And what a
/// command takes from --damper and --fluid together.

#include <CLI/CLI.hpp>

#include <string>

#include "host_sim/damper/damper_file.hpp"
#include "host_sim/fluid/fluid_file.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::cli {

/// Registers --fluid FILE on `app`.
void add_fluid_option(CLI::App& app, std::string& fluid_file);

/// The damper and the idle-time physics of --damper and --fluid.
struct DamperAndFluid {
  damper::DamperFile damper;  ///< as read (its params without the fluid)
  fluid::FluidFile fluid;     ///< as read
  /// The damper's params with, when a fluid file is given, the fluid's Table
  /// 5.6 coefficients in place of the damper file's.
  physics::MrDamperParams params{};
  /// The fluid's quantities (Table 5.3, a measured T_max) in the damper's
  /// cylinder (Eq. 5.3): what SQ comes from (Eq. 5.4–5.5).
  physics::SettlingParams settling{};
};

/// Loads both (an empty name: the thesis's), printing their warnings on
/// stderr ("mrd COMMAND: warning: FILE: ..."). io::UsageError for a bad file,
/// and when the fluid's solids would not fit in the damper's cylinder (χ·V at
/// least the annulus L·π(R² − r_s²) of Eq. 5.3).
DamperAndFluid load_damper_and_fluid(const char* command, const std::string& damper_file,
                                     const std::string& fluid_file);

/// The damper (params) is the thesis's, value for value (e.g. read from
/// dampers/thesis-200kn.toml): reports then say nothing of a damper file.
bool is_thesis_damper(const DamperAndFluid& d);
/// The idle-time physics (settling) is the thesis's model fluid in the thesis
/// damper, value for value.
bool is_thesis_settling(const DamperAndFluid& d);

}  // namespace mrd::cli
