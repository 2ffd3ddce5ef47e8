#pragma once
/// Earthquake ground-motion records: reading, PGA scaling and resampling.
///
/// A record is a uniformly sampled horizontal ground acceleration in m/s²
/// (thesis §6, Tables 6.2–6.3). Two file formats are read:
///
/// * the shared CSV format (`shared/ground_motions/README.md`): a header line
///   `time_s,accel_m_s2`, then one `t,a` row per sample, t in s, a in m/s²;
/// * PEER NGA `.AT2` files: four header lines, the fourth giving the number
///   of points and the step (`NPTS=   5590, DT=   .0050 SEC` or
///   `2689    0.0200    NPTS, DT`), then the accelerations in g, several per
///   line, Fortran style (`.1234567E-02`). They are converted to m/s² with
///   standard gravity, 9.80665 m/s².
///
/// Every input problem throws `mrd::io::UsageError` with a one-line
/// message of the form `<file>:<line>: field '<column>': <what was expected>`
/// (or `<file>: <problem>` when no single line is at fault).

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace mrd::excitation {

/// A uniformly sampled ground acceleration. Sample i is at time i·dt_s from
/// the start of the record (a file's own start time is not kept).
struct GroundMotion {
  std::string name;    ///< short label, e.g. the file stem `hachinohe_ns`
  std::string source;  ///< where it came from: the file path, or the generator and its parameters
  double dt_s = 0.0;   ///< sample step, s
  std::vector<double> accel_m_s2;  ///< ground acceleration, m/s²

  /// (N − 1)·dt, s; 0 for fewer than two samples.
  double duration_s() const noexcept;
  /// Peak ground acceleration max |a|, m/s²; 0 for an empty record.
  double pga_m_s2() const noexcept;
  /// Index of the first sample with |a| = PGA; 0 for an empty record.
  std::size_t pga_index() const noexcept;
  /// Time of that sample from the start of the record, s.
  double pga_time_s() const noexcept;
};

/// Largest ground-motion file read, bytes (a 1 kHz hour-long CSV is ~100 MiB).
inline constexpr std::size_t kMaxGroundMotionFileBytes = std::size_t{256} << 20;
/// Largest |acceleration| a record may hold, m/s² (about 100 g; the
/// strongest recorded ground motions stay below 5 g).
inline constexpr double kMaxRecordAccel_m_s2 = 1000.0;
/// Sample steps a record may have, s.
inline constexpr double kMinRecordStep_s = 1e-6;
inline constexpr double kMaxRecordStep_s = 1.0;

/// Parses the shared CSV format from `text` (see read_ground_motion_csv);
/// `file` names the source in messages, `name` becomes the record's name.
GroundMotion parse_ground_motion_csv(std::string_view text, const std::string& file, const std::string& name);

/// Parses a PEER NGA `.AT2` file's text (see read_peer_at2).
GroundMotion parse_peer_at2(std::string_view text, const std::string& file, const std::string& name);

/// Reads the shared CSV format (see the file comment). Tolerates a UTF-8
/// byte-order mark, a trailing CR on each line (CRLF files), whitespace
/// around fields and blank lines. Requires at least two samples and times that
/// increase with a uniform step: every step must equal the first one within
/// 1e-6 of it plus 1e-9 s. The stored step is (t_last − t_first)/(N − 1).
/// Both readers accept only a regular file of at most
/// kMaxGroundMotionFileBytes, a step within [kMinRecordStep_s,
/// kMaxRecordStep_s] and samples within ±kMaxRecordAccel_m_s2.
/// Throws io::UsageError on any problem.
GroundMotion read_ground_motion_csv(const std::filesystem::path& path);

/// Reads a PEER NGA `.AT2` acceleration file (values in g) and converts it
/// to m/s². The count of values must equal NPTS. Throws io::UsageError on
/// any problem.
GroundMotion read_peer_at2(const std::filesystem::path& path);

/// Picks the reader by extension, case-insensitive: `.csv` or `.at2`.
/// Throws io::UsageError for anything else.
GroundMotion read_ground_motion(const std::filesystem::path& path);

/// Factor that brings the record's PGA to `target_pga_m_s2`. Throws
/// io::UsageError if the record has zero PGA or the target is not a
/// positive finite number.
double scale_factor_for_pga(const GroundMotion& motion, double target_pga_m_s2);

/// Copy of `motion` with every sample multiplied by
/// scale_factor_for_pga(motion, target). The result's PGA is exactly the
/// target (the peak sample is set to ±target and rounding can push no other
/// sample above it). Name and source are kept.
GroundMotion scaled_to_pga(const GroundMotion& motion, double target_pga_m_s2);

/// Linear interpolation of a record at arbitrary times. Before the first
/// sample (t < 0) and after the last one (t > duration) the acceleration is 0:
/// the ground is at rest outside the record.
class GroundMotionSampler {
 public:
  /// Keeps a copy of the samples. Throws io::UsageError if the record is
  /// empty or its step is not a positive finite number.
  explicit GroundMotionSampler(const GroundMotion& motion);

  /// Ground acceleration at `t_s` seconds from the start of the record, m/s².
  double accel_at(double t_s) const noexcept;

  double dt_s() const noexcept { return dt_s_; }
  double duration_s() const noexcept;

 private:
  double dt_s_;
  std::vector<double> accel_m_s2_;
};

/// The record at times k·dt_new_s, k = 0, 1, …, for k·dt_new_s up to the
/// record's duration (within 1e-9 of a step), by linear interpolation. Times
/// that fall on an original sample (within 1e-9 of a step) return that
/// sample exactly. Throws io::UsageError if dt_new_s is not a positive
/// finite number or the result would exceed 1e9 samples.
std::vector<double> resample_linear(const GroundMotion& motion, double dt_new_s);

/// As above, but the result covers `duration_s` (k·dt_new_s ≤ duration_s),
/// padded with zeros after the end of the record, or cut short before it.
std::vector<double> resample_linear(const GroundMotion& motion, double dt_new_s, double duration_s);

}  // namespace mrd::excitation
