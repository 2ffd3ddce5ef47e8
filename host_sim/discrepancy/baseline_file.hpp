#pragma once
/// `damper.toml`: a calibrated baseline (baseline.hpp) with its standard
/// errors, the records it was fitted to and its validity range, written by
/// `mrd calibrate` and read by `mrd discrepancy --baseline`; with the tables
/// a closed loop needs ([rating], [geometry]), the damper file of `--damper`
/// (host_sim/damper/damper_file.hpp).
///
/// <pre>
///   [model]          law ("bingham" | "bouc_wen" | "spencer"), name, source_records
///   [yield_n]        at_zero, limit, rate_per_a (1/A), each with _sigma; fitted = [...]   Eq. 4.2
///   [viscous_ns_m]   the same for the viscous coefficient, N·s/m                           Eq. 4.3
///   [bingham]        v_tf_m_s, v_tf_m_s_sigma                                              Eq. 4.4
///                    transition ("linear", Eq. 4.4, when absent | "tanh")
///                    transition_time_s, transition_time_s_sigma (only when the baseline has one)
///   [bouc_wen]       yield_disp_m, stiffness_n_m, each with _sigma
///   [spencer]        alpha_n_m, alpha_per_a_n_m, alpha_per_a2_n_m, c0_ns_m, c0_per_a_ns_m,
///                    c1_ns_m, c1_per_a_ns_m, gamma_per_m_pow_n, gamma_rate_per_a,
///                    beta_over_gamma, a, n, k0_n_m, k1_n_m, x0_m          Spencer et al. (1997)
///                    (physics/spencer_law.hpp; no _sigma: a calibration reports its
///                    standard errors, of α, c_0 and c_1 at the records' currents, in
///                    calibration.txt); with it no [yield_n], [viscous_ns_m] or [lost_motion]
///   [lost_motion]    m_per_n (m/N), share, each with _sigma (only when the baseline has one);
///                    band_m_s (m/s) with _sigma when the force inside the play grows over a band
///   [channels]       force_delay_s, force_delay_s_sigma
///   [coil]           tau_slow_s, tau_fast_s, weight_slow, weight_fast, identified        Eq. 4.5
///                    tau_slow_s_sigma, tau_fast_s_sigma (only when identified)
///                    resistance_ohm, inductance_1a_h, inductance_2a_h (optional: the coil's
///                    circuit, which the hardware plant uses; Table 3.1: 4.8 ohm, 5.0 H at 1 A,
///                    3.0 H at 2 A; the two inductances together or neither)
///                    thermal_resistance_k_w (with resistance_ohm), thermal_time_constant_s
///                    (optional: the coil's heating, mrd/physics/coil_heat.hpp)
///   [participant_ratio]  Table 5.6 coefficients, flow_area_m2, volume_unit_m3, identified
///   [validity]       current_min_a … frequency_max_hz, expected_gap, expected_gap_basis (optional:
///                    "calibration_records" when absent)
///   [rating]         current_a, force_n, stroke_m (± from the centre), velocity_m_s (optional:
///                    what a closed loop holds the damper to; host_sim/damper derives it from
///                    [validity] when absent)
///   [geometry]       inner_diameter_m, shaft_radius_m, fluid_length_m, fluid_volume_m3
///                    (optional: the cylinder the fluid settles in, Eq. 5.3; Table 3.1, 5.4)
///   [[fit]]          file, law, transition ("tanh", when so), transition_time, lost_motion and
///                    viscous_lost_motion (when true), gap, samples
///                    (one per record and form fitted)
/// </pre>
/// Only the table of the model's law ([bingham], [bouc_wen] or [spencer]) may be present.
/// A file written by hand may leave out what only a calibration has: the
/// standard errors (`*_sigma`, 0 when absent), `fitted` (none), `source_records`
/// (none), [channels] (no lag) and [[fit]].

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "host_sim/discrepancy/baseline.hpp"
#include "host_sim/discrepancy/calibrate.hpp"
#include "mrd/physics/mr_damper.hpp"

namespace mrd::discrepancy {

/// Fit quality of one law on one record.
struct RecordFit {
  std::string file;
  BaseLaw law = BaseLaw::bingham;
  double gap = 0.0;  ///< normalized_rms_gap at full rate, over the record's moving_span
  std::size_t samples = 0;
  bool lost_motion = false;      ///< the law with a lost motion at reversals
  bool transition_time = false;  ///< the law with a transition time
  bool tanh_transition = false;  ///< the Bingham law with the tanh transition
  bool viscous_lost_motion = false;  ///< its lost motion with a viscous force inside the play
};

/// [geometry]: the cylinder the fluid settles in, Eq. 5.3 (the fields of
/// physics::SettlingParams that are the damper's; Table 3.1, 5.4 for the
/// thesis damper).
struct DamperGeometry {
  double inner_diameter_m = 0.0;
  double shaft_radius_m = 0.0;
  double fluid_length_m = 0.0;
  double fluid_volume_m3 = 0.0;
};

/// [coil]'s optional circuit: R and L(i) at 1 A and 2 A (plant/coil.hpp),
/// and its heating (mrd/physics/coil_heat.hpp).
struct CoilCircuit {
  std::optional<double> resistance_ohm;
  std::optional<double> inductance_1a_h;
  std::optional<double> inductance_2a_h;  ///< given with inductance_1a_h, never alone
  std::optional<double> thermal_resistance_k_w;   ///< R_th, K/W; given with resistance_ohm, never alone
  std::optional<double> thermal_time_constant_s;  ///< τ = R_th C, s
};

/// Everything damper.toml holds.
struct BaselineFile {
  Baseline baseline;
  BaselineSigmas sigma;
  CurrentLawFitted yield_fitted, viscous_fitted;
  bool pr_identified = false;  ///< the coil's is Baseline::coil_identified
  std::vector<std::string> source_records;
  std::vector<RecordFit> fits;
  CoilCircuit coil_circuit;                      ///< none from a calibration
  std::optional<physics::DamperRating> rating;   ///< [rating]; none from a calibration
  std::optional<DamperGeometry> geometry;        ///< [geometry]; none from a calibration
};

/// The file's content for a calibration: its chosen fit, and every law's
/// per-record quality.
[[nodiscard]] BaselineFile baseline_file_of(const CalibrationResult& r);

/// TOML text of `f` (numbers written so that they read back exactly).
[[nodiscard]] std::string baseline_toml(const BaselineFile& f);

/// Largest damper.toml read, bytes. A file is a few kB; its [[fit]] tables
/// take about 120 bytes per record and form, so ten thousand records of ten
/// forms fit in 12 MB.
inline constexpr std::size_t kMaxBaselineFileBytes = std::size_t{16} << 20;

/// Parses TOML text. Errors read `origin:LINE: field: what was expected` and
/// are thrown as io::UsageError: a syntax error, a missing or unknown table
/// or key, a wrong type, an unknown law, a non-finite number, a number
/// outside its physical range (physical_ranges.hpp; the message states the
/// range), coil weights that do not sum to 1, a range whose minimum exceeds
/// its maximum, one coil inductance without the other or one that grows with
/// the current, a shaft as wide as the bore.
///
/// baseline_toml writes a standard error larger than its range's top as that
/// top (with a comment): such a parameter is not identified, and the file
/// reads back.
[[nodiscard]] BaselineFile parse_baseline_toml(const std::string& text, const std::string& origin);

/// Reads a damper.toml file through io::read_regular_file (a regular file of
/// at most kMaxBaselineFileBytes, opened without blocking). io::UsageError
/// when it cannot be read or is invalid.
[[nodiscard]] BaselineFile read_baseline_file(const std::filesystem::path& path);

/// Writes baseline_toml(f) to `path` atomically.
void write_baseline_file(const BaselineFile& f, const std::filesystem::path& path);

}  // namespace mrd::discrepancy
