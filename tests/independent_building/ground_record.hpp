#pragma once
/// A ground-motion record (CSV `time_s,accel_m_s2`, one header line, a
/// uniform step from t = 0) scaled to a peak ground acceleration, and its
/// value at any time by linear interpolation between the samples (0 after
/// the last one).

#include <filesystem>
#include <vector>

namespace ibuild {

struct GroundRecord {
  double step_s = 0.0;
  std::vector<double> accel_m_s2;  ///< sample k at t = k·step_s

  /// Linear interpolation at `t_s`; 0 before 0 and after the last sample.
  double at(double t_s) const;
  /// Time of the last sample, s.
  double end_s() const { return accel_m_s2.empty() ? 0.0 : step_s * static_cast<double>(accel_m_s2.size() - 1); }
};

/// Reads `file`; throws std::runtime_error naming the file and line for a
/// malformed one (non-numeric field, non-uniform or non-increasing time).
GroundRecord read_ground_record(const std::filesystem::path& file);

/// The record multiplied so that max |a| is `pga_g`·g.
GroundRecord scaled_to_pga(GroundRecord r, double pga_g);

}  // namespace ibuild
