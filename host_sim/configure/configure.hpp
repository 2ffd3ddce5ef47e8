#pragma once
/// `mrd configure`: one building, damper and fluid turned into the board
/// file's [controller], [damper] and [fluid] tables (and the [mixing]
/// numbers that follow from the damper), every derived number with the
/// rule and the inputs that gave it, for configure.md beside the file.
///
/// The rules (README "Your damper, your fluid, your controller"):
/// - RILD (Eq. 6.1): k = the effective stiffness of the element the first
///   damper acts on (the isolation layer: its springs plus the bearings'
///   secant stiffness at the design displacement D); ω_f = the fundamental
///   mode of the building with that layer linear at k; η = 0.8 (§6.3).
/// - Forces: |F_d| ≤ 2 F_rated (the thesis: 400 kN for 200 kN); the load
///   cell's guard at 2.5 F_rated (500 kN); deadband 1 % of F_rated (2 kN).
/// - Currents (ODBDCO): I_r = I_nom = I_fallback = the rated current;
///   forcing I_od = −I_bd = min(4 I_r, the drive's command range) (the
///   thesis: 10 A for 2.5 A); band 4 % of I_r (0.1 A).
/// - Direction thresholds from the stroke sensor's noise σ_x (white noise
///   and the converter's quantization): the velocity estimate's noise
///   σ_v = σ_x (β/T) √(2/(2 − β)), β = 1 − e^{−2π f_v T}; v_on = 10 σ_v,
///   v_off = 5 σ_v (the thesis's LVDT: 5.9 and 2.9 mm/s against its 6 and 3).
/// - Guard: stroke limit 1.03 × the rated stroke (0.30 m for 0.2921 m).
/// - Estimator: the fluid (Table 5.3, 5.6 or a measured T_max) and the
///   damper's geometry and mixing area; its dead band 30 σ_x (0.1 mm).
/// - Mixing cycle: amplitude ≤ 0.26 × the stroke (the thesis's 76 mm of
///   292 mm), velocity ≤ 0.4 × the rated velocity (0.1 of 0.249 m/s).

#include <string>
#include <vector>

#include "firmware/app/board_config.hpp"
#include "host_sim/structure/building_params.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::configure {

/// The stroke sensor (the thesis rig's LVDT, §3: ±0.2921 m over 16 bit, 2 µm RMS noise).
struct StrokeSensor {
  double noise_rms_m = 2.0e-6;
  int bits = 16;  ///< over the span 2 × the damper's rated stroke
};

/// The drive's limits (the thesis rig's, §3.2: ±10 A command at 1 V/A; 15 A
/// continuous, 30 A peak; `mrd configure --drive-*` gives another drive's).
struct DriveLimits {
  double command_limit_a = 10.0;
  double continuous_limit_a = 15.0;
  double peak_limit_a = 30.0;
};

struct Inputs {
  structure::BuildingParams building{};
  std::string building_name = "thesis-6dof";
  physics::MrDamperParams damper{};
  std::string damper_name = "thesis-200kn";
  physics::SettlingParams settling{};  ///< fluid (Table 5.3) and the damper's geometry
  std::string fluid_name = "thesis-model-fluid";
  app::BoardConfig board{};            ///< the board file to configure (its other tables are kept)
  /// D for the bearings' secant stiffness, m; 0: half the damper's rated stroke.
  double design_displacement_m = 0.0;
  StrokeSensor sensor{};
  DriveLimits drive{};
  /// Where the drive's limits come from when they are not the thesis rig's:
  /// "given" (options) or "the drive file's (NAME)".
  std::string drive_source = "given";
};

/// One derived number.
struct Derived {
  std::string field;  ///< "controller.stiffness_n_m"
  double value = 0.0;
  std::string unit;
  std::string rule;  ///< how, with the inputs' values
};

struct Result {
  app::BoardConfig board;  ///< the configured board
  std::vector<Derived> derived;
  std::vector<std::string> notes;  ///< what the user should know (e.g. values kept from the thesis)
};

/// Derives the configuration. Throws io::UsageError when the control core
/// would refuse it (naming the rule and, for the fixed build, the format's
/// limit), or when the building has no damper.
Result configure(const Inputs& in);

/// configure.md: every derived number, its rule and inputs.
std::string configure_markdown(const Inputs& in, const Result& r);

}  // namespace mrd::configure
