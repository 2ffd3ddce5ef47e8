#include "host_sim/discrepancy/measured_data.hpp"

#include <matio.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>

#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::discrepancy {
namespace fs = std::filesystem;
using io::UsageError;

namespace {

enum class Quantity { time, displacement, velocity, current_cmd, current, force, extra };

struct UnitDef {
  std::string_view unit;  ///< lower case
  std::string_view shown; ///< as written in help and errors
  double to_si;
};

constexpr double kNewtonPerKip = 4448.2216152605;
constexpr double kNewtonPerLbf = 4.4482216152605;

constexpr std::array kTimeUnits{UnitDef{"s", "s", 1.0}, UnitDef{"ms", "ms", 1e-3}};
constexpr std::array kDispUnits{UnitDef{"m", "m", 1.0}, UnitDef{"mm", "mm", 1e-3}, UnitDef{"cm", "cm", 1e-2},
                                UnitDef{"in", "in", 0.0254}};
constexpr std::array kVelUnits{UnitDef{"m_s", "m_s", 1.0}, UnitDef{"mm_s", "mm_s", 1e-3},
                               UnitDef{"cm_s", "cm_s", 1e-2}, UnitDef{"in_s", "in_s", 0.0254}};
constexpr std::array kCurrentUnits{UnitDef{"a", "A", 1.0}, UnitDef{"ma", "mA", 1e-3}};
constexpr std::array kForceUnits{UnitDef{"n", "N", 1.0}, UnitDef{"kn", "kN", 1e3}, UnitDef{"kip", "kip", kNewtonPerKip},
                                 UnitDef{"lbf", "lbf", kNewtonPerLbf}};

/// Units an extra column may end in (kept unconverted).
constexpr std::array<std::string_view, 44> kExtraUnits{
    "s",   "ms",   "m",    "mm",  "cm",  "in",  "m_s", "mm_s", "cm_s", "in_s", "m_s2", "mm_s2", "g",  "a",   "ma",
    "v",   "mv",   "n",    "kn",  "kip", "lbf", "c",   "degc", "f",    "degf", "k",    "pa",    "kpa", "mpa", "psi",
    "bar", "hz",   "pct",  "frac", "1",  "w",   "kw",  "j",    "kj",   "rad",  "deg",  "ohm",   "t",   "mt"};

struct QuantityDef {
  Quantity q;
  std::string_view base;
  std::string_view label;
  const UnitDef* units;
  std::size_t n_units;
};

/// Longest base first so that `current_cmd_A` is not read as `current` + `cmd_A`.
const std::array<QuantityDef, 6>& quantity_defs() {
  static const std::array<QuantityDef, 6> defs{
      QuantityDef{Quantity::current_cmd, "current_cmd", "commanded current", kCurrentUnits.data(), kCurrentUnits.size()},
      QuantityDef{Quantity::displacement, "displacement", "displacement", kDispUnits.data(), kDispUnits.size()},
      QuantityDef{Quantity::velocity, "velocity", "velocity", kVelUnits.data(), kVelUnits.size()},
      QuantityDef{Quantity::current, "current", "current", kCurrentUnits.data(), kCurrentUnits.size()},
      QuantityDef{Quantity::force, "force", "force", kForceUnits.data(), kForceUnits.size()},
      QuantityDef{Quantity::time, "time", "time", kTimeUnits.data(), kTimeUnits.size()},
  };
  return defs;
}

/// Up to 40 characters of user text on one printable line.
std::string excerpt(std::string_view text) { return io::excerpt(text, 40); }

std::string num(double v) { return io::format_number("%.6g", v); }

std::string unit_list(const QuantityDef& d) {
  std::string s;
  for (std::size_t i = 0; i < d.n_units; ++i) {
    if (i) s += i + 1 == d.n_units ? " or " : ", ";
    s += std::string(d.base) + "_" + std::string(d.units[i].shown);
  }
  return s;
}

bool ends_with_extra_unit(std::string_view lname) {
  return std::any_of(kExtraUnits.begin(), kExtraUnits.end(), [&](std::string_view u) {
    return lname.size() > u.size() + 1 && lname.substr(lname.size() - u.size()) == u &&
           lname[lname.size() - u.size() - 1] == '_';
  });
}

/// What a column is and how its values convert to SI.
struct ColumnRole {
  Quantity q = Quantity::extra;
  double to_si = 1.0;
};

/// Classifies a column name; throws naming `where` and the column otherwise.
ColumnRole classify(std::string_view name, const std::string& where, std::size_t col_no) {
  const std::string lname = io::to_lower(name);
  const std::string col = "column " + std::to_string(col_no) + " '" + excerpt(name) + "'";
  if (lname.empty()) throw UsageError(where + col + ": empty column name");
  for (const auto& d : quantity_defs()) {
    if (lname == d.base) {
      throw UsageError(where + col + ": no unit; name it with one, e.g. " + unit_list(d));
    }
    if (lname.size() > d.base.size() + 1 && lname.compare(0, d.base.size(), d.base) == 0 &&
        lname[d.base.size()] == '_') {
      const std::string unit = lname.substr(d.base.size() + 1);
      for (std::size_t i = 0; i < d.n_units; ++i) {
        if (unit == d.units[i].unit) return {d.q, d.units[i].to_si};
      }
      // `current_meas_A`, `force_top_kN`: another signal of the same kind, kept.
      if (ends_with_extra_unit(lname) && unit.find('_') != std::string::npos) return {Quantity::extra, 1.0};
      throw UsageError(where + col + ": unknown unit '" + excerpt(name.substr(d.base.size() + 1)) + "' for " +
                       std::string(d.label) + " (use " + unit_list(d) + ")");
    }
  }
  if (ends_with_extra_unit(lname)) return {Quantity::extra, 1.0};
  throw UsageError(where + col + ": the name does not end in a known unit (e.g. _s, _m, _mm, _A, _N, _kN, _degC)");
}

/// Columns gathered from a CSV or .mat source, with a way to name a sample.
struct RawTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;  ///< per column
  /// Location of sample `row` of column `col` for messages: "file:LINE: column 'x'".
  std::function<std::string(std::size_t row, std::size_t col)> where;
  /// Location of the column itself: "file:1: column 3 'x'" / "file: variable 'x'".
  std::function<std::string(std::size_t col)> where_column;
  std::string file_where;  ///< "file:1: " or "file: "
};

/// Roles of the columns and where each required quantity is; throws for an
/// unknown unit, a repeated quantity or a missing column.
struct HeaderRoles {
  std::vector<ColumnRole> roles;
  std::size_t time = 0, disp = 0, cmd = 0, force = 0;
  std::optional<std::size_t> vel;
  std::optional<std::size_t> cur;  ///< measured coil current, beside the command
};

HeaderRoles header_roles(const std::vector<std::string>& names, const std::string& file_where,
                         const std::function<std::string(std::size_t)>& where_column) {
  const std::size_t ncol = names.size();
  HeaderRoles h;
  h.roles.resize(ncol);
  std::array<std::optional<std::size_t>, 6> idx{};  // by Quantity (not extra)
  for (std::size_t c = 0; c < ncol; ++c) {
    h.roles[c] = classify(names[c], file_where, c + 1);
    if (h.roles[c].q == Quantity::extra) continue;
    auto& slot = idx[static_cast<std::size_t>(h.roles[c].q)];
    if (slot) throw UsageError(where_column(c) + ": repeats the quantity of '" + excerpt(names[*slot]) + "'");
    slot = c;
  }
  auto& cmd = idx[static_cast<std::size_t>(Quantity::current_cmd)];
  auto& cur = idx[static_cast<std::size_t>(Quantity::current)];
  if (!cmd && cur) {
    cmd = cur;  // `current_A` is taken as the commanded current when there is no current_cmd column
    h.roles[*cmd].q = Quantity::current_cmd;
    cur.reset();
  }  // with both, `current_A` is the measured coil current beside the command
  const auto require = [&](Quantity q) {
    const auto& s = idx[static_cast<std::size_t>(q)];
    if (!s) {
      for (const auto& d : quantity_defs()) {
        if (d.q == q) throw UsageError(file_where + "missing column for " + std::string(d.label) + ": " + unit_list(d));
      }
    }
    return *s;
  };
  h.time = require(Quantity::time);
  h.disp = require(Quantity::displacement);
  h.cmd = require(Quantity::current_cmd);
  h.force = require(Quantity::force);
  h.vel = idx[static_cast<std::size_t>(Quantity::velocity)];
  h.cur = cur;
  return h;
}

/// Validates and converts a raw table (shared by CSV and .mat).
/// Refuses a column with a sample beyond `limit` (SI), naming the first one.
void check_magnitude(const std::vector<double>& v, double limit, const char* unit, const RawTable& raw,
                     std::size_t col) {
  for (std::size_t r = 0; r < v.size(); ++r) {
    if (!(std::abs(v[r]) <= limit)) {
      throw UsageError(raw.where(r, col) + ": " + num(v[r]) + " " + unit + " is beyond any damper test (limit " +
                       num(limit) + " " + unit + ")");
    }
  }
}

/// Refuses a column that never changes: a constant or all-zero force or
/// displacement is a disconnected sensor, not a measurement.
void check_varies(const std::vector<double>& v, const char* unit, const RawTable& raw, std::size_t col) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  if (lo != v.end() && *lo == *hi) {
    throw UsageError(raw.where_column(col) + ": constant " + num(*lo) + " " + unit +
                     " in every sample (a disconnected sensor?): nothing to compare a model with");
  }
}

MeasuredData build(RawTable&& raw, const std::string& label) {
  const std::size_t ncol = raw.names.size();
  const HeaderRoles h = header_roles(raw.names, raw.file_where, raw.where_column);
  const auto& roles = h.roles;
  const std::size_t c_time = h.time;
  const std::size_t c_disp = h.disp;
  const std::size_t c_cmd = h.cmd;
  const std::size_t c_force = h.force;
  const auto& c_vel = h.vel;
  const auto& c_cur = h.cur;

  const std::size_t n = raw.values.empty() ? 0 : raw.values[0].size();
  for (std::size_t c = 0; c < ncol; ++c) {
    for (std::size_t r = 0; r < n; ++r) {
      if (!std::isfinite(raw.values[c][r])) throw UsageError(raw.where(r, c) + ": not a finite number");
    }
  }
  const auto& t = raw.values[c_time];
  const double t_scale = roles[c_time].to_si;
  if (n < kMinSamples || (n > 0 && (t[n - 1] - t[0]) * t_scale < kMinDuration_s)) {
    const double dur = n > 0 ? (t[n - 1] - t[0]) * t_scale : 0.0;
    const std::string w = n > 0 ? raw.where(n - 1, c_time) : raw.where_column(c_time);
    throw UsageError(w + ": record too short: " + std::to_string(n) + " samples over " + num(dur) +
                     " s (need at least " + std::to_string(kMinSamples) + " samples and " + num(kMinDuration_s) + " s)");
  }
  std::vector<double> steps;
  steps.reserve(n - 1);
  for (std::size_t r = 1; r < n; ++r) {
    const double dt = (t[r] - t[r - 1]) * t_scale;
    if (!(dt > 0.0)) {
      throw UsageError(raw.where(r, c_time) + ": time " + num(t[r]) + " does not increase (previous sample " +
                       num(t[r - 1]) + ")");
    }
    if (dt > kMaxStep_s) {
      throw UsageError(raw.where(r, c_time) + ": gap of " + num(dt) + " s after the previous sample (at most " +
                       num(kMaxStep_s) + " s)");
    }
    steps.push_back(dt);
  }
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  const double median_dt = steps[steps.size() / 2];
  if (median_dt > kMaxMedianStep_s) {
    throw UsageError(raw.where_column(c_time) + ": median sample step " + num(median_dt) +
                     " s is too coarse (at most " + num(kMaxMedianStep_s) + " s, i.e. 50 Hz)");
  }

  MeasuredData m;
  m.source = label;
  const auto convert = [&](std::size_t c) {
    std::vector<double> v = std::move(raw.values[c]);
    const double s = roles[c].to_si;
    if (s != 1.0) {
      for (double& x : v) x *= s;
    }
    return v;
  };
  m.time_s = convert(c_time);
  m.displacement_m = convert(c_disp);
  m.current_cmd_a = convert(c_cmd);
  m.force_n = convert(c_force);
  if (c_vel) m.velocity_m_s = convert(*c_vel);
  if (c_cur) m.current_a = convert(*c_cur);
  check_magnitude(m.force_n, kMaxMeasuredForce_n, "N", raw, c_force);
  check_magnitude(m.displacement_m, kMaxMeasuredDisplacement_m, "m", raw, c_disp);
  check_magnitude(m.current_cmd_a, kMaxMeasuredCurrent_a, "A", raw, c_cmd);
  if (c_vel) check_magnitude(m.velocity_m_s, kMaxMeasuredVelocity_m_s, "m/s", raw, *c_vel);
  if (c_cur) check_magnitude(m.current_a, kMaxMeasuredCurrent_a, "A", raw, *c_cur);
  check_varies(m.force_n, "N", raw, c_force);
  check_varies(m.displacement_m, "m", raw, c_disp);
  for (std::size_t c = 0; c < ncol; ++c) {
    if (roles[c].q == Quantity::extra) m.extra.push_back({raw.names[c], std::move(raw.values[c])});
  }
  return m;
}

/// Parses a whole field as a double (a leading '+' allowed); nullopt if it is not one.
std::optional<double> parse_double(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return std::nullopt;
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

std::string read_text(const fs::path& path) { return io::read_regular_file(path, kMaxMeasuredFileBytes); }

/// The bytes of a .mat file as its data elements declare them: checks that
/// every element lies within the file, so that a truncated file is refused
/// before libmatio reads past its end. Returns the 0-based index of the first
/// element cut short and its name where the bytes hold it, or nullopt when the
/// file is complete. Level 5 layouts (a 128-byte header, version 0x0100) are
/// walked; level 4 files too; HDF5-based v7.3 files are left to libmatio.
struct MatCut {
  std::size_t index = 0;
  std::string name;
  std::string reason = "declares more bytes than the file holds or sizes that disagree (truncated or corrupt file)";
};

/// Array classes the reader takes (mxDOUBLE_CLASS to mxUINT64_CLASS); others
/// (cell, struct, object, char, sparse) are refused before libmatio reads them.
bool numeric_class(std::uint32_t cls) { return cls >= 6 && cls <= 15; }

std::string not_numeric(std::uint32_t cls) {
  return "is not a numeric array (MATLAB class " + std::to_string(cls) + "): expected double or single values";
}

/// Most values one .mat variable may declare (5e7 doubles, 400 MB).
constexpr std::size_t kMaxMatElements = 50'000'000;

class MatLayout {
 public:
  explicit MatLayout(std::string bytes) : b_(std::move(bytes)) {}

  std::optional<MatCut> first_cut_element() const {
    // As libmatio tells them apart: a level 5 (or HDF5-based 7.3) header ends
    // in the version and the endian indicator 'IM' (or 'MI'); anything else
    // is read as level 4.
    if (b_.size() >= 128 && ((b_[126] == 'I' && b_[127] == 'M') || (b_[126] == 'M' && b_[127] == 'I'))) {
      const bool swap = b_[126] == 'M';
      const auto lo = static_cast<unsigned char>(b_[swap ? 125 : 124]);
      const auto hi = static_cast<unsigned char>(b_[swap ? 124 : 125]);
      const auto v = static_cast<std::uint16_t>(lo | (hi << 8));
      if (v == 0x0100) return walk_v5();
      if (v == 0x0200) return std::nullopt;
    }
    return walk_v4();
  }

 private:
  std::uint32_t u32(std::size_t at, bool swap) const {
    std::uint32_t v = 0;
    std::memcpy(&v, b_.data() + at, 4);
    return swap ? __builtin_bswap32(v) : v;
  }

  std::optional<MatCut> walk_v5() const {
    constexpr std::size_t kHeader = 128;
    const bool swap = b_[126] == 'M' && b_[127] == 'I';
    std::size_t pos = kHeader;
    for (std::size_t k = 0; pos < b_.size(); ++k) {
      if (b_.size() - pos < 8) return MatCut{k, {}};
      const std::uint32_t type = u32(pos, swap);
      if ((type >> 16) != 0) {  // small data element: tag and data in 8 bytes
        pos += 8;
        continue;
      }
      std::uint64_t n = u32(pos + 4, swap);
      if (type == kMiMatrix) n = (n + 7) / 8 * 8;
      std::string name;
      std::uint32_t cls = 0;
      if (n > b_.size() - pos - 8) {
        if (type == kMiMatrix) (void)matrix_sizes_consistent(pos + 8, b_.size() - pos - 8, swap, name, cls, true);
        return MatCut{k, name};
      }
      if (type == kMiMatrix) {
        if (!matrix_sizes_consistent(pos + 8, static_cast<std::size_t>(n), swap, name, cls, true)) {
          return MatCut{k, name};
        }
        if (!numeric_class(cls)) return MatCut{k, name, not_numeric(cls)};
      } else if (type == kMiCompressed) {
        if (auto cut = check_compressed_header(pos + 8, static_cast<std::size_t>(n), swap, k)) return cut;
      }
      pos += 8 + static_cast<std::size_t>(n);
    }
    return std::nullopt;
  }

  /// Inside an uncompressed miMATRIX element: flags, dimensions, name, then
  /// the real part whose byte count must equal the elements the dimensions
  /// declare times the size of its type.
  static constexpr std::uint32_t kMiMatrix = 14;
  static constexpr std::uint32_t kMiCompressed = 15;

  /// A compressed variable: inflates the start of its stream (enough for the
  /// matrix tag, flags, dimensions and name) and checks the class and the
  /// declared size before libmatio allocates for them.
  std::optional<MatCut> check_compressed_header(std::size_t at, std::size_t size, bool swap, std::size_t k) const {
    std::string head(4096, '\0');
    z_stream z{};
    if (inflateInit(&z) != Z_OK) return MatCut{k, {}, "cannot be inflated"};
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(b_.data() + at));
    z.avail_in = static_cast<uInt>(std::min<std::size_t>(size, 1u << 30));
    z.next_out = reinterpret_cast<Bytef*>(head.data());
    z.avail_out = static_cast<uInt>(head.size());
    const int rc = inflate(&z, Z_SYNC_FLUSH);
    const std::size_t got = head.size() - z.avail_out;
    inflateEnd(&z);
    if ((rc != Z_OK && rc != Z_STREAM_END && rc != Z_BUF_ERROR) || got < 8) {
      return MatCut{k, {}, "holds a compressed variable that does not inflate"};
    }
    head.resize(got);
    const MatLayout inner(std::move(head));
    if (inner.u32(0, swap) != kMiMatrix) return MatCut{k, {}, "holds a compressed element that is not an array"};
    std::string name;
    std::uint32_t cls = 0;
    // The data of the inflated matrix lies beyond the inflated head: check only its header elements.
    if (!inner.matrix_sizes_consistent(8, inner.b_.size() - 8, swap, name, cls, false)) {
      return MatCut{k, name, "has array flags, dimensions or a name that disagree (corrupt file)"};
    }
    if (!numeric_class(cls)) return MatCut{k, name, not_numeric(cls)};
    return std::nullopt;
  }

  bool matrix_sizes_consistent(std::size_t at, std::size_t size, bool swap, std::string& name, std::uint32_t& cls,
                               bool with_data) const {
    std::size_t p = at;
    const std::size_t end = at + size;
    const auto sub = [&](std::uint32_t& type, std::uint64_t& n, std::size_t& data) {
      if (end - p < 8) return false;
      type = u32(p, swap);
      if ((type >> 16) != 0) {
        n = type >> 16;
        type &= 0xFFFFu;
        data = p + 4;
        if (n > 4) return false;
        p += 8;
        return true;
      }
      n = u32(p + 4, swap);
      data = p + 8;
      const std::uint64_t padded = (n + 7) / 8 * 8;
      if (padded > end - p - 8) return false;
      p += 8 + static_cast<std::size_t>(padded);
      return true;
    };
    std::uint32_t type = 0;
    std::uint64_t n = 0;
    std::size_t data = 0;
    if (!sub(type, n, data)) return false;  // array flags
    if (n < 8) return false;
    cls = u32(data, swap) & 0xFFu;
    if (!sub(type, n, data) || type != 5 || n % 4 != 0) return false;  // dimensions, miINT32
    std::uint64_t elements = 1;
    for (std::size_t i = 0; i < n / 4; ++i) {
      const std::uint32_t d = u32(data + 4 * i, swap);
      if (d != 0 && elements > (std::uint64_t{1} << 40) / d) return false;
      elements *= d;
    }
    if (!sub(type, n, data)) return false;  // name
    name.assign(b_.data() + data, static_cast<std::size_t>(n));
    if (!numeric_class(cls)) return true;  // refused by class by the caller
    if (elements > kMaxMatElements) return false;
    if (elements == 0 || !with_data) return true;
    if (!sub(type, n, data)) return false;  // real part
    const std::uint64_t bytes_per = type_size(type);
    return bytes_per != 0 && n == elements * bytes_per;
  }

  static std::uint64_t type_size(std::uint32_t mi_type) {
    switch (mi_type) {
      case 1: case 2: return 1;   // miINT8, miUINT8
      case 3: case 4: return 2;   // miINT16, miUINT16
      case 5: case 6: case 7: return 4;  // miINT32, miUINT32, miSINGLE
      case 9: case 12: case 13: return 8;  // miDOUBLE, miINT64, miUINT64
      default: return 0;
    }
  }

  std::optional<MatCut> walk_v4() const {
    std::size_t pos = 0;
    for (std::size_t k = 0; pos < b_.size(); ++k) {
      if (b_.size() - pos < 20) return MatCut{k, {}};
      std::uint32_t type = u32(pos, false);
      const bool swap = type > 9999;
      if (swap) type = u32(pos, true);
      const std::uint64_t rows = u32(pos + 4, swap);
      const std::uint64_t cols = u32(pos + 8, swap);
      const std::uint32_t imag = u32(pos + 12, swap);
      const std::uint64_t name_len = u32(pos + 16, swap);
      static constexpr std::uint64_t kSize[] = {8, 4, 4, 2, 2, 1};
      const std::uint32_t prec = (type / 10) % 10;
      if (prec > 5 || rows > (std::uint64_t{1} << 31) || cols > (std::uint64_t{1} << 31) || name_len > 4096) {
        return MatCut{k, {}};
      }
      const std::uint64_t bytes = name_len + rows * cols * kSize[prec] * (imag != 0 ? 2 : 1);
      if (bytes > b_.size() - pos - 20) {
        const std::size_t have = std::min<std::size_t>(static_cast<std::size_t>(name_len), b_.size() - pos - 20);
        std::string name(b_.data() + pos + 20, have);
        if (const auto nul = name.find('\0'); nul != std::string::npos) name.resize(nul);
        return MatCut{k, name};
      }
      pos += 20 + static_cast<std::size_t>(bytes);
    }
    return std::nullopt;
  }

  std::string b_;
};

struct MatFileCloser {
  void operator()(mat_t* m) const noexcept { Mat_Close(m); }
};
struct MatVarFreer {
  void operator()(matvar_t* v) const noexcept { Mat_VarFree(v); }
};
using MatFile = std::unique_ptr<mat_t, MatFileCloser>;
using MatVar = std::unique_ptr<matvar_t, MatVarFreer>;

MeasuredData read_mat(const fs::path& path) {
  const std::string label = path.string();
  if (const auto cut = MatLayout(io::read_regular_file(path, kMaxMeasuredFileBytes)).first_cut_element()) {
    const std::string which = !cut->name.empty() ? "variable '" + excerpt(cut->name) + "'"
                                                 : "variable number " + std::to_string(cut->index + 1);
    throw UsageError(label + ": " + which + " " + cut->reason);
  }
  // reader policy: checked by io::read_regular_file above (the same path, read whole within the limit).
  MatFile mat(Mat_Open(label.c_str(), MAT_ACC_RDONLY));
  if (!mat) throw UsageError(label + ": not a readable MATLAB .mat file");
  std::vector<std::string> names;
  for (;;) {
    MatVar info(Mat_VarReadNextInfo(mat.get()));
    if (!info) break;
    if (!info->name) continue;
    // Checked before Mat_VarRead allocates what the variable declares.
    const std::string w = label + ": variable '" + excerpt(info->name) + "'";
    if (info->class_type != MAT_C_DOUBLE && info->class_type != MAT_C_SINGLE) {
      throw UsageError(w + ": expected double or single values");
    }
    if (info->isComplex) throw UsageError(w + ": is complex, expected real numbers");
    if (info->rank != 2 || !info->dims || (info->dims[0] != 1 && info->dims[1] != 1)) {
      throw UsageError(w + ": expected a vector");
    }
    if (info->dims[0] * info->dims[1] > kMaxMatElements) {
      throw UsageError(w + ": declares " + std::to_string(info->dims[0] * info->dims[1]) +
                       " values, more than the limit of " + std::to_string(kMaxMatElements));
    }
    names.emplace_back(info->name);
  }
  if (names.empty()) throw UsageError(label + ": the .mat file holds no variables");
  RawTable raw;
  raw.file_where = label + ": ";
  std::size_t n = 0;
  for (const auto& name : names) {
    MatVar v(Mat_VarRead(mat.get(), name.c_str()));
    const std::string w = label + ": variable '" + excerpt(name) + "'";
    if (!v || !v->data) throw UsageError(w + ": cannot be read");
    if (v->isComplex) throw UsageError(w + ": is complex, expected real numbers");
    if (v->rank != 2 || (v->dims[0] != 1 && v->dims[1] != 1)) throw UsageError(w + ": expected a vector");
    const std::size_t len = v->dims[0] * v->dims[1];
    std::vector<double> values(len);
    if (v->class_type == MAT_C_DOUBLE) {
      const auto* d = static_cast<const double*>(v->data);
      std::copy(d, d + len, values.begin());
    } else if (v->class_type == MAT_C_SINGLE) {
      const auto* d = static_cast<const float*>(v->data);
      std::transform(d, d + len, values.begin(), [](float x) { return static_cast<double>(x); });
    } else {
      throw UsageError(w + ": expected double or single values");
    }
    if (raw.names.empty()) {
      n = len;
    } else if (len != n) {
      throw UsageError(w + ": has " + std::to_string(len) + " values, '" + excerpt(raw.names[0]) + "' has " +
                       std::to_string(n));
    }
    raw.names.push_back(name);
    raw.values.push_back(std::move(values));
  }
  const auto names_copy = raw.names;
  raw.where = [label, names_copy](std::size_t row, std::size_t col) {
    return label + ": variable '" + excerpt(names_copy[col]) + "' element " + std::to_string(row + 1);
  };
  raw.where_column = [label, names_copy](std::size_t col) {
    return label + ": variable '" + excerpt(names_copy[col]) + "'";
  };
  return build(std::move(raw), label);
}

}  // namespace

MeasuredData parse_measured_csv(std::string_view text, const std::string& label) {
  text = io::strip_bom(text);
  RawTable raw;
  std::vector<std::size_t> line_of_row;
  std::size_t line_no = 0;
  std::size_t header_line = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = io::trim(text.substr(pos, end - pos));
    pos = end + 1;
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    const std::string where = io::line_prefix(label, line_no);
    const auto fields = io::split_commas(line);
    if (raw.names.empty()) {
      header_line = line_no;
      raw.file_where = where;
      for (const auto f : fields) raw.names.emplace_back(f);
      raw.values.resize(raw.names.size());
      // Check the header now so that it is reported before any data line.
      for (std::size_t c = 0; c < raw.names.size(); ++c) {
        if (parse_double(raw.names[c])) {
          throw UsageError(where + "column " + std::to_string(c + 1) +
                           ": expected a header of named columns with units (e.g. "
                           "time_s,displacement_m,current_cmd_A,force_N), got a number");
        }
      }
      const auto header_names = raw.names;
      (void)header_roles(raw.names, where, [&](std::size_t c) {
        return where + "column " + std::to_string(c + 1) + " '" + excerpt(header_names[c]) + "'";
      });
      continue;
    }
    if (fields.size() != raw.names.size()) {
      throw UsageError(where + "expected " + std::to_string(raw.names.size()) + " fields as in the header, got " +
                       std::to_string(fields.size()));
    }
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const auto v = parse_double(fields[c]);
      if (!v) {
        throw UsageError(where + "column '" + excerpt(raw.names[c]) + "': not a number: '" + excerpt(fields[c]) + "'");
      }
      if (!std::isfinite(*v)) {
        throw UsageError(where + "column '" + excerpt(raw.names[c]) + "': not a finite number: '" + excerpt(fields[c]) +
                         "'");
      }
      raw.values[c].push_back(*v);
    }
    line_of_row.push_back(line_no);
  }
  if (raw.names.empty()) {
    throw UsageError(label + ": empty file (expected a header such as time_s,displacement_m,current_cmd_A,force_N)");
  }
  const auto names = raw.names;
  raw.where = [label, names, line_of_row](std::size_t row, std::size_t col) {
    return io::line_prefix(label, line_of_row[row]) + "column '" + excerpt(names[col]) + "'";
  };
  raw.where_column = [label, names, header_line](std::size_t col) {
    return io::line_prefix(label, header_line) + "column " + std::to_string(col + 1) + " '" + excerpt(names[col]) + "'";
  };
  return build(std::move(raw), label);
}

MeasuredData read_measured(const fs::path& path) {
  std::string ext = io::to_lower(path.extension().string());
  if (ext == ".mat") return read_mat(path);
  return parse_measured_csv(read_text(path), path.string());
}

void write_measured_mat(const MeasuredData& data, const fs::path& path) {
  const std::string tmp = path.string() + ".tmp";
  {
    MatFile mat(Mat_CreateVer(tmp.c_str(), nullptr, MAT_FT_MAT5));
    if (!mat) throw UsageError(path.string() + ": cannot create the .mat file");
    const auto put = [&](const std::string& name, const std::vector<double>& v) {
      std::size_t dims[2] = {v.size(), 1};
      MatVar var(Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                               const_cast<double*>(v.data()), MAT_F_DONT_COPY_DATA));
      if (!var || Mat_VarWrite(mat.get(), var.get(), MAT_COMPRESSION_NONE) != 0) {
        throw UsageError(path.string() + ": cannot write variable '" + name + "'");
      }
    };
    put("time_s", data.time_s);
    put("displacement_m", data.displacement_m);
    if (!data.velocity_m_s.empty()) put("velocity_m_s", data.velocity_m_s);
    put("current_cmd_A", data.current_cmd_a);
    if (!data.current_a.empty()) put("current_A", data.current_a);
    put("force_N", data.force_n);
    for (const auto& e : data.extra) put(e.name, e.values);
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw UsageError(path.string() + ": cannot write the .mat file");
  }
}

std::string measured_to_csv(const MeasuredData& data) {
  std::string out = "time_s,displacement_m";
  const bool vel = !data.velocity_m_s.empty();
  if (vel) out += ",velocity_m_s";
  out += ",current_cmd_A";
  const bool cur = !data.current_a.empty();
  if (cur) out += ",current_A";
  out += ",force_N";
  for (const auto& e : data.extra) out += "," + e.name;
  out += '\n';
  char buf[64];
  const auto add = [&](double v) {
    std::snprintf(buf, sizeof buf, ",%.9g", v);
    out += buf;
  };
  out.reserve(out.size() + data.size() * 64);
  for (std::size_t k = 0; k < data.size(); ++k) {
    std::snprintf(buf, sizeof buf, "%.9g", data.time_s[k]);
    out += buf;
    add(data.displacement_m[k]);
    if (vel) add(data.velocity_m_s[k]);
    add(data.current_cmd_a[k]);
    if (cur) add(data.current_a[k]);
    add(data.force_n[k]);
    for (const auto& e : data.extra) add(e.values[k]);
    out += '\n';
  }
  return out;
}

SmoothedMotion smooth_motion(const std::vector<double>& time_s, const std::vector<double>& displacement_m,
                             double half_window_s) {
  const std::size_t n = time_s.size();
  SmoothedMotion out;
  out.displacement_m.resize(n);
  out.velocity_m_s.resize(n);
  constexpr std::size_t kTerms = kSmoothingDegree + 1;
  if (n < kTerms + 1) {
    out.displacement_m = displacement_m;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t p = k > 0 ? k - 1 : 0;
      const std::size_t q = k + 1 < n ? k + 1 : n - 1;
      out.velocity_m_s[k] = q > p ? (displacement_m[q] - displacement_m[p]) / (time_s[q] - time_s[p]) : 0.0;
    }
    return out;
  }
  constexpr std::size_t kMinSide = 3;
  const double h = std::max(half_window_s, 1e-12);
  std::size_t lo = 0;
  std::size_t hi = 0;  // window is [lo, hi)
  for (std::size_t k = 0; k < n; ++k) {
    const double tk = time_s[k];
    while (lo < k && tk - time_s[lo] > half_window_s) ++lo;
    if (hi < k + 1) hi = k + 1;
    while (hi < n && time_s[hi] - tk <= half_window_s) ++hi;
    std::size_t a = lo;
    std::size_t b = hi;
    if (k - a < kMinSide) a = k >= kMinSide ? k - kMinSide : 0;
    if (b - k - 1 < kMinSide) b = std::min(n, k + 1 + kMinSide);
    while (b - a < kTerms + 1) {  // near the ends: widen on the side that has samples
      if (a > 0) --a;
      if (b - a < kTerms + 1 && b < n) ++b;
    }
    // Least squares in s = (t − t_k)/h: x ≈ Σ c_p s^p, normal equations
    // Σ_q S_{p+q} c_q = Y_p with S_m = Σ s^m, Y_p = Σ x s^p.
    std::array<double, 2 * kSmoothingDegree + 1> sm{};
    std::array<double, kTerms> y{};
    for (std::size_t j = a; j < b; ++j) {
      const double s = (time_s[j] - tk) / h;
      double pw = 1.0;
      for (std::size_t m = 0; m < sm.size(); ++m) {
        sm[m] += pw;
        if (m < kTerms) y[m] += displacement_m[j] * pw;
        pw *= s;
      }
    }
    std::array<std::array<double, kTerms + 1>, kTerms> g{};
    for (std::size_t p = 0; p < kTerms; ++p) {
      for (std::size_t q = 0; q < kTerms; ++q) g[p][q] = sm[p + q];
      g[p][kTerms] = y[p];
    }
    // Gaussian elimination with partial pivoting.
    bool singular = false;
    for (std::size_t c = 0; c < kTerms && !singular; ++c) {
      std::size_t piv = c;
      for (std::size_t r = c + 1; r < kTerms; ++r) {
        if (std::fabs(g[r][c]) > std::fabs(g[piv][c])) piv = r;
      }
      if (std::fabs(g[piv][c]) < 1e-12 * std::max(1.0, sm[0])) {
        singular = true;
        break;
      }
      std::swap(g[c], g[piv]);
      for (std::size_t r = 0; r < kTerms; ++r) {
        if (r == c) continue;
        const double f = g[r][c] / g[c][c];
        for (std::size_t q = c; q <= kTerms; ++q) g[r][q] -= f * g[c][q];
      }
    }
    if (singular) {
      out.displacement_m[k] = displacement_m[k];
      const std::size_t p = k > 0 ? k - 1 : 0;
      const std::size_t q = k + 1 < n ? k + 1 : n - 1;
      out.velocity_m_s[k] = (displacement_m[q] - displacement_m[p]) / (time_s[q] - time_s[p]);
      continue;
    }
    out.displacement_m[k] = g[0][kTerms] / g[0][0];
    out.velocity_m_s[k] = g[1][kTerms] / g[1][1] / h;
  }
  return out;
}

}  // namespace mrd::discrepancy
