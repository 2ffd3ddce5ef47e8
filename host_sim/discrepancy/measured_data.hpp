#pragma once
/// Measured damper records for the model-discrepancy workflow: CSV (and
/// MATLAB .mat) readers with units in the column names, validation, and the
/// velocity derived from the displacement when the record has none.
///
/// Column names are `<quantity>_<unit>`. Quantities the workflow uses:
/// <pre>
///   time          s, ms
///   displacement  m, mm, cm, in          actuator LVDT (§3.2)
///   velocity      m_s, mm_s, cm_s, in_s  optional; derived when absent
///   current_cmd   A, mA                  commanded coil current (`current_A` accepted too)
///   current       A, mA                  optional beside current_cmd: the measured coil current
///   force         N, kN, kip, lbf        load cell, sign of Eq. 4.1
/// </pre>
/// Units are matched without regard to case and converted to SI. Other
/// columns are kept as they are (name and values, unconverted) when their
/// name ends in a unit this reader knows (`temp_top_degC`, `current_meas_A`).

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace mrd::discrepancy {

/// A column kept from the input without interpretation.
struct ExtraColumn {
  std::string name;
  std::vector<double> values;
};

/// One measured record, SI units, time strictly increasing.
struct MeasuredData {
  std::string source;                  ///< file name (for messages and reports)
  std::vector<double> time_s;
  std::vector<double> displacement_m;  ///< actuator displacement
  std::vector<double> velocity_m_s;    ///< measured velocity; empty when the record had none
  std::vector<double> current_cmd_a;   ///< commanded coil current
  /// Measured coil current (a `current` column beside `current_cmd`; §3's
  /// current sensor); empty when the record has none. The model's coil
  /// current then follows it (DamperModel, damper_model.hpp).
  std::vector<double> current_a;
  std::vector<double> force_n;         ///< load-cell force, positive resisting positive velocity
  std::vector<ExtraColumn> extra;

  [[nodiscard]] std::size_t size() const noexcept { return time_s.size(); }
  [[nodiscard]] double duration_s() const noexcept { return time_s.empty() ? 0.0 : time_s.back() - time_s.front(); }
};

/// Shortest record the workflow accepts.
inline constexpr std::size_t kMinSamples = 200;
inline constexpr double kMinDuration_s = 1.0;
/// Slowest sampling accepted: the median step must not exceed this (50 Hz),
/// and no single step may exceed kMaxStep_s.
inline constexpr double kMaxMedianStep_s = 0.02;
inline constexpr double kMaxStep_s = 0.1;

/// Largest measured file read, bytes (an hour at 1 kHz with ten columns is ~400 MiB of CSV).
inline constexpr std::size_t kMaxMeasuredFileBytes = std::size_t{1} << 30;
/// Magnitudes beyond any damper test: a record holding one is refused.
inline constexpr double kMaxMeasuredForce_n = 1e8;
inline constexpr double kMaxMeasuredDisplacement_m = 10.0;
inline constexpr double kMaxMeasuredVelocity_m_s = 100.0;
inline constexpr double kMaxMeasuredCurrent_a = 1000.0;

/// Parses CSV text. `label` names the source in errors, which read
/// `label:LINE: column 'NAME': what is wrong` (line 1 is the header; `#`
/// comment lines and blank lines count as lines and are skipped). Throws
/// io::UsageError for a missing or repeated column, an unknown unit, a
/// field that is not a finite number, a wrong field count, time that does not
/// increase, a record that is too short or too coarsely sampled, a force,
/// displacement, velocity or current beyond the kMaxMeasured* limits, and a
/// force or displacement that never changes (constant or all zero).
[[nodiscard]] MeasuredData parse_measured_csv(std::string_view text, const std::string& label);

/// Reads a CSV file, or a MATLAB .mat file (by extension, `.mat`) whose
/// variables are vectors named like the CSV columns (`time_s`, `force_kN`, …).
/// Errors for .mat name the variable and, for a bad value, its 1-based index.
/// Only a regular file of at most kMaxMeasuredFileBytes is read; a .mat file
/// must hold every byte its variables declare (a truncated file is refused,
/// naming the variable cut short). Throws io::UsageError.
[[nodiscard]] MeasuredData read_measured(const std::filesystem::path& path);

/// Writes `data` to a MATLAB v5 .mat file with one double vector per column
/// (`time_s`, `displacement_m`, [`velocity_m_s`,] `current_cmd_A`, [`current_A`,]
/// `force_N`, extras). Throws io::UsageError when the file cannot be written.
void write_measured_mat(const MeasuredData& data, const std::filesystem::path& path);

/// CSV text of `data` with SI column names: time_s, displacement_m,
/// [velocity_m_s,] current_cmd_A, [current_A,] force_N, then the extra columns.
[[nodiscard]] std::string measured_to_csv(const MeasuredData& data);

/// Velocity and smoothed displacement by a local quartic least-squares fit
/// (a Savitzky–Golay filter that also works on non-uniform time) over the
/// samples within ±half_window_s of each sample; at least three neighbours on
/// each side are used where the record has them.
///
/// Why quartic over ±75 ms: with 10 µm of LVDT noise at 1 kHz it gives
/// 0.05 mm/s of velocity noise (a quadratic fit over ±20 ms: 0.13 mm/s, and
/// 1 % low at 2.5 Hz). That matters in the 10 mm/s transition band of
/// Eq. 4.4, where the force rises by up to 14 kN per mm/s. The quartic fit's
/// gain stays within 0.3 % of 1 up to 2.5 Hz. Faster records get a shorter
/// window (smoothing_half_window_for, motion_timescale.hpp); model_input()
/// chooses it.
struct SmoothedMotion {
  std::vector<double> displacement_m;
  std::vector<double> velocity_m_s;
};
inline constexpr std::size_t kSmoothingDegree = 4;
inline constexpr double kDefaultSmoothingHalfWindow_s = 0.075;
[[nodiscard]] SmoothedMotion smooth_motion(const std::vector<double>& time_s, const std::vector<double>& displacement_m,
                                           double half_window_s = kDefaultSmoothingHalfWindow_s);

}  // namespace mrd::discrepancy
