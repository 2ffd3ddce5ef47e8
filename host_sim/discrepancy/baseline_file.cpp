#include "host_sim/discrepancy/baseline_file.hpp"

#include <toml++/toml.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <set>

#include "host_sim/discrepancy/physical_ranges.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/report/output_dir.hpp"

namespace mrd::discrepancy {
namespace {

// ---- writing ---------------------------------------------------------------

/// Shortest text that reads back as exactly `v`, always a TOML float.
std::string num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, r.ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string fitted_list(const CurrentLawFitted& f) {
  std::string s = "[";
  const auto add = [&](bool on, const char* name) {
    if (!on) return;
    if (s.size() > 1) s += ", ";
    s += quoted(name);
  };
  add(f.at_zero, "at_zero");
  add(f.limit, "limit");
  add(f.rate_per_a, "rate_per_a");
  return s + "]";
}

/// "key = sigma": a standard error within the range of its quantity's
/// standard errors (sigma_range); a larger one (a parameter the records do
/// not identify, or an infinite one) is written as that range's top with a
/// comment that says so, so that the file reads back.
std::string sigma_line(const std::string& key, double sigma, const PhysicalRange& quantity) {
  const double top = sigma_range(quantity).max;
  if (sigma <= top) return key + " = " + num(sigma) + "\n";
  return key + " = " + num(top) + "  # the fit's standard error, " + num(sigma) +
         ", exceeds the quantity's range: not identified\n";
}

void law_table(std::string& t, const char* name, const char* comment, const CurrentLaw& v, const CurrentLaw& s,
               const CurrentLawFitted& f, const PhysicalRange& value_range) {
  t += std::string("\n[") + name + "]  # " + comment + "\n";
  t += "at_zero = " + num(v.at_zero) + "\n";
  t += sigma_line("at_zero_sigma", s.at_zero, value_range);
  t += "limit = " + num(v.limit) + "\n";
  t += sigma_line("limit_sigma", s.limit, value_range);
  t += "rate_per_a = " + num(v.rate_per_a) + "\n";
  t += sigma_line("rate_per_a_sigma", s.rate_per_a, kCurrentRateRange);
  t += "fitted = " + fitted_list(f) + "  # the others are held (sigma 0)\n";
}

// ---- reading ---------------------------------------------------------------

/// "a force in [0.001, 1e+09] N": what a number of range `r` must be.
std::string range_text(const PhysicalRange& r) {
  std::string t = std::string(r.what) + " in [" + io::format_number("%.6g", r.min) + ", " +
                  io::format_number("%.6g", r.max) + "]";
  if (*r.unit != '\0') t += std::string(" ") + r.unit;
  return t;
}

[[noreturn]] void fail(const std::string& origin, const toml::source_region& where, const std::string& field,
                       const std::string& problem) {
  throw io::UsageError(origin + ":" + std::to_string(std::max<toml::source_index>(where.begin.line, 1)) + ": " +
                       field + ": " + problem);
}

/// The keys of one table; refuses keys it was never asked for.
class Table {
 public:
  Table(const toml::table& t, std::string name, const std::string& origin) : t_(t), name_(std::move(name)), origin_(origin) {}

  /// A finite number inside the physical range `r` (integers accepted).
  double in(const char* key, const PhysicalRange& r) {
    const toml::node& n = need(key);
    const std::optional<double> v = n.is_number() ? n.value<double>() : std::nullopt;
    if (!v) fail(origin_, n.source(), field(key), "expected a number");
    if (!std::isfinite(*v)) fail(origin_, n.source(), field(key), "expected a finite number");
    if (!r.contains(*v)) fail(origin_, n.source(), field(key), "expected " + range_text(r) + ", got " + num(*v));
    return *v;
  }
  bool boolean(const char* key) {
    const toml::node& n = need(key);
    if (!n.is_boolean()) fail(origin_, n.source(), field(key), "expected true or false");
    return *n.value<bool>();
  }
  std::string string(const char* key) {
    const toml::node& n = need(key);
    if (!n.is_string()) fail(origin_, n.source(), field(key), "expected a string");
    return *n.value<std::string>();
  }
  std::vector<std::string> strings(const char* key) {
    const toml::node& n = need(key);
    const toml::array* a = n.as_array();
    if (!a) fail(origin_, n.source(), field(key), "expected an array of strings");
    std::vector<std::string> out;
    for (const toml::node& e : *a) {
      if (!e.is_string()) fail(origin_, e.source(), field(key), "expected an array of strings");
      out.push_back(*e.value<std::string>());
    }
    return out;
  }
  /// An integer in [0, max].
  std::size_t count(const char* key, std::size_t max) {
    const toml::node& n = need(key);
    // value<int64_t>() of a float node converts it (undefined beyond int64's range): integers only.
    const auto v = n.is_integer() ? n.value<std::int64_t>() : std::nullopt;
    if (!v || *v < 0 || static_cast<std::uint64_t>(*v) > max)
      fail(origin_, n.source(), field(key), "expected an integer in [0, " + std::to_string(max) + "]");
    return static_cast<std::size_t>(*v);
  }
  [[nodiscard]] bool has(const char* key) const { return t_.get(key) != nullptr; }
  const toml::source_region& where(const char* key) const {
    const toml::node* n = t_.get(key);
    return n ? n->source() : t_.source();
  }
  void no_unknown_keys() const {
    for (const auto& [k, v] : t_) {
      if (!asked_.count(std::string(k.str()))) fail(origin_, v.source(), field(std::string(k.str()).c_str()), "unknown key");
    }
  }
  std::string field(const char* key) const { return name_ + "." + key; }

 private:
  const toml::node& need(const char* key) {
    asked_.insert(key);
    const toml::node* n = t_.get(key);
    if (!n) fail(origin_, t_.source(), field(key), "missing key");
    return *n;
  }
  const toml::table& t_;
  std::string name_;
  const std::string& origin_;
  std::set<std::string> asked_;
};

const toml::table& table_of(const toml::table& root, const char* name, const std::string& origin) {
  const toml::node* n = root.get(name);
  if (!n) throw io::UsageError(origin + ":1: [" + std::string(name) + "]: missing table");
  const toml::table* t = n->as_table();
  if (!t) fail(origin, n->source(), name, std::string("expected a table [") + name + "]");
  return *t;
}

BaseLaw law_named(const std::string& s, const std::string& origin, const toml::source_region& where,
                  const std::string& field) {
  if (s == "bingham") return BaseLaw::bingham;
  if (s == "bouc_wen") return BaseLaw::bouc_wen;
  fail(origin, where, field, "expected \"bingham\" or \"bouc_wen\", got \"" + s + "\"");
}

/// The `transition` key of table `t`: true for "tanh", false for "linear".
bool transition_named(Table& t, const std::string& origin, const std::string& field) {
  const std::string s = t.string("transition");
  if (s == "tanh") return true;
  if (s == "linear") return false;
  fail(origin, t.where("transition"), field, "expected \"linear\" or \"tanh\", got \"" + s + "\"");
}

void read_law(const toml::table& root, const char* name, const std::string& origin, CurrentLaw& v, CurrentLaw& s,
              CurrentLawFitted& f, const PhysicalRange& value_range) {
  Table t(table_of(root, name, origin), name, origin);
  v.at_zero = t.in("at_zero", value_range);
  s.at_zero = t.in("at_zero_sigma", sigma_range(value_range));
  v.limit = t.in("limit", value_range);
  s.limit = t.in("limit_sigma", sigma_range(value_range));
  v.rate_per_a = t.in("rate_per_a", kCurrentRateRange);
  s.rate_per_a = t.in("rate_per_a_sigma", sigma_range(kCurrentRateRange));
  f = {false, false, false};
  for (const std::string& p : t.strings("fitted")) {
    if (p == "at_zero") {
      f.at_zero = true;
    } else if (p == "limit") {
      f.limit = true;
    } else if (p == "rate_per_a") {
      f.rate_per_a = true;
    } else {
      fail(origin, t.where("fitted"), t.field("fitted"), "expected at_zero, limit or rate_per_a, got \"" + p + "\"");
    }
  }
  t.no_unknown_keys();
}

}  // namespace

BaselineFile baseline_file_of(const CalibrationResult& r) {
  BaselineFile f;
  const LawFit& best = r.best();
  f.baseline = best.baseline;
  f.sigma = best.sigma;
  f.yield_fitted = best.yield_fitted;
  f.viscous_fitted = best.viscous_fitted;
  f.source_records = r.sources;
  for (const LawFit& fit : r.fits) {
    for (std::size_t i = 0; i < r.sources.size(); ++i)
      f.fits.push_back({r.sources[i], fit.baseline.law, fit.record_gaps.at(i), r.record_samples.at(i),
                        fit.baseline.has_lost_motion(), fit.baseline.has_transition_time(),
                        fit.baseline.has_tanh_transition(), fit.baseline.has_viscous_lost_motion()});
  }
  return f;
}

std::string baseline_toml(const BaselineFile& f) {
  const Baseline& b = f.baseline;
  const ValidityRange& v = b.range;
  std::string t;
  t += "# Damper baseline for `mrd discrepancy --baseline` (written by `mrd calibrate`). SI units.\n";
  t += "\n[model]\n";
  t += "law = " + quoted(base_law_name(b.law)) + "  # bingham: Eq. 4.1-4.4; bouc_wen: Spencer et al. (1997), normalized\n";
  t += "name = " + quoted(b.name) + "\n";
  t += "source_records = [";
  for (std::size_t i = 0; i < f.source_records.size(); ++i) t += (i ? ", " : "") + quoted(f.source_records[i]);
  t += "]\n";
  law_table(t, "yield_n", "Y(I) = limit + (at_zero - limit) exp(-rate_per_a |I|), N (Eq. 4.2)", b.yield_n,
            f.sigma.yield_n, f.yield_fitted, kYieldForceRange);
  law_table(t, "viscous_ns_m", "C(I), the same law, N s/m (Eq. 4.3)", b.viscous_ns_m, f.sigma.viscous_ns_m,
            f.viscous_fitted, kViscousRange);
  if (b.law == BaseLaw::bingham) {
    t += std::string("\n[bingham]  # transition function, ") + (b.has_tanh_transition() ? "tanh" : "Eq. 4.4") + "\n";
    t += "v_tf_m_s = " + num(b.v_tf_m_s) + "\n";
    t += sigma_line("v_tf_m_s_sigma", f.sigma.v_tf_m_s, kVelocityBandRange);
    if (b.has_tanh_transition()) t += "transition = \"tanh\"  # F = Y tanh(v / v_tf_m_s) + C v\n";
    if (b.has_transition_time()) {
      t += "transition_time_s = " + num(b.transition_time_s) + "  # the band is v_tf_m_s + transition_time_s |a|\n";
      t += sigma_line("transition_time_s_sigma", f.sigma.transition_time_s, kTransitionTimeRange);
    }
  } else {
    t += "\n[bouc_wen]  # F = Y z + C v + k0 x, z' = (v/x_y)(1 - |z|^2 (1/2 + 1/2 sgn(v z)))\n";
    t += "yield_disp_m = " + num(b.yield_disp_m) + "\n";
    t += sigma_line("yield_disp_m_sigma", f.sigma.yield_disp_m, kYieldDispRange);
    t += "stiffness_n_m = " + num(b.stiffness_n_m) + "\n";
    t += sigma_line("stiffness_n_m_sigma", f.sigma.stiffness_n_m, kStiffnessRange);
  }
  if (b.has_lost_motion()) {
    t += "\n[lost_motion]  # F = F_law ((1 - share) + share e) + (1 - e) Y(I) tanh(v / band_m_s), e: play of width "
         "m_per_n Y(I) at reversals\n";
    t += "m_per_n = " + num(b.lost_motion_m_per_n) + "\n";
    t += sigma_line("m_per_n_sigma", f.sigma.lost_motion_m_per_n, kPlayRange);
    t += "share = " + num(b.lost_motion_share) + "\n";
    t += sigma_line("share_sigma", f.sigma.lost_motion_share, kShareRange);
    if (b.has_viscous_lost_motion()) {
      t += "band_m_s = " + num(b.lost_motion_band_m_s) + "  # the force inside the play\n";
      t += sigma_line("band_m_s_sigma", f.sigma.lost_motion_band_m_s, kVelocityBandRange);
    }
  }
  t += "\n[channels]  # the force channel's lag behind the motion channels\n";
  t += "force_delay_s = " + num(b.force_delay_s) + "\n";
  t += sigma_line("force_delay_s_sigma", f.sigma.force_delay_s, kForceDelayRange);
  t += "\n[coil]  # Eq. 4.5";
  t += b.coil_identified ? ", fitted to the records whose current changes\n"
                         : ": assumed (thesis values), not identified from the records\n";
  t += "tau_slow_s = " + num(b.coil.tau_slow_s) + "\n";
  if (b.coil_identified) t += sigma_line("tau_slow_s_sigma", f.sigma.coil_tau_slow_s, kCoilTimeConstantRange);
  t += "tau_fast_s = " + num(b.coil.tau_fast_s) + "\n";
  if (b.coil_identified) t += sigma_line("tau_fast_s_sigma", f.sigma.coil_tau_fast_s, kCoilTimeConstantRange);
  t += "weight_slow = " + num(b.coil.weight_slow) + "\n";
  t += "weight_fast = " + num(b.coil.weight_fast) + "\n";
  t += std::string("identified = ") + (b.coil_identified ? "true" : "false") + "\n";
  const auto& p = b.pr;
  t += "\n[participant_ratio]  # Eq. 5.6-5.11, Table 5.6";
  t += f.pr_identified ? "\n" : ": assumed (thesis values), not identified from the records\n";
  t += "a_initial = " + num(p.a_initial) + "\n";
  t += "b_initial = " + num(p.b_initial) + "\n";
  t += "c_initial = " + num(p.c_initial) + "\n";
  t += "a_final = " + num(p.a_final) + "\n";
  t += "b_final = " + num(p.b_final) + "\n";
  t += "c_final = " + num(p.c_final) + "\n";
  t += "a_rise = " + num(p.a_rise) + "\n";
  t += "b_rise = " + num(p.b_rise) + "\n";
  t += "c_rise = " + num(p.c_rise) + "\n";
  t += "flow_area_m2 = " + num(p.flow_area_m2) + "\n";
  t += "volume_unit_m3 = " + num(p.volume_unit_m3) + "\n";
  t += std::string("identified = ") + (f.pr_identified ? "true" : "false") + "\n";
  t += "\n[validity]  # the conditions the records cover\n";
  t += "current_min_a = " + num(v.current_min_a) + "\n";
  t += "current_max_a = " + num(v.current_max_a) + "\n";
  t += "velocity_max_m_s = " + num(v.velocity_max_m_s) + "\n";
  t += "force_peak_n = " + num(v.force_peak_n) + "\n";
  t += "amplitude_min_m = " + num(v.amplitude_min_m) + "\n";
  t += "amplitude_max_m = " + num(v.amplitude_max_m) + "\n";
  t += "frequency_min_hz = " + num(v.frequency_min_hz) + "\n";
  t += "frequency_max_hz = " + num(v.frequency_max_hz) + "\n";
  t += "expected_gap = " + num(b.expected_gap) + "  # largest normalized RMS gap of the calibration records\n";
  for (const RecordFit& r : f.fits) {
    t += "\n[[fit]]\n";
    t += "file = " + quoted(r.file) + "\n";
    t += "law = " + quoted(base_law_name(r.law)) + "\n";
    if (r.tanh_transition) t += "transition = \"tanh\"\n";
    if (r.transition_time) t += "transition_time = true\n";
    if (r.lost_motion) t += "lost_motion = true\n";
    if (r.viscous_lost_motion) t += "viscous_lost_motion = true\n";
    t += "gap = " + num(r.gap) + "\n";
    t += "samples = " + std::to_string(r.samples) + "\n";
  }
  return t;
}

BaselineFile parse_baseline_toml(const std::string& text, const std::string& origin) {
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw io::UsageError(origin + ":" + std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
  }
  BaselineFile f;
  Baseline& b = f.baseline;
  b = thesis_baseline();
  for (const auto& [k, v] : root) {
    const std::string key(k.str());
    if (key != "model" && key != "yield_n" && key != "viscous_ns_m" && key != "bingham" && key != "bouc_wen" &&
        key != "lost_motion" && key != "channels" && key != "coil" && key != "participant_ratio" && key != "validity" && key != "fit")
      fail(origin, v.source(), key,
           "unknown table (expected model, yield_n, viscous_ns_m, bingham or bouc_wen, lost_motion, channels, coil, "
           "participant_ratio, validity, fit)");
  }
  {
    Table m(table_of(root, "model", origin), "model", origin);
    b.law = law_named(m.string("law"), origin, m.where("law"), "model.law");
    b.name = m.string("name");
    f.source_records = m.strings("source_records");
    m.no_unknown_keys();
  }
  read_law(root, "yield_n", origin, b.yield_n, f.sigma.yield_n, f.yield_fitted, kYieldForceRange);
  read_law(root, "viscous_ns_m", origin, b.viscous_ns_m, f.sigma.viscous_ns_m, f.viscous_fitted, kViscousRange);
  const char* own = b.law == BaseLaw::bingham ? "bingham" : "bouc_wen";
  const char* other = b.law == BaseLaw::bingham ? "bouc_wen" : "bingham";
  if (const toml::node* n = root.get(other))
    fail(origin, n->source(), other, std::string("not allowed with model.law = \"") + own + "\"");
  {
    Table t(table_of(root, own, origin), own, origin);
    if (b.law == BaseLaw::bingham) {
      b.v_tf_m_s = t.in("v_tf_m_s", kVelocityBandRange);
      f.sigma.v_tf_m_s = t.in("v_tf_m_s_sigma", sigma_range(kVelocityBandRange));
      if (t.has("transition")) b.tanh_transition = transition_named(t, origin, "bingham.transition");
      if (t.has("transition_time_s")) {
        b.transition_time_s = t.in("transition_time_s", kTransitionTimeRange);
        f.sigma.transition_time_s = t.in("transition_time_s_sigma", sigma_range(kTransitionTimeRange));
      }
    } else {
      b.yield_disp_m = t.in("yield_disp_m", kYieldDispRange);
      f.sigma.yield_disp_m = t.in("yield_disp_m_sigma", sigma_range(kYieldDispRange));
      b.stiffness_n_m = t.in("stiffness_n_m", kStiffnessRange);
      f.sigma.stiffness_n_m = t.in("stiffness_n_m_sigma", sigma_range(kStiffnessRange));
    }
    t.no_unknown_keys();
  }
  if (root.get("lost_motion") != nullptr) {
    Table t(table_of(root, "lost_motion", origin), "lost_motion", origin);
    b.lost_motion_m_per_n = t.in("m_per_n", kPlayRange);
    f.sigma.lost_motion_m_per_n = t.in("m_per_n_sigma", sigma_range(kPlayRange));
    b.lost_motion_share = t.in("share", kShareRange);
    f.sigma.lost_motion_share = t.in("share_sigma", sigma_range(kShareRange));
    if (t.has("band_m_s")) {
      b.lost_motion_band_m_s = t.in("band_m_s", kVelocityBandRange);
      f.sigma.lost_motion_band_m_s = t.in("band_m_s_sigma", sigma_range(kVelocityBandRange));
    }
    t.no_unknown_keys();
  }
  {
    Table ch(table_of(root, "channels", origin), "channels", origin);
    b.force_delay_s = ch.in("force_delay_s", kForceDelayRange);
    f.sigma.force_delay_s = ch.in("force_delay_s_sigma", sigma_range(kForceDelayRange));
    ch.no_unknown_keys();
  }
  {
    Table c(table_of(root, "coil", origin), "coil", origin);
    b.coil.tau_slow_s = c.in("tau_slow_s", kCoilTimeConstantRange);
    b.coil.tau_fast_s = c.in("tau_fast_s", kCoilTimeConstantRange);
    b.coil.weight_slow = c.in("weight_slow", kCoilWeightRange);
    b.coil.weight_fast = c.in("weight_fast", kCoilWeightRange);
    b.coil_identified = c.boolean("identified");
    const PhysicalRange tau_sigma = sigma_range(kCoilTimeConstantRange);
    if (c.has("tau_slow_s_sigma")) f.sigma.coil_tau_slow_s = c.in("tau_slow_s_sigma", tau_sigma);
    if (c.has("tau_fast_s_sigma")) f.sigma.coil_tau_fast_s = c.in("tau_fast_s_sigma", tau_sigma);
    if (std::fabs(b.coil.weight_slow + b.coil.weight_fast - 1.0) > 1e-9)
      fail(origin, c.where("weight_fast"), "coil.weight_fast", "expected weight_slow + weight_fast = 1 (unity DC gain)");
    c.no_unknown_keys();
  }
  {
    Table p(table_of(root, "participant_ratio", origin), "participant_ratio", origin);
    auto& q = b.pr;
    q.a_initial = p.in("a_initial", kParticipantRatioRange);
    q.b_initial = p.in("b_initial", kParticipantRatioRange);
    q.c_initial = p.in("c_initial", kSettlingRateRange);
    q.a_final = p.in("a_final", kParticipantRatioRange);
    q.b_final = p.in("b_final", kParticipantRatioRange);
    q.c_final = p.in("c_final", kSettlingRateRange);
    q.a_rise = p.in("a_rise", kMixingRateRange);
    q.b_rise = p.in("b_rise", kMixingRateRange);
    q.c_rise = p.in("c_rise", kSettlingRateRange);
    q.flow_area_m2 = p.in("flow_area_m2", kFlowAreaRange);
    q.volume_unit_m3 = p.in("volume_unit_m3", kVolumeUnitRange);
    f.pr_identified = p.boolean("identified");
    p.no_unknown_keys();
  }
  {
    Table v(table_of(root, "validity", origin), "validity", origin);
    auto& r = b.range;
    r.current_min_a = v.in("current_min_a", kRecordCurrentRange);
    r.current_max_a = v.in("current_max_a", kRecordCurrentRange);
    r.velocity_max_m_s = v.in("velocity_max_m_s", kRecordVelocityRange);
    r.force_peak_n = v.in("force_peak_n", kRecordForceRange);
    r.amplitude_min_m = v.in("amplitude_min_m", kRecordAmplitudeRange);
    r.amplitude_max_m = v.in("amplitude_max_m", kRecordAmplitudeRange);
    r.frequency_min_hz = v.in("frequency_min_hz", kRecordFrequencyRange);
    r.frequency_max_hz = v.in("frequency_max_hz", kRecordFrequencyRange);
    b.expected_gap = v.in("expected_gap", kGapRange);
    const auto order = [&](double lo, double hi, const char* key, const char* what) {
      if (lo > hi) fail(origin, v.where(key), v.field(key), std::string("expected at least ") + what + " (" + num(lo) + ")");
    };
    order(r.current_min_a, r.current_max_a, "current_max_a", "current_min_a");
    order(r.amplitude_min_m, r.amplitude_max_m, "amplitude_max_m", "amplitude_min_m");
    order(r.frequency_min_hz, r.frequency_max_hz, "frequency_max_hz", "frequency_min_hz");
    v.no_unknown_keys();
  }
  if (const toml::node* n = root.get("fit")) {
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables()) fail(origin, n->source(), "fit", "expected [[fit]] tables");
    std::size_t i = 0;
    for (const toml::node& e : *a) {
      Table t(*e.as_table(), "fit[" + std::to_string(i++) + "]", origin);
      RecordFit r;
      r.file = t.string("file");
      r.law = law_named(t.string("law"), origin, t.where("law"), t.field("law"));
      if (t.has("transition")) r.tanh_transition = transition_named(t, origin, t.field("transition"));
      if (t.has("transition_time")) r.transition_time = t.boolean("transition_time");
      if (t.has("lost_motion")) r.lost_motion = t.boolean("lost_motion");
      if (t.has("viscous_lost_motion")) r.viscous_lost_motion = t.boolean("viscous_lost_motion");
      r.gap = t.in("gap", kGapRange);
      r.samples = t.count("samples", kMaxRecordSamples);
      t.no_unknown_keys();
      f.fits.push_back(std::move(r));
    }
  }
  return f;
}

BaselineFile read_baseline_file(const std::filesystem::path& path) {
  return parse_baseline_toml(io::read_regular_file(path, kMaxBaselineFileBytes), io::file_label(path));
}

void write_baseline_file(const BaselineFile& f, const std::filesystem::path& path) {
  report::write_file_atomically(path, baseline_toml(f));
}

}  // namespace mrd::discrepancy
