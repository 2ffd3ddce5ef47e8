#pragma once
/// Localizing a force residual: how much of the squared gap falls in each
/// regime of the test (velocity reversals, near-zero velocity, current
/// level, current transients, early or late in the record, displacement
/// extremes) and in each tenth of the record's time.

#include <span>
#include <string>
#include <vector>

#include "host_sim/discrepancy/damper_model.hpp"

namespace mrd::discrepancy {

struct RegionStat {
  std::string name;
  std::string description;
  double fraction_of_time = 0.0;    ///< share of the record's duration in the region
  double share_of_gap_before = 0.0; ///< share of ∫(F_meas − F_baseline)² dt in the region
  double share_of_gap_after = 0.0;  ///< the same for the updated model
  /// share_of_gap_before / fraction_of_time: above 1 the gap concentrates here.
  double concentration_before = 0.0;
  double rms_before_n = 0.0;  ///< RMS residual in the region, baseline, N
  double rms_after_n = 0.0;   ///< RMS residual in the region, updated model, N
  /// Mean of (F_meas − F_baseline)·sgn(F_baseline), N: positive when the
  /// baseline gives too little force in magnitude, negative when too much.
  double magnitude_bias_before_n = 0.0;
  bool concentrated = false;  ///< concentration ≥ 1.5 and at least 10 % of the gap
};

struct TimeWindowStat {
  double start_s = 0.0;
  double end_s = 0.0;
  double rms_before_n = 0.0;
  double rms_after_n = 0.0;
  double share_of_gap_before = 0.0;
};

/// Inputs of the localization, all at the record's samples.
struct ResidualTraces {
  std::span<const double> time_s;
  std::span<const double> disp_m;
  std::span<const double> vel_m_s;
  std::span<const double> current_cmd_a;
  std::span<const double> coil_current_a;  ///< Eq. 4.5 response to the command
  std::span<const double> measured_force_n;
  std::span<const double> baseline_force_n;
  std::span<const double> updated_force_n;
};

/// Regime statistics, sorted by concentration_before, largest first. Regions
/// that hold no sample are left out. `v_tf_m_s` is the transition velocity of
/// Eq. 4.4 (the near-zero band).
[[nodiscard]] std::vector<RegionStat> localize_regions(const ResidualTraces& t, double v_tf_m_s);

/// The record cut into `count` windows of equal duration.
[[nodiscard]] std::vector<TimeWindowStat> localize_time(const ResidualTraces& t, std::size_t count = 10);

}  // namespace mrd::discrepancy
