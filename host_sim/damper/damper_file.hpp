#pragma once
/// The damper file of `--damper FILE`: the damper.toml `mrd calibrate`
/// writes (host_sim/discrepancy/baseline_file.hpp), or one written by hand,
/// read into what a closed loop simulates (README "Your damper and fluid").
///
/// The baseline's current laws map onto Eq. 4.2–4.3's constants one for one:
/// CurrentLaw's value(I, PR) = PR·limit + (at_zero − PR·limit)·exp(−rate |I|)
/// is coulomb_force_n's b + (f_c,a − b)·exp(−f_c,c |I|) with b = PR·f_c,b, so
/// <pre>
///   [yield_n]       at_zero → bingham.fc_a_n, limit → fc_b_n, rate_per_a → fc_c_per_a
///   [viscous_ns_m]  at_zero → bingham.c0_a_ns_m, limit → c0_b_ns_m, rate_per_a → c0_c_per_a
///   [bingham]       v_tf_m_s → bingham.v_tf_m_s; transition linear → ForceLaw::kBingham,
///                   tanh → ForceLaw::kBinghamTanh; transition_time_s, stiffness_n_m,
///                   viscous_exponent, viscous_ref_m_s and series_compliance_m_per_n →
///                   MrDamperParams::shape
///   current_exponent of [yield_n] and [viscous_ns_m] → shape's current exponents
///   [lost_motion]   m_per_n, share, band_m_s → shape's lost motion
///   [bouc_wen]      → ForceLaw::kBoucWen with yield_disp_m, stiffness_n_m
///   [spencer]       → ForceLaw::kSpencer with its model and current laws (SI, as the file
///                   holds them); [coil] with equal time constants τ is the paper's
///                   first-order filter, η = 1/τ
///   [coil]          the time constants and weights of Eq. 4.5; the circuit (R, L(i)) for the
///                   hardware plant; R, thermal_resistance_k_w and thermal_time_constant_s →
///                   coil_heat (absent: the thesis coil's assumptions at this coil's rating,
///                   mrd/physics/coil_heat.hpp, with a warning)
///   [participant_ratio]  Table 5.6's coefficients, flow_area_m2, volume_unit_m3
///   [rating]        MrDamperParams::rating; absent: derived from [validity] (the largest
///                   |current|, force_peak_n, amplitude_max_m as the half stroke,
///                   velocity_max_m_s), with a warning
///   [geometry]      the cylinder of Eq. 5.3; absent: the thesis damper's, with a warning
/// </pre>
/// (the thesis's Table 4.1 in baseline.hpp's thesis_baseline(): f_c 4.1 kN at
/// 0 A → 170 kN at 0.7 1/A, the same three numbers as physics::BinghamParams).
/// What a baseline holds and the closed loop does not simulate (the test
/// rig's force-channel lag) is named in a warning, as are a coil or
/// participant ratio not identified from records. The transition time and
/// the lost motion are simulated causally (physics/mr_damper.hpp: the
/// damper's acceleration over the last step, the engagement averaged over
/// the last 6 ms), where the calibration averages around each sample.

#include <filesystem>
#include <string>
#include <vector>

#include "host_sim/discrepancy/baseline_file.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::damper {

/// A damper as the closed loop simulates it.
struct DamperFile {
  std::string name = "thesis-200kn";  ///< [model] name
  physics::MrDamperParams params{};   ///< force law, current laws, coil, participant ratio, rating
  /// The cylinder the fluid settles in: the file's [geometry], else the
  /// thesis damper's (Table 3.1, 5.4).
  discrepancy::DamperGeometry geometry{};
  discrepancy::CoilCircuit coil_circuit{};  ///< absent fields: the hardware plant's thesis coil
  bool rating_given = true;                 ///< false: params.rating was derived from [validity]
  bool geometry_given = true;               ///< false: geometry is the thesis damper's
  /// What the closed loop leaves out of the file or assumed, one sentence
  /// each (printed on stderr by the commands).
  std::vector<std::string> warnings;
  std::string origin;  ///< the file's label, for refusals after reading
  int law_line = 0;    ///< the line of [model] law (kSpencer), for require_law_for
};

/// The thesis damper's cylinder: physics::SettlingParams' defaults.
[[nodiscard]] discrepancy::DamperGeometry thesis_geometry();

/// The thesis damper, without a file: physics::MrDamperParams{} and
/// thesis_geometry() (what dampers/thesis-200kn.toml reads as).
[[nodiscard]] DamperFile thesis_damper();

/// Parses a damper file's text (parse_baseline_toml's refusals), then maps it
/// as above. io::UsageError `origin:LINE: field: ...` also when a rating must
/// be derived from [validity] and a quantity there is none (no current above
/// 0, an amplitude not stated, ...): the message asks for a [rating] table.
[[nodiscard]] DamperFile parse_damper_toml(const std::string& text, const std::string& origin);

/// Reads a damper file (a regular file of at most
/// discrepancy::kMaxBaselineFileBytes). io::UsageError when it cannot be
/// read or is invalid.
[[nodiscard]] DamperFile read_damper_file(const std::filesystem::path& path);

/// Refuses a damper whose law `command` cannot simulate: the spencer law
/// is simulated in the closed loop (sim, sine, sweep, study, fragility, whose
/// SIMD lanes step it by the scalar damper, and rths) and settle uses only the
/// cylinder; configure and schedule model the damper by its Bingham laws
/// (the control core's estimator, the board file). io::UsageError
/// "origin:LINE: model.law: ...".
void require_law_for(const DamperFile& d, const std::string& command);

/// `settling` with its geometry fields (bore, shaft, length, fluid volume)
/// replaced by `g`; the fluid's fields are left as they are.
[[nodiscard]] physics::SettlingParams with_geometry(physics::SettlingParams settling,
                                                   const discrepancy::DamperGeometry& g);

}  // namespace mrd::damper
