#include "building_toml.hpp"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <toml++/toml.h>

namespace ibuild {
namespace {

[[noreturn]] void refuse(const std::string& origin, const toml::source_region& where, const std::string& field,
                         const std::string& problem) {
  const auto line = where.begin.line > 0 ? where.begin.line : 1;
  throw std::runtime_error(origin + ":" + std::to_string(line) + ": " + field + ": " + problem);
}

/// One TOML table read key by key; keys never read are refused at the end.
class Keys {
 public:
  Keys(const toml::table& t, std::string name, std::string origin)
      : t_(t), name_(std::move(name)), origin_(std::move(origin)) {}

  bool has(const char* key) const { return t_.get(key) != nullptr; }

  double number(const char* key) {
    const toml::node& n = need(key);
    const std::optional<double> v = n.is_number() ? n.value<double>() : std::nullopt;
    if (!v || !std::isfinite(*v)) refuse(origin_, n.source(), field(key), "expected a finite number");
    return *v;
  }
  double number_or(const char* key, double fallback) { return has(key) ? number(key) : fallback; }

  unsigned whole(const char* key) {
    const toml::node& n = need(key);
    const std::optional<std::int64_t> v = n.is_integer() ? n.value<std::int64_t>() : std::nullopt;
    if (!v || *v < 0 || *v > 1000000) refuse(origin_, n.source(), field(key), "expected a whole number >= 0");
    return static_cast<unsigned>(*v);
  }
  unsigned whole_or(const char* key, unsigned fallback) { return has(key) ? whole(key) : fallback; }

  std::string text(const char* key) {
    const toml::node& n = need(key);
    if (!n.is_string()) refuse(origin_, n.source(), field(key), "expected a string");
    return *n.value<std::string>();
  }

  std::vector<double> numbers(const char* key) {
    const toml::node& n = need(key);
    const toml::array* a = n.as_array();
    if (!a) refuse(origin_, n.source(), field(key), "expected an array of numbers");
    std::vector<double> out;
    for (const toml::node& e : *a) {
      const std::optional<double> v = e.is_number() ? e.value<double>() : std::nullopt;
      if (!v || !std::isfinite(*v)) refuse(origin_, e.source(), field(key), "expected an array of finite numbers");
      out.push_back(*v);
    }
    return out;
  }

  const toml::table& table(const char* key) {
    const toml::node& n = need(key);
    if (!n.is_table()) refuse(origin_, n.source(), field(key), "expected a table");
    return *n.as_table();
  }

  const toml::source_region& where(const char* key) const {
    const toml::node* n = t_.get(key);
    return n ? n->source() : t_.source();
  }
  std::string field(const char* key) const { return name_.empty() ? std::string(key) : name_ + "." + key; }
  [[noreturn]] void fail(const char* key, const std::string& problem) const {
    refuse(origin_, where(key), field(key), problem);
  }

  void refuse_unread() const {
    for (const auto& [k, v] : t_) {
      const std::string key(k.str());
      if (!read_.count(key)) refuse(origin_, v.source(), name_ + "." + key, "unknown key");
    }
  }

 private:
  const toml::node& need(const char* key) {
    read_.insert(key);
    const toml::node* n = t_.get(key);
    if (!n) refuse(origin_, t_.source(), field(key), "missing");
    return *n;
  }

  const toml::table& t_;
  std::string name_;
  std::string origin_;
  std::set<std::string> read_;
};

IsolatorGroup read_isolator(Keys& k) {
  IsolatorGroup g;
  const std::string kind = k.text("kind");
  g.count = k.whole_or("count", 1);
  g.yield_displacement_m = k.number("yield_displacement_m");
  g.exponent = k.number_or("exponent", 2.0);
  (void)k.number_or("displacement_capacity_m", 0.0);
  if (kind == "lead_rubber") {
    g.kind = IsolatorKind::kLeadRubber;
    g.characteristic_strength_n = k.number("characteristic_strength_n");
    g.post_yield_stiffness_n_m = k.number("post_yield_stiffness_n_m");
  } else if (kind == "friction_pendulum") {
    g.kind = IsolatorKind::kFrictionPendulum;
    g.radius_m = k.number("radius_m");
    g.friction_slow = k.number("friction_slow");
    g.friction_fast = k.number("friction_fast");
    g.rate_s_per_m = k.number("rate_s_per_m");
    g.weight_n = k.number_or("weight_n", 0.0);
  } else {
    k.fail("kind", "expected lead_rubber or friction_pendulum, got '" + kind + "'");
  }
  return g;
}

template <class Read>
void each_entry(const toml::table& root, const char* key, const std::string& origin, Read&& read) {
  const toml::node* n = root.get(key);
  if (!n) return;
  const toml::array* a = n->as_array();
  if (!a) refuse(origin, n->source(), key, "expected [[" + std::string(key) + "]] entries");
  std::size_t i = 0;
  for (const toml::node& e : *a) {
    if (!e.is_table()) refuse(origin, e.source(), key, "expected [[" + std::string(key) + "]] entries");
    Keys k(*e.as_table(), std::string(key) + "[" + std::to_string(i++) + "]", origin);
    read(k);
    k.refuse_unread();
  }
}

Building read_root(const toml::table& root, const std::string& origin) {
  Building b;
  Keys top(root, "", origin);
  Keys bk(top.table("building"), "building", origin);
  b.name = bk.has("name") ? bk.text("name") : "";
  if (bk.has("base")) {
    const std::string base = bk.text("base");
    if (base == "fixed") {
      b.base = Base::kFixed;
    } else if (base != "isolated") {
      bk.fail("base", "expected isolated or fixed, got '" + base + "'");
    }
  }
  b.mass_kg = bk.numbers("mass_kg");
  b.stiffness_n_m = bk.numbers("stiffness_n_m");
  if (b.stiffness_n_m.size() != b.mass_kg.size())
    bk.fail("stiffness_n_m", "expected as many entries as mass_kg");
  if (bk.has("rayleigh")) {
    Keys rk(bk.table("rayleigh"), "building.rayleigh", origin);
    RayleighSpec r;
    r.ratio = rk.number("ratio");
    const std::vector<double> modes = rk.numbers("modes");
    if (modes.size() != 2 || modes[0] < 1 || modes[1] <= modes[0] || modes[1] > static_cast<double>(b.mass_kg.size()) ||
        modes[0] != std::floor(modes[0]) || modes[1] != std::floor(modes[1]))
      rk.fail("modes", "expected two increasing mode numbers 1..N");
    r.mode_a = static_cast<int>(modes[0]);
    r.mode_b = static_cast<int>(modes[1]);
    rk.refuse_unread();
    b.rayleigh = r;
    if (bk.has("damping_n_s_m")) bk.fail("damping_n_s_m", "Rayleigh damping is given too");
  } else {
    b.damping_n_s_m = bk.numbers("damping_n_s_m");
    if (b.damping_n_s_m.size() != b.mass_kg.size())
      bk.fail("damping_n_s_m", "expected as many entries as mass_kg");
  }
  bk.refuse_unread();
  each_entry(root, "isolator", origin, [&](Keys& k) { b.isolators.push_back(read_isolator(k)); });
  each_entry(root, "damper", origin, [&](Keys& k) {
    DamperGroup d;
    d.element = static_cast<int>(k.whole("element"));
    d.count = k.whole_or("count", 1);
    if (d.element >= b.dofs()) k.fail("element", "expected an element 0..N-1");
    b.dampers.push_back(d);
  });
  for (const auto& [key, node] : root) {
    const std::string name(key.str());
    if (name != "building" && name != "isolator" && name != "damper") refuse(origin, node.source(), name, "unknown table");
  }
  return b;
}

}  // namespace

Building parse_building(const std::string& text, const std::string& origin) {
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    refuse(origin, e.source(), "syntax", std::string(e.description()));
  }
  return read_root(root, origin);
}

Building read_building_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot open the building file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_building(ss.str(), file.string());
}

}  // namespace ibuild
