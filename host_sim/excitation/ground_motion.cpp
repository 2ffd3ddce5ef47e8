#include "host_sim/excitation/ground_motion.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string_view>
#include <system_error>

#include "mrd/units.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::excitation {
namespace fs = std::filesystem;
using io::file_label;
using io::is_space;
using io::line_prefix;
using io::split_words;
using io::strip_bom;
using io::to_upper;
using io::trim;
using io::UsageError;

namespace {

constexpr std::string_view kTimeColumn = "time_s";
constexpr std::string_view kAccelColumn = "accel_m_s2";
constexpr std::string_view kCsvHeader = "time_s,accel_m_s2";
constexpr std::string_view kAt2ValueField = "accel_g";

/// Uniform-step check: |step − first step| ≤ kStepRelTol·first step + kStepAbsTol_s.
constexpr double kStepRelTol = 1e-6;
constexpr double kStepAbsTol_s = 1e-9;
/// A time within this fraction of a step of a sample counts as on the sample.
constexpr double kSnapFraction = 1e-9;
/// Largest resampled length accepted (8 GB of doubles).
constexpr double kMaxResampledSamples = 1e9;

/// Up to 60 characters of user text, on one printable line.
std::string excerpt(std::string_view text) { return io::excerpt(text, 60); }

std::string format_number(double value) { return io::format_number("%.9g", value); }

/// Refuses a record whose step makes no run or whose samples are beyond any earthquake.
void check_record(const GroundMotion& motion, const std::string& file) {
  if (!(motion.dt_s >= kMinRecordStep_s) || !(motion.dt_s <= kMaxRecordStep_s)) {
    throw UsageError(file + ": sample step " + format_number(motion.dt_s) + " s is outside " +
                     format_number(kMinRecordStep_s) + " to " + format_number(kMaxRecordStep_s) + " s");
  }
  for (std::size_t i = 0; i < motion.accel_m_s2.size(); ++i) {
    if (!(std::abs(motion.accel_m_s2[i]) <= kMaxRecordAccel_m_s2)) {
      throw UsageError(file + ": sample " + std::to_string(i + 1) + ": acceleration " +
                       format_number(motion.accel_m_s2[i]) + " m/s^2 is beyond the limit of " +
                       format_number(kMaxRecordAccel_m_s2) + " m/s^2 (about 100 g)");
    }
  }
}

/// Splits text into lines, numbered from 1, without the line break (LF or CRLF).
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}

  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', pos_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    line = text_.substr(pos_, stop - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = stop + 1;
    ++line_no_;
    return true;
  }

  std::size_t line_no() const { return line_no_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_no_ = 0;
};

enum class NumberStatus { kOk, kNotANumber, kNotFinite, kOutOfRange };

/// Whole-string decimal number; a leading '+' is accepted.
NumberStatus parse_double(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') {
    s.remove_prefix(1);
    if (!s.empty() && (s.front() == '+' || s.front() == '-')) return NumberStatus::kNotANumber;
  }
  if (s.empty()) return NumberStatus::kNotANumber;
  const char* const end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, out);
  if (ec == std::errc::result_out_of_range && ptr == end) {
    // Overflow is an error; a value below the smallest subnormal (e.g.
    // 1e-400) is read as strtod reads it, i.e. as (signed) zero.
    const std::string copy(s);
    out = std::strtod(copy.c_str(), nullptr);
    return std::isfinite(out) ? NumberStatus::kOk : NumberStatus::kOutOfRange;
  }
  if (ec != std::errc() || ptr != end) return NumberStatus::kNotANumber;
  if (!std::isfinite(out)) return NumberStatus::kNotFinite;
  return NumberStatus::kOk;
}

[[noreturn]] void fail_field(const std::string& file, std::size_t line_no, std::string_view field,
                             const std::string& what) {
  throw UsageError(line_prefix(file, line_no) + "field '" + std::string(field) + "': " + what);
}

/// Parses one numeric field; throws naming file, line and field otherwise.
/// `field_detail` is appended after the quoted field name (e.g. a position).
double parse_field(std::string_view text, const std::string& file, std::size_t line_no, std::string_view field,
                   const std::string& field_detail = {}) {
  double value = 0.0;
  const NumberStatus status = parse_double(text, value);
  if (status == NumberStatus::kOk) return value;
  const char* what = status == NumberStatus::kNotFinite    ? "expected a finite number"
                     : status == NumberStatus::kOutOfRange ? "number out of range"
                                                           : "expected a number";
  throw UsageError(line_prefix(file, line_no) + "field '" + std::string(field) + "'" + field_detail + ": " + what +
                   ", got '" + excerpt(text) + "'");
}

std::string stem_of(const fs::path& path) { return path.stem().string(); }

// ---------------------------------------------------------------- PEER AT2

struct At2Header {
  std::size_t npts = 0;
  double dt_s = 0.0;
};

/// Finds `key` followed by '=' (spaces allowed around it) in the upper-cased
/// line and sets `value` to the text after it up to the next space or comma.
/// False when there is no `key=`.
bool find_keyed_value(std::string_view line_upper, std::string_view line, std::string_view key,
                      std::string_view& value) {
  std::size_t from = 0;
  while (true) {
    const std::size_t at = line_upper.find(key, from);
    if (at == std::string_view::npos) return false;
    std::size_t i = at + key.size();
    while (i < line.size() && is_space(line[i])) ++i;
    if (i < line.size() && line[i] == '=') {
      ++i;
      while (i < line.size() && is_space(line[i])) ++i;
      const std::size_t start = i;
      while (i < line.size() && !is_space(line[i]) && line[i] != ',') ++i;
      value = line.substr(start, i - start);
      return true;
    }
    from = at + 1;
  }
}

std::size_t parse_npts(std::string_view text, const std::string& file, std::size_t line_no) {
  unsigned long long npts = 0;
  const char* const end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, npts);
  if (text.empty() || ec != std::errc() || ptr != end || npts < 2 || npts > 1'000'000'000ULL) {
    fail_field(file, line_no, "NPTS", "expected a whole number of samples, at least 2, got '" + excerpt(text) + "'");
  }
  return static_cast<std::size_t>(npts);
}

At2Header parse_at2_npts_dt(std::string_view line, const std::string& file, std::size_t line_no) {
  const std::string upper = to_upper(line);
  std::string_view npts_text;
  std::string_view dt_text;
  const std::size_t npts_at = upper.find("NPTS");
  const bool keyed = find_keyed_value(upper, line, "NPTS", npts_text) && find_keyed_value(upper, line, "DT", dt_text);
  if (!keyed) {
    // Older layout: "<npts> <dt> NPTS, DT".
    const std::vector<std::string_view> words =
        npts_at == std::string::npos ? std::vector<std::string_view>{} : split_words(line.substr(0, npts_at));
    if (npts_at == std::string::npos || words.size() != 2 || upper.find("DT", npts_at) == std::string::npos) {
      throw UsageError(line_prefix(file, line_no) + "expected 'NPTS=<n>, DT=<s>' or '<n> <s> NPTS, DT', got '" +
                       excerpt(trim(line)) + "'");
    }
    npts_text = words[0];
    dt_text = words[1];
    if (!npts_text.empty() && npts_text.back() == ',') npts_text.remove_suffix(1);
    if (!dt_text.empty() && dt_text.back() == ',') dt_text.remove_suffix(1);
  }
  if (dt_text.size() > 3 && to_upper(dt_text.substr(dt_text.size() - 3)) == "SEC") dt_text.remove_suffix(3);

  At2Header header;
  header.npts = parse_npts(npts_text, file, line_no);
  header.dt_s = parse_field(dt_text, file, line_no, "DT");
  if (!(header.dt_s > 0.0)) {
    fail_field(file, line_no, "DT", "expected a positive step in s, got '" + excerpt(dt_text) + "'");
  }
  return header;
}

/// Line 3 names the quantity and its unit; reject files that are clearly not
/// accelerations in g (e.g. a renamed .VT2 or .DT2).
void check_at2_units(std::string_view line, const std::string& file, std::size_t line_no) {
  const std::string upper = to_upper(line);
  bool ok = upper.find("VELOCITY") == std::string::npos && upper.find("DISPLACEMENT") == std::string::npos;
  const std::size_t units_at = upper.find("UNITS OF");
  if (ok && units_at != std::string::npos) {
    std::size_t i = units_at + 8;
    while (i < upper.size() && is_space(upper[i])) ++i;
    std::size_t j = i;
    while (j < upper.size() && !is_space(upper[j]) && upper[j] != ',' && upper[j] != '.') ++j;
    const std::string unit = upper.substr(i, j - i);
    ok = unit == "G" || unit == "G'S" || unit == "GS";
  }
  if (!ok) {
    throw UsageError(line_prefix(file, line_no) + "expected an acceleration time series in units of g, got '" +
                     excerpt(trim(line)) + "'");
  }
}

/// Fortran writes double-precision exponents with D (1.0D-02).
double parse_fortran_value(std::string_view word, const std::string& file, std::size_t line_no,
                           std::size_t index_on_line) {
  const std::string suffix = " (value " + std::to_string(index_on_line) + " on the line)";
  if (word.find_first_of("dD") == std::string_view::npos) {
    return parse_field(word, file, line_no, kAt2ValueField, suffix);
  }
  std::string copy(word);
  std::replace(copy.begin(), copy.end(), 'D', 'E');
  std::replace(copy.begin(), copy.end(), 'd', 'e');
  double value = 0.0;
  if (parse_double(copy, value) == NumberStatus::kOk) return value;
  return parse_field(word, file, line_no, kAt2ValueField, suffix);  // throws with the original text
}

}  // namespace

// ---------------------------------------------------------------- GroundMotion

double GroundMotion::duration_s() const noexcept {
  return accel_m_s2.size() < 2 ? 0.0 : static_cast<double>(accel_m_s2.size() - 1) * dt_s;
}

double GroundMotion::pga_m_s2() const noexcept {
  double peak = 0.0;
  for (const double a : accel_m_s2) peak = std::max(peak, std::abs(a));
  return peak;
}

std::size_t GroundMotion::pga_index() const noexcept {
  std::size_t best = 0;
  double peak = -1.0;
  for (std::size_t i = 0; i < accel_m_s2.size(); ++i) {
    if (std::abs(accel_m_s2[i]) > peak) {
      peak = std::abs(accel_m_s2[i]);
      best = i;
    }
  }
  return best;
}

double GroundMotion::pga_time_s() const noexcept { return static_cast<double>(pga_index()) * dt_s; }

// ---------------------------------------------------------------- readers

GroundMotion read_ground_motion_csv(const fs::path& path) {
  return parse_ground_motion_csv(io::read_regular_file(path, kMaxGroundMotionFileBytes), file_label(path),
                                 stem_of(path));
}

GroundMotion parse_ground_motion_csv(std::string_view data, const std::string& file, const std::string& name) {
  const std::string_view text = strip_bom(data);
  if (trim(text).empty()) throw UsageError(file + ": empty file");

  LineReader lines(text);
  std::string_view line;
  while (lines.next(line) && trim(line).empty()) {
  }
  const std::vector<std::string_view> header = io::split_commas(line);
  if (header.size() != 2 || header[0] != kTimeColumn || header[1] != kAccelColumn) {
    throw UsageError(line_prefix(file, lines.line_no()) + "expected header '" + std::string(kCsvHeader) + "', got '" +
                     excerpt(trim(line)) + "'");
  }

  GroundMotion motion;
  motion.name = name;
  motion.source = file;
  double first_time_s = 0.0;
  double previous_time_s = 0.0;
  double first_step_s = 0.0;
  while (lines.next(line)) {
    if (trim(line).empty()) continue;
    const std::size_t line_no = lines.line_no();
    const std::vector<std::string_view> fields = io::split_commas(line);
    if (fields.size() != 2) {
      throw UsageError(line_prefix(file, line_no) + "expected 2 fields '" + std::string(kCsvHeader) + "', got " +
                       std::to_string(fields.size()) + ": '" + excerpt(trim(line)) + "'");
    }
    const double time_s = parse_field(fields[0], file, line_no, kTimeColumn);
    const double accel_m_s2 = parse_field(fields[1], file, line_no, kAccelColumn);
    const std::size_t index = motion.accel_m_s2.size();
    if (index == 0) {
      first_time_s = time_s;
    } else {
      const double step_s = time_s - previous_time_s;
      if (!(step_s > 0.0) || !std::isfinite(step_s)) {
        fail_field(file, line_no, kTimeColumn,
                   "time must increase, got " + format_number(time_s) + " s after " + format_number(previous_time_s) +
                       " s");
      }
      if (index == 1) {
        first_step_s = step_s;
      } else if (std::abs(step_s - first_step_s) > kStepRelTol * first_step_s + kStepAbsTol_s) {
        fail_field(file, line_no, kTimeColumn,
                   "non-uniform time step " + format_number(step_s) + " s (expected " + format_number(first_step_s) +
                       " s from the first two samples)");
      }
    }
    previous_time_s = time_s;
    motion.accel_m_s2.push_back(accel_m_s2);
  }
  const std::size_t n = motion.accel_m_s2.size();
  if (n < 2) {
    throw UsageError(file + ": expected at least 2 samples after the header, got " + std::to_string(n));
  }
  motion.dt_s = (previous_time_s - first_time_s) / static_cast<double>(n - 1);
  check_record(motion, file);
  return motion;
}

GroundMotion read_peer_at2(const fs::path& path) {
  return parse_peer_at2(io::read_regular_file(path, kMaxGroundMotionFileBytes), file_label(path), stem_of(path));
}

GroundMotion parse_peer_at2(std::string_view data, const std::string& file, const std::string& name) {
  const std::string_view text = strip_bom(data);
  if (trim(text).empty()) throw UsageError(file + ": empty file");

  LineReader lines(text);
  std::string_view header[4];
  for (std::size_t i = 0; i < 4; ++i) {
    if (!lines.next(header[i])) {
      throw UsageError(file + ": expected 4 header lines (PEER .AT2), got " + std::to_string(i));
    }
  }
  check_at2_units(header[2], file, 3);
  const At2Header at2 = parse_at2_npts_dt(header[3], file, 4);

  GroundMotion motion;
  motion.name = name;
  motion.source = file;
  motion.dt_s = at2.dt_s;
  motion.accel_m_s2.reserve(std::min(at2.npts, data.size() / 2 + 1));
  std::string_view line;
  while (lines.next(line)) {
    const std::vector<std::string_view> words = split_words(line);
    for (std::size_t j = 0; j < words.size(); ++j) {
      const double accel_g = parse_fortran_value(words[j], file, lines.line_no(), j + 1);
      motion.accel_m_s2.push_back(accel_g * units::kStandardGravity_m_s2);
    }
  }
  if (motion.accel_m_s2.size() != at2.npts) {
    fail_field(file, 4, "NPTS",
               "header says " + std::to_string(at2.npts) + " values, the file has " +
                   std::to_string(motion.accel_m_s2.size()));
  }
  check_record(motion, file);
  return motion;
}

GroundMotion read_ground_motion(const fs::path& path) {
  const std::string ext = to_upper(path.extension().string());
  if (ext == ".CSV") return read_ground_motion_csv(path);
  if (ext == ".AT2") return read_peer_at2(path);
  throw UsageError(file_label(path) + ": unknown ground-motion format '" + excerpt(path.extension().string()) +
                   "' (expected .csv or .AT2)");
}

// ---------------------------------------------------------------- scaling

double scale_factor_for_pga(const GroundMotion& motion, double target_pga_m_s2) {
  if (!std::isfinite(target_pga_m_s2) || !(target_pga_m_s2 > 0.0)) {
    throw UsageError("target PGA must be a positive number of m/s^2, got " + format_number(target_pga_m_s2));
  }
  const double pga_m_s2 = motion.pga_m_s2();
  if (!(pga_m_s2 > 0.0) || !std::isfinite(pga_m_s2)) {
    throw UsageError("ground motion '" + motion.name + "' has a PGA of " + format_number(pga_m_s2) +
                     " m/s^2; it cannot be scaled to " + format_number(target_pga_m_s2) + " m/s^2");
  }
  return target_pga_m_s2 / pga_m_s2;
}

GroundMotion scaled_to_pga(const GroundMotion& motion, double target_pga_m_s2) {
  const double factor = scale_factor_for_pga(motion, target_pga_m_s2);
  GroundMotion scaled = motion;
  for (double& a : scaled.accel_m_s2) a = std::clamp(a * factor, -target_pga_m_s2, target_pga_m_s2);
  const std::size_t peak = motion.pga_index();
  scaled.accel_m_s2[peak] = std::copysign(target_pga_m_s2, motion.accel_m_s2[peak]);
  return scaled;
}

// ---------------------------------------------------------------- resampling

GroundMotionSampler::GroundMotionSampler(const GroundMotion& motion)
    : dt_s_(motion.dt_s), accel_m_s2_(motion.accel_m_s2) {
  if (accel_m_s2_.empty()) throw UsageError("ground motion '" + motion.name + "' has no samples");
  if (!std::isfinite(dt_s_) || !(dt_s_ > 0.0)) {
    throw UsageError("ground motion '" + motion.name + "' has an invalid time step " + format_number(dt_s_) + " s");
  }
}

double GroundMotionSampler::duration_s() const noexcept {
  return static_cast<double>(accel_m_s2_.size() - 1) * dt_s_;
}

double GroundMotionSampler::accel_at(double t_s) const noexcept {
  const double position = t_s / dt_s_;  // in samples
  const double last = static_cast<double>(accel_m_s2_.size() - 1);
  if (!(position >= -kSnapFraction)) return 0.0;  // before the record, or NaN
  if (position > last) return position - last <= kSnapFraction ? accel_m_s2_.back() : 0.0;
  const double whole = std::floor(std::max(position, 0.0));
  const double fraction = std::max(position, 0.0) - whole;
  const auto i = static_cast<std::size_t>(whole);
  if (fraction <= kSnapFraction) return accel_m_s2_[i];
  // Here whole < position ≤ last, so i + 1 is a valid index.
  if (1.0 - fraction <= kSnapFraction) return accel_m_s2_[i + 1];
  return accel_m_s2_[i] + fraction * (accel_m_s2_[i + 1] - accel_m_s2_[i]);
}

std::vector<double> resample_linear(const GroundMotion& motion, double dt_new_s) {
  return resample_linear(motion, dt_new_s, motion.duration_s());
}

std::vector<double> resample_linear(const GroundMotion& motion, double dt_new_s, double duration_s) {
  if (!std::isfinite(dt_new_s) || !(dt_new_s > 0.0)) {
    throw UsageError("resampling step must be a positive number of s, got " + format_number(dt_new_s));
  }
  if (!std::isfinite(duration_s) || !(duration_s >= 0.0)) {
    throw UsageError("resampling duration must be a non-negative number of s, got " + format_number(duration_s));
  }
  const double steps = duration_s / dt_new_s;
  if (!(steps < kMaxResampledSamples)) {
    throw UsageError("resampling " + format_number(duration_s) + " s at " + format_number(dt_new_s) +
                     " s would need more than 1e9 samples");
  }
  const GroundMotionSampler sampler(motion);
  const auto count = static_cast<std::size_t>(std::floor(steps + kSnapFraction)) + 1;
  std::vector<double> out(count);
  for (std::size_t k = 0; k < count; ++k) out[k] = sampler.accel_at(static_cast<double>(k) * dt_new_s);
  return out;
}

}  // namespace mrd::excitation
