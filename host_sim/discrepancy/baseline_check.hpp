#pragma once
/// Whether a record lies inside what the baseline describes. A record whose
/// force scale, velocity or current is far outside the baseline's validity
/// range is not judged against it: no catalogue effect may be fitted to hide
/// a baseline that describes another damper.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "host_sim/discrepancy/baseline.hpp"

namespace mrd::discrepancy {

/// Limits of the check: a least-squares force ratio F_meas ≈ s·F_baseline
/// above kMaxForceRatio (no catalogue effect adds force beyond an asymmetry
/// of 1.5 and an offset), or below half the ratio a fully settled fluid
/// gives on the same record (SQ = 1, PR from a_PR(1) ≈ 0.1 recovering with
/// the record's displaced volume, Eq. 5.6–5.9; the half leaves room for a
/// fade or free play on top).
inline constexpr double kMaxForceRatio = 4.0;
inline constexpr double kSettledRatioMargin = 0.5;
/// Velocity beyond twice the range covered: the viscous law is linear in v
/// and carries a twofold extrapolation; further, the record tests the law
/// rather than the damper. Current beyond 1.5 times the range (plus the
/// slack below): the current laws saturate, and a law fitted up to I
/// says little of its shape much above I.
inline constexpr double kVelocityRangeFactor = 2.0;
inline constexpr double kRangeFactor = 1.5;
inline constexpr double kCurrentSlack_a = 0.05;

/// A record's half range or dominant frequency more than this factor outside
/// the range the baseline was calibrated on is named as outside its
/// coverage. The margin is that between a test's nominal and achieved stroke
/// (the laboratory's "2 mm" and "5 mm" records move ±1.645 and ±4.62 mm, up
/// to 18 % less): a later record planned like a calibration record stays
/// inside. A record beyond it is judged, but the baseline's expected gap was
/// not measured there.
inline constexpr double kCoverageFactor = 1.25;

struct BaselineCheck {
  bool mismatch = false;
  std::vector<std::string> reasons;  ///< one sentence each, with the numbers
  bool force_scale_outside = false;  ///< the mismatch is (also) one of force scale, not only of range
  double force_ratio = 1.0;          ///< least-squares s in F_meas ≈ s·F_baseline
  double min_force_ratio = 0.0;      ///< the lower limit it was checked against
  double velocity_max_m_s = 0.0;     ///< of the record
  double current_min_a = 0.0;
  double current_max_a = 0.0;
  double amplitude_m = 0.0;                 ///< the record's displacement half range
  double frequency_hz = 0.0;                ///< its dominant frequency (0: fewer than two crossings)
  std::vector<std::string> outside_coverage;  ///< coverage_notes() and coil_notes(): one sentence each
};

/// Where a record's half range `amplitude_m` and dominant frequency
/// `frequency_hz` lie beyond kCoverageFactor times the amplitudes and
/// frequencies `range` covers, one sentence each with the numbers; empty
/// inside, or when the range does not state them (0, as the thesis
/// baseline's) or the frequency is unknown (0). Not a mismatch: the force
/// scale, velocity and current decide that.
[[nodiscard]] std::vector<std::string> coverage_notes(const ValidityRange& range, double amplitude_m,
                                                      double frequency_hz, double expected_gap);

/// A command change smaller than this share of the record's largest |I|
/// (or than kCommandResolution_a) is the drive's or the logger's resolution,
/// not a change of current.
inline constexpr double kCommandChangeShare = 0.02;
inline constexpr double kCommandResolution_a = 1e-3;

/// The changes of the commanded current in a record: how many samples step
/// by more than the resolution above, and the range. A record with none
/// holds its current (a characterization test).
struct CommandChanges {
  std::size_t steps = 0;
  double min_a = 0.0;
  double max_a = 0.0;
};
[[nodiscard]] CommandChanges command_changes(std::span<const double> current_cmd_a);

/// When the record's commanded current changes but the baseline's coil
/// dynamics were not identified (Baseline::coil_identified), one sentence
/// that says so with the numbers: the force after each change follows an
/// assumed coil (with a measured coil current `current_meas_a`, non-empty,
/// its assumed slow branch). Empty otherwise.
[[nodiscard]] std::vector<std::string> coil_notes(const Baseline& baseline, std::span<const double> current_cmd_a,
                                                  std::span<const double> current_meas_a = {});

/// `settled_force_n`: the baseline with idle_settling at SQ = 1 on the record.
[[nodiscard]] BaselineCheck check_baseline(const Baseline& baseline, std::span<const double> measured_force_n,
                                           std::span<const double> baseline_force_n,
                                           std::span<const double> settled_force_n,
                                           std::span<const double> vel_m_s, std::span<const double> current_cmd_a);

}  // namespace mrd::discrepancy
