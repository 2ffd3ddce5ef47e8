#pragma once
/// Ground motions as the studies use them: the four records of Table 6.2,
/// found in the shared data folder, scaled to a target PGA (Table 6.3) and
/// resampled to the run's step; or a synthetic motion when no record is at
/// hand.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mrd::run {

/// Table 6.3: every record scaled to 0.1127 g.
inline constexpr double kThesisPga_g = 0.1127;

struct StudyMotion {
  std::string name;        ///< e.g. "hachinohe_ns" or "synthetic-1"
  std::string label;       ///< e.g. "Case a: Hachinohe"
  std::string source;      ///< file path or generator description
  bool synthetic = false;
  double scale_factor = 1.0;              ///< applied to the record to reach the PGA
  double pga_m_s2 = 0.0;                  ///< after scaling
  std::vector<double> accel_m_s2;         ///< at the run's step
};

/// The folder holding the four shared records, if any: $MRD_SHARED_DIR/ground_motions,
/// then ../shared/ground_motions from the current folder, then the one the
/// build was configured with.
std::optional<std::filesystem::path> find_shared_ground_motions();

/// Loads `path` (CSV or PEER AT2), scales it to `pga_g` and resamples it to
/// `step_s`, covering `duration_s` when > 0 (zero-padded), else the record
/// (excitation::load_scaled_motion), labelled as Table 6.2 names it.
StudyMotion load_study_motion(const std::filesystem::path& path, double pga_g, double step_s,
                              double duration_s = 0.0);

/// A synthetic stationary-filtered, enveloped motion (see
/// excitation/synthetic_motion.hpp) scaled to `pga_g`.
StudyMotion synthetic_study_motion(std::uint64_t seed, double pga_g, double step_s, double duration_s);

/// The four records of Table 6.2 (cases a–d) at `pga_g`; when the shared
/// folder is absent, four synthetic motions (seeds 1–4, 40 s) instead, with
/// `synthetic` set so reports say so.
std::vector<StudyMotion> thesis_study_motions(double pga_g, double step_s);

}  // namespace mrd::run
