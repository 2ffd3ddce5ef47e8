#pragma once
/// Plausibility of measured records: values probably written in another unit,
/// or records of another device mixed into one calibration. They are warned
/// about, not refused (the reader refuses only what no damper test can hold,
/// kMaxMeasured*, measured_data.hpp): `mrd calibrate` and `mrd discrepancy`
/// print them ("mrd <command>: warning: ...") and list them in summary.json's
/// `warnings`.
///
/// Thresholds, each with its physical reason:
/// <pre>
///   displacement half range  > 1 m    beyond any damper's half stroke (kMaxHalfStroke_m); millimetres
///                                     in a _m column put a 5 mm test at 5 m
///   peak velocity            > 10 m/s beyond any damper (kMaxDamperVelocity_m_s); mm/s in a _m_s column
///                                     put 0.1 m/s at 100 m/s
///   current (command, coil)  > 20 A   eight times the thesis drive's 2.5 A rating (§3.1); MR coils are
///                                     driven at a few amperes; mA in an _A column put 0.5 A at 500 A
///   peak forces of two records        more than 10 times beyond what their currents and velocities
///                                     allow one damper (below)
/// </pre>
/// One damper's peak force at a held current is about Y(I) + C(I)|v|, and
/// both laws are concave in I with Y(0), C(0) ≥ 0 (Eq. 4.2-4.3), so
/// Y(kI) ≤ k Y(I) for k ≥ 1: between two records its peak force grows at most
/// by the ratio of their currents times the ratio of their peak velocities.
/// Two records whose peak forces are more than kForceScaleSpread times beyond
/// that bound (two dampers 250 times apart at the same current and velocity,
/// or kN in an _N column) are warned about. A record without field (below
/// kNoFieldCurrent_a) is compared only with another without field: the field
/// raises the thesis damper's yield force 41 times (Table 4.1, 4.1 to 170 kN),
/// more than any bound from the currents.

#include <span>
#include <string>
#include <vector>

#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/physical_ranges.hpp"

namespace mrd::discrepancy {

inline constexpr double kPlausibleHalfRange_m = kMaxHalfStroke_m;
inline constexpr double kPlausibleVelocity_m_s = kMaxDamperVelocity_m_s;
inline constexpr double kPlausibleCurrent_a = 20.0;
inline constexpr double kForceScaleSpread = 10.0;
/// Below this current a coil's field is none: 10 mA is 0.4 % of the thesis
/// drive's rating, within the offset of any current drive.
inline constexpr double kNoFieldCurrent_a = 0.01;

/// What one record reaches.
struct RecordReach {
  std::string source;
  double half_range_m = 0.0;      ///< of the smoothed displacement
  double velocity_max_m_s = 0.0;  ///< largest |v|, measured or derived (model_input)
  bool velocity_derived = false;
  double current_cmd_max_a = 0.0;   ///< largest |commanded current|
  double current_meas_max_a = 0.0;  ///< largest |measured coil current| (0 without one)
  double force_peak_n = 0.0;        ///< largest |F|
};

[[nodiscard]] RecordReach record_reach(const MeasuredData& data,
                                       double smoothing_half_window_s = kDefaultSmoothingHalfWindow_s);

/// Warnings about one record's values: a half range, velocity or current
/// beyond the thresholds above. A derived velocity beyond its threshold is
/// not warned about when the half range already is (the same cause).
[[nodiscard]] std::vector<std::string> unit_warnings(const RecordReach& r);

/// At most one warning: the pair of records whose peak forces lie furthest
/// beyond what their currents and velocities allow one damper, when that is
/// more than kForceScaleSpread.
[[nodiscard]] std::vector<std::string> force_scale_warnings(std::span<const RecordReach> records);

/// unit_warnings of every record, then force_scale_warnings of them together
/// (the records of one calibration, or the one record of a discrepancy run).
[[nodiscard]] std::vector<std::string> plausibility_warnings(std::span<const RecordReach> records);
[[nodiscard]] std::vector<std::string> plausibility_warnings(
    std::span<const MeasuredData> records, double smoothing_half_window_s = kDefaultSmoothingHalfWindow_s);

}  // namespace mrd::discrepancy
