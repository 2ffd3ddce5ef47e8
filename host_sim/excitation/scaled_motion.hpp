#pragma once
/// A ground-motion record as a run uses it: read from its file, scaled to a
/// target PGA (Table 6.3) and resampled to the run's step.

#include <filesystem>
#include <string>
#include <vector>

namespace mrd::excitation {

struct ScaledMotion {
  std::string name;                ///< the record's name, e.g. the file stem `hachinohe_ns`
  std::string source;              ///< the file it was read from
  double scale_factor = 1.0;       ///< applied to the record to reach the PGA
  double pga_m_s2 = 0.0;           ///< after scaling, m/s²
  std::vector<double> accel_m_s2;  ///< ground acceleration at the run's step, m/s²
};

/// Reads `path` (CSV or PEER .AT2, see read_ground_motion), scales it to
/// `pga_g` (in g, standard gravity) and resamples it to `step_s`, covering
/// `duration_s` when > 0 (zero-padded after the record's end, or cut short),
/// else the whole record. Throws io::UsageError naming the file, line and
/// field for a bad record or a bad step.
ScaledMotion load_scaled_motion(const std::filesystem::path& path, double pga_g, double step_s,
                                double duration_s = 0.0);

}  // namespace mrd::excitation
