#include "host_sim/discrepancy/baseline_file.hpp"

#include <toml++/toml.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

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

void law_table(std::string& t, const char* name, const char* comment, const CurrentLaw& v, const CurrentLaw& s,
               const CurrentLawFitted& f) {
  t += std::string("\n[") + name + "]  # " + comment + "\n";
  t += "at_zero = " + num(v.at_zero) + "\n";
  t += "at_zero_sigma = " + num(s.at_zero) + "\n";
  t += "limit = " + num(v.limit) + "\n";
  t += "limit_sigma = " + num(s.limit) + "\n";
  t += "rate_per_a = " + num(v.rate_per_a) + "\n";
  t += "rate_per_a_sigma = " + num(s.rate_per_a) + "\n";
  t += "fitted = " + fitted_list(f) + "  # the others are held (sigma 0)\n";
}

// ---- reading ---------------------------------------------------------------

[[noreturn]] void fail(const std::string& origin, const toml::source_region& where, const std::string& field,
                       const std::string& problem) {
  throw io::UsageError(origin + ":" + std::to_string(std::max<toml::source_index>(where.begin.line, 1)) + ": " +
                       field + ": " + problem);
}

/// The keys of one table; refuses keys it was never asked for.
class Table {
 public:
  Table(const toml::table& t, std::string name, const std::string& origin) : t_(t), name_(std::move(name)), origin_(origin) {}

  /// A finite number ≥ `min` (integers accepted).
  double number(const char* key, double min = 0.0) {
    const toml::node& n = need(key);
    const std::optional<double> v = n.is_number() ? n.value<double>() : std::nullopt;
    if (!v) fail(origin_, n.source(), field(key), "expected a number");
    if (!std::isfinite(*v)) fail(origin_, n.source(), field(key), "expected a finite number");
    if (*v < min) fail(origin_, n.source(), field(key), "expected a number >= " + num(min) + ", got " + num(*v));
    return *v;
  }
  /// A number > 0.
  double positive(const char* key) {
    const double v = number(key, 0.0);
    if (!(v > 0.0)) fail(origin_, t_.get(key)->source(), field(key), "expected a number > 0");
    return v;
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
  std::size_t count(const char* key) {
    const toml::node& n = need(key);
    const auto v = n.value<std::int64_t>();
    if (!n.is_integer() || !v || *v < 0) fail(origin_, n.source(), field(key), "expected an integer >= 0");
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
              CurrentLawFitted& f) {
  Table t(table_of(root, name, origin), name, origin);
  v.at_zero = t.positive("at_zero");
  s.at_zero = t.number("at_zero_sigma");
  v.limit = t.positive("limit");
  s.limit = t.number("limit_sigma");
  v.rate_per_a = t.number("rate_per_a");
  s.rate_per_a = t.number("rate_per_a_sigma");
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
            f.sigma.yield_n, f.yield_fitted);
  law_table(t, "viscous_ns_m", "C(I), the same law, N s/m (Eq. 4.3)", b.viscous_ns_m, f.sigma.viscous_ns_m,
            f.viscous_fitted);
  if (b.law == BaseLaw::bingham) {
    t += std::string("\n[bingham]  # transition function, ") + (b.has_tanh_transition() ? "tanh" : "Eq. 4.4") + "\n";
    t += "v_tf_m_s = " + num(b.v_tf_m_s) + "\n";
    t += "v_tf_m_s_sigma = " + num(f.sigma.v_tf_m_s) + "\n";
    if (b.has_tanh_transition()) t += "transition = \"tanh\"  # F = Y tanh(v / v_tf_m_s) + C v\n";
    if (b.has_transition_time()) {
      t += "transition_time_s = " + num(b.transition_time_s) + "  # the band is v_tf_m_s + transition_time_s |a|\n";
      t += "transition_time_s_sigma = " + num(f.sigma.transition_time_s) + "\n";
    }
  } else {
    t += "\n[bouc_wen]  # F = Y z + C v + k0 x, z' = (v/x_y)(1 - |z|^2 (1/2 + 1/2 sgn(v z)))\n";
    t += "yield_disp_m = " + num(b.yield_disp_m) + "\n";
    t += "yield_disp_m_sigma = " + num(f.sigma.yield_disp_m) + "\n";
    t += "stiffness_n_m = " + num(b.stiffness_n_m) + "\n";
    t += "stiffness_n_m_sigma = " + num(f.sigma.stiffness_n_m) + "\n";
  }
  if (b.has_lost_motion()) {
    t += "\n[lost_motion]  # F = F_law ((1 - share) + share e) + (1 - e) Y(I) tanh(v / band_m_s), e: play of width "
         "m_per_n Y(I) at reversals\n";
    t += "m_per_n = " + num(b.lost_motion_m_per_n) + "\n";
    t += "m_per_n_sigma = " + num(f.sigma.lost_motion_m_per_n) + "\n";
    t += "share = " + num(b.lost_motion_share) + "\n";
    t += "share_sigma = " + num(f.sigma.lost_motion_share) + "\n";
    if (b.has_viscous_lost_motion()) {
      t += "band_m_s = " + num(b.lost_motion_band_m_s) + "  # the force inside the play\n";
      t += "band_m_s_sigma = " + num(f.sigma.lost_motion_band_m_s) + "\n";
    }
  }
  t += "\n[channels]  # the force channel's lag behind the motion channels\n";
  t += "force_delay_s = " + num(b.force_delay_s) + "\n";
  t += "force_delay_s_sigma = " + num(f.sigma.force_delay_s) + "\n";
  t += "\n[coil]  # Eq. 4.5";
  t += b.coil_identified ? ", fitted to the records whose current changes\n"
                         : ": assumed (thesis values), not identified from the records\n";
  t += "tau_slow_s = " + num(b.coil.tau_slow_s) + "\n";
  if (b.coil_identified) t += "tau_slow_s_sigma = " + num(f.sigma.coil_tau_slow_s) + "\n";
  t += "tau_fast_s = " + num(b.coil.tau_fast_s) + "\n";
  if (b.coil_identified) t += "tau_fast_s_sigma = " + num(f.sigma.coil_tau_fast_s) + "\n";
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
  read_law(root, "yield_n", origin, b.yield_n, f.sigma.yield_n, f.yield_fitted);
  read_law(root, "viscous_ns_m", origin, b.viscous_ns_m, f.sigma.viscous_ns_m, f.viscous_fitted);
  const char* own = b.law == BaseLaw::bingham ? "bingham" : "bouc_wen";
  const char* other = b.law == BaseLaw::bingham ? "bouc_wen" : "bingham";
  if (const toml::node* n = root.get(other))
    fail(origin, n->source(), other, std::string("not allowed with model.law = \"") + own + "\"");
  {
    Table t(table_of(root, own, origin), own, origin);
    if (b.law == BaseLaw::bingham) {
      b.v_tf_m_s = t.positive("v_tf_m_s");
      f.sigma.v_tf_m_s = t.number("v_tf_m_s_sigma");
      if (t.has("transition")) b.tanh_transition = transition_named(t, origin, "bingham.transition");
      if (t.has("transition_time_s")) {
        b.transition_time_s = t.positive("transition_time_s");
        f.sigma.transition_time_s = t.number("transition_time_s_sigma");
        if (b.transition_time_s > 0.1)
          fail(origin, t.where("transition_time_s"), "bingham.transition_time_s", "expected a time in (0, 0.1] s");
      }
    } else {
      b.yield_disp_m = t.positive("yield_disp_m");
      f.sigma.yield_disp_m = t.number("yield_disp_m_sigma");
      b.stiffness_n_m = t.number("stiffness_n_m");
      f.sigma.stiffness_n_m = t.number("stiffness_n_m_sigma");
    }
    t.no_unknown_keys();
  }
  if (root.get("lost_motion") != nullptr) {
    Table t(table_of(root, "lost_motion", origin), "lost_motion", origin);
    b.lost_motion_m_per_n = t.positive("m_per_n");
    f.sigma.lost_motion_m_per_n = t.number("m_per_n_sigma");
    b.lost_motion_share = t.positive("share");
    f.sigma.lost_motion_share = t.number("share_sigma");
    if (b.lost_motion_share > 1.0) fail(origin, t.where("share"), "lost_motion.share", "expected a share in (0, 1]");
    if (t.has("band_m_s")) {
      b.lost_motion_band_m_s = t.positive("band_m_s");
      f.sigma.lost_motion_band_m_s = t.number("band_m_s_sigma");
    }
    t.no_unknown_keys();
  }
  {
    Table ch(table_of(root, "channels", origin), "channels", origin);
    b.force_delay_s = ch.number("force_delay_s");
    f.sigma.force_delay_s = ch.number("force_delay_s_sigma");
    if (b.force_delay_s < 0.0 || b.force_delay_s > 0.1)
      fail(origin, ch.where("force_delay_s"), "channels.force_delay_s", "expected a lag in [0, 0.1] s");
    ch.no_unknown_keys();
  }
  {
    Table c(table_of(root, "coil", origin), "coil", origin);
    b.coil.tau_slow_s = c.positive("tau_slow_s");
    b.coil.tau_fast_s = c.positive("tau_fast_s");
    b.coil.weight_slow = c.number("weight_slow");
    b.coil.weight_fast = c.number("weight_fast");
    b.coil_identified = c.boolean("identified");
    if (c.has("tau_slow_s_sigma")) f.sigma.coil_tau_slow_s = c.number("tau_slow_s_sigma");
    if (c.has("tau_fast_s_sigma")) f.sigma.coil_tau_fast_s = c.number("tau_fast_s_sigma");
    if (std::fabs(b.coil.weight_slow + b.coil.weight_fast - 1.0) > 1e-9)
      fail(origin, c.where("weight_fast"), "coil.weight_fast", "expected weight_slow + weight_fast = 1 (unity DC gain)");
    c.no_unknown_keys();
  }
  {
    Table p(table_of(root, "participant_ratio", origin), "participant_ratio", origin);
    auto& q = b.pr;
    q.a_initial = p.number("a_initial");
    q.b_initial = p.number("b_initial");
    q.c_initial = p.number("c_initial");
    q.a_final = p.number("a_final");
    q.b_final = p.number("b_final");
    q.c_final = p.number("c_final");
    q.a_rise = p.number("a_rise");
    q.b_rise = p.number("b_rise");
    q.c_rise = p.number("c_rise");
    q.flow_area_m2 = p.positive("flow_area_m2");
    q.volume_unit_m3 = p.positive("volume_unit_m3");
    f.pr_identified = p.boolean("identified");
    p.no_unknown_keys();
  }
  {
    Table v(table_of(root, "validity", origin), "validity", origin);
    auto& r = b.range;
    r.current_min_a = v.number("current_min_a");
    r.current_max_a = v.number("current_max_a");
    r.velocity_max_m_s = v.positive("velocity_max_m_s");
    r.force_peak_n = v.positive("force_peak_n");
    r.amplitude_min_m = v.number("amplitude_min_m");
    r.amplitude_max_m = v.number("amplitude_max_m");
    r.frequency_min_hz = v.number("frequency_min_hz");
    r.frequency_max_hz = v.number("frequency_max_hz");
    b.expected_gap = v.number("expected_gap");
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
      r.gap = t.number("gap");
      r.samples = t.count("samples");
      t.no_unknown_keys();
      f.fits.push_back(std::move(r));
    }
  }
  return f;
}

BaselineFile read_baseline_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io::UsageError(path.string() + ": cannot read the baseline file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_baseline_toml(ss.str(), path.string());
}

void write_baseline_file(const BaselineFile& f, const std::filesystem::path& path) {
  report::write_file_atomically(path, baseline_toml(f));
}

}  // namespace mrd::discrepancy
