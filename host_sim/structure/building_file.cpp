#include "host_sim/structure/building_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "mrd/units.hpp"

namespace mrd::structure {
namespace {

// ---- physical bounds (each with its reason) ---------------------------------

/// Bearings of one [[isolator]] group. The largest isolated buildings rest on
/// about 2000 bearings; more than 10000 is a typing error.
constexpr std::int64_t kMaxIsolatorCount = 10000;
/// Dampers of one [[damper]] table: a story holds a few dozen at most.
constexpr std::int64_t kMaxDamperCount = 1000;
/// The Bouc–Wen yield displacement D_y: lead-rubber bearings 10–30 mm,
/// friction pendulums 0.1–1 mm (the elastic slip before sliding). Beyond
/// 1 m the hysteresis would never yield in an earthquake: a value in mm.
constexpr double kMaxYieldDisplacement_m = 1.0;
/// The Bouc–Wen exponent n: 1 (smooth) to about 2–5 (sharp, near bilinear);
/// above 10 |z|ⁿ is a step and only makes the equations stiff.
constexpr double kMinExponent = 1.0;
constexpr double kMaxExponent = 10.0;
/// Displacement capacity: the largest bearings reach 1.5–2 m; beyond 5 m it
/// is a value in mm.
constexpr double kMaxCapacity_m = 5.0;
/// Pendulum radius: practice 1–6 m (periods 2–5 s); 100 m is a 20 s period,
/// close to a flat slider, and more than 100 is a value in mm.
constexpr double kMaxRadius_m = 100.0;
/// The lead-rubber bearings' total characteristic strength ΣQ over the
/// building's weight: practice 0.03–0.10. Below 0.005 the lead would yield
/// under any breeze (a strength in kN, 1000 times too small); above 1 the
/// isolation would not yield below 1 g (a strength 1000 times too large).
constexpr double kMinStrengthRatio = 0.005;
constexpr double kMaxStrengthRatio = 1.0;
/// The friction pendulums' total load Σ count·W over the building's weight:
/// the bearings cannot carry more than the building (1.5: room for a seismic
/// mass that leaves out part of the gravity load), and less than 0.01 of it
/// is a load in kN.
constexpr double kMinLoadRatio = 0.01;
constexpr double kMaxLoadRatio = 1.5;
/// Period 2π·√(ΣM / k) of the whole building on the isolation layer's
/// restoring stiffness k (element 0, the bearings' post-yield stiffness and
/// the pendulums' W/R): practice 2–6 s; over 30 s the restoring force is a
/// stiffness in kN/m.
constexpr double kMaxRestoringPeriod_s = 30.0;
/// One lumped mass: the heaviest buildings weigh about 1e9 kg in all, so a
/// single mass above that is not a building (and the sums stay finite).
constexpr double kMaxMass_kg = 1e9;
/// The building's name is printed in reports and file headers.
constexpr std::size_t kMaxNameBytes = 100;

constexpr double kGravity_m_s2 = units::kStandardGravity_m_s2;

// ---- messages -----------------------------------------------------------------

/// Shortest text that reads back as exactly `v` ("inf", "nan" for those).
std::string num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::size_t line_of(const toml::node& n) { return std::max<std::size_t>(n.source().begin.line, 1); }

[[noreturn]] void fail(const std::string& origin, std::size_t line, const std::string& field,
                       const std::string& problem) {
  throw io::UsageError(io::line_prefix(origin, line) + field + ": " + problem);
}

[[noreturn]] void fail(const std::string& origin, const toml::node& where, const std::string& field,
                       const std::string& problem) {
  fail(origin, line_of(where), field, problem);
}

/// What a node holds, for "expected X, found Y".
std::string found(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "the string \"" + io::excerpt(*n.value<std::string>(), 40) + "\"";
    case toml::node_type::integer: return std::to_string(*n.value<std::int64_t>());
    case toml::node_type::floating_point: return num(*n.value<double>());
    case toml::node_type::boolean: return *n.value<bool>() ? "true" : "false";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "a date or time";
  }
}

// ---- reading ------------------------------------------------------------------

/// One value of the file: its node, the field name used in messages and the
/// file's name. The checks throw the file:line:field error.
class Value {
 public:
  Value(const toml::node& n, std::string field, const std::string& origin)
      : n_(n), field_(std::move(field)), origin_(origin) {}

  const toml::node& node() const { return n_; }
  const std::string& field() const { return field_; }
  [[noreturn]] void refuse(const std::string& problem) const { fail(origin_, n_, field_, problem); }

  /// A finite number (integers accepted).
  double number() const {
    if (!n_.is_number()) refuse("expected a number, found " + found(n_));
    const double v = *n_.value<double>();
    if (!std::isfinite(v)) refuse("expected a finite number, found " + num(v));
    return v;
  }
  /// A finite number in [lo, hi] (open at either end when `lo_open` / `hi_open`).
  double number_in(double lo, bool lo_open, double hi, bool hi_open, const char* unit_and_reason) const {
    const double v = number();
    const bool below = lo_open ? !(v > lo) : !(v >= lo);
    const bool above = hi_open ? !(v < hi) : !(v <= hi);
    if (below || above) {
      const std::string range = std::isinf(hi) ? std::string(lo_open ? "> " : ">= ") + num(lo)
                                               : std::string("in ") + (lo_open ? "(" : "[") + num(lo) + ", " +
                                                     num(hi) + (hi_open ? ")" : "]");
      refuse("expected a value " + range + " " + unit_and_reason + ", found " + num(v));
    }
    return v;
  }
  double positive(const char* unit_and_reason) const {
    return number_in(0.0, true, HUGE_VAL, true, unit_and_reason);
  }
  double non_negative(const char* unit_and_reason) const {
    return number_in(0.0, false, HUGE_VAL, true, unit_and_reason);
  }
  /// An integer in [lo, hi].
  std::int64_t integer_in(std::int64_t lo, std::int64_t hi, const char* what) const {
    if (!n_.is_integer())
      refuse(std::string("expected ") + what + ", an integer " + std::to_string(lo) + ".." + std::to_string(hi) +
             ", found " + found(n_));
    const std::int64_t v = *n_.value<std::int64_t>();
    if (v < lo || v > hi)
      refuse(std::string("expected ") + what + ", an integer " + std::to_string(lo) + ".." + std::to_string(hi) +
             ", found " + std::to_string(v));
    return v;
  }
  std::string string() const {
    if (!n_.is_string()) refuse("expected a string, found " + found(n_));
    return *n_.value<std::string>();
  }
  const toml::array& array() const {
    const toml::array* a = n_.as_array();
    if (!a) refuse("expected an array [...], found " + found(n_));
    return *a;
  }
  const toml::table& table() const {
    const toml::table* t = n_.as_table();
    if (!t) refuse("expected a table [" + field_ + "], found " + found(n_));
    return *t;
  }

 private:
  const toml::node& n_;
  std::string field_;
  const std::string& origin_;
};

/// The keys of one table; refuses the keys nobody asked for.
class Keys {
 public:
  Keys(const toml::table& t, std::string name, const std::string& origin)
      : t_(t), name_(std::move(name)), origin_(origin) {}

  std::optional<Value> find(const char* key) {
    asked_.insert(key);
    const toml::node* n = t_.get(key);
    if (!n) return std::nullopt;
    return Value(*n, field(key), origin_);
  }
  Value need(const char* key, const std::string& what) {
    std::optional<Value> v = find(key);
    if (!v) fail(origin_, t_, field(key), "missing key (" + what + ")");
    return *v;
  }
  /// Refuses a key of `foreign` (keys that belong to another kind of table).
  void refuse_foreign(const std::set<std::string>& foreign, const std::string& why) const {
    for (const auto& [k, v] : t_) {
      const std::string key(k.str());
      if (foreign.count(key) && !asked_.count(key)) fail(origin_, v, field(key), why);
    }
  }
  void refuse_unknown(const std::string& expected) const {
    for (const auto& [k, v] : t_) {
      const std::string key(k.str());
      if (!asked_.count(key)) fail(origin_, v, field(key), "unknown key (expected " + expected + ")");
    }
  }
  std::string field(const std::string& key) const { return name_ + "." + key; }
  const std::string& name() const { return name_; }
  const toml::table& table() const { return t_; }

 private:
  const toml::table& t_;
  std::string name_;
  const std::string& origin_;
  std::set<std::string> asked_;
};

/// An array of numbers, each checked by `check(Value)` (which returns it).
template <class Check>
std::vector<double> numbers(const Value& v, const std::string& origin, Check check) {
  std::vector<double> out;
  const toml::array& a = v.array();
  out.reserve(a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    out.push_back(check(Value(a[i], v.field() + "[" + std::to_string(i) + "]", origin)));
  return out;
}

/// The length of an array that must hold one value per degree of freedom.
void require_length(const Value& v, std::size_t dofs) {
  const std::size_t n = v.array().size();
  if (n != dofs)
    v.refuse("expected " + std::to_string(dofs) + " values (one per mass of building.mass_kg), found " +
             std::to_string(n));
}

BaseKind base_named(const Value& v) {
  const std::string s = v.string();
  if (s == "isolated") return BaseKind::kIsolated;
  if (s == "fixed") return BaseKind::kFixed;
  v.refuse("expected \"isolated\" or \"fixed\", found \"" + io::excerpt(s, 40) + "\"");
}

std::string building_name(const Value& v) {
  std::string s = v.string();
  if (s.empty() || s.size() > kMaxNameBytes)
    v.refuse("expected a name of 1 to " + std::to_string(kMaxNameBytes) + " bytes, found " +
             std::to_string(s.size()) + " bytes");
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) v.refuse("expected a name without control characters (tabs, line breaks)");
  }
  return s;
}

std::vector<double> read_masses(Keys& b, const std::string& origin) {
  const Value v = b.need("mass_kg", "the lumped masses, kg, DOF 0 first");
  const std::size_t n = v.array().size();
  if (n == 0) v.refuse("expected at least one mass, found an empty array");
  if (n > static_cast<std::size_t>(kMaxDofs))
    v.refuse("expected at most " + std::to_string(kMaxDofs) + " masses (degrees of freedom), found " +
             std::to_string(n));
  return numbers(v, origin,
                 [](const Value& e) { return e.number_in(0.0, true, kMaxMass_kg, false, "kg (a lumped mass)"); });
}

std::vector<double> read_stiffness(Keys& b, const std::string& origin, std::size_t dofs, BaseKind base) {
  const Value v = b.need("stiffness_n_m", "the element stiffnesses, N/m, element 0 first");
  require_length(v, dofs);
  // Element 0 of an isolated building may be 0 when the isolators restore;
  // every story (all elements of a fixed-base building) needs a stiffness.
  bool element0 = true;
  return numbers(v, origin, [&](const Value& e) {
    const bool first = std::exchange(element0, false);
    if (first && base == BaseKind::kIsolated)
      return e.non_negative("N/m (element 0, the isolation layer's linear spring)");
    return e.positive(first ? "N/m (with base = \"fixed\" element 0 is the first story)" : "N/m (a story's stiffness)");
  });
}

RayleighDamping read_rayleigh(const Value& v, const std::string& origin, std::size_t dofs) {
  Keys r(v.table(), v.field(), origin);
  RayleighDamping out;
  // A ratio of critical damping: 0.02–0.05 in practice, 1 is critical.
  out.ratio = r.need("ratio", "the damping ratio at the two modes").number_in(0.0, true, 1.0, true,
                                                                             "(a ratio of critical damping)");
  const Value m = r.need("modes", "the two modes, 1-based, where the ratio is exact");
  const toml::array& a = m.array();
  if (a.size() != 2) m.refuse("expected two modes [i, j], found " + std::to_string(a.size()) + " values");
  const auto mode = [&](std::size_t k) {
    return static_cast<int>(Value(a[k], m.field() + "[" + std::to_string(k) + "]", origin)
                                .integer_in(1, static_cast<std::int64_t>(dofs), "a mode number"));
  };
  out.mode_a = mode(0);
  out.mode_b = mode(1);
  if (out.mode_a == out.mode_b)
    m.refuse("expected two different modes, found " + std::to_string(out.mode_a) + " twice");
  r.refuse_unknown("ratio, modes");
  return out;
}

/// True when the N×N row-major `a` + shift·I has a Cholesky factor (all
/// pivots > 0): positive definite for shift 0, semi-definite within `shift`.
bool cholesky_ok(std::vector<double> a, std::size_t n, double shift) {
  for (std::size_t i = 0; i < n; ++i) a[i * n + i] += shift;
  for (std::size_t j = 0; j < n; ++j) {
    double d = a[j * n + j];
    for (std::size_t k = 0; k < j; ++k) d -= a[j * n + k] * a[j * n + k];
    if (!(d > 0.0)) return false;
    const double l = std::sqrt(d);
    a[j * n + j] = l;
    for (std::size_t i = j + 1; i < n; ++i) {
      double s = a[i * n + j];
      for (std::size_t k = 0; k < j; ++k) s -= a[i * n + k] * a[j * n + k];
      a[i * n + j] = s / l;
    }
  }
  return true;
}

/// A full N×N matrix: N rows of N finite numbers, symmetric within 1e-9 of
/// its largest entry, positive definite (`definite`, a stiffness) or
/// semi-definite within 1e-9 of its largest entry (a damping). Row-major.
std::vector<double> read_full_matrix(const Value& v, const std::string& origin, std::size_t dofs, bool definite,
                                     const char* unit) {
  const toml::array& rows = v.array();
  if (rows.size() != dofs)
    v.refuse("expected " + std::to_string(dofs) + " rows (one per mass of building.mass_kg), found " +
             std::to_string(rows.size()));
  std::vector<double> out;
  out.reserve(dofs * dofs);
  double largest = 0.0;
  for (std::size_t i = 0; i < dofs; ++i) {
    const Value row(rows[i], v.field() + "[" + std::to_string(i) + "]", origin);
    require_length(row, dofs);
    for (const double x : numbers(row, origin, [&](const Value& e) { return e.number(); })) {
      out.push_back(x);
      largest = std::max(largest, std::fabs(x));
    }
  }
  for (std::size_t i = 0; i < dofs; ++i) {
    const Value row(rows[i], v.field() + "[" + std::to_string(i) + "]", origin);
    const double d = out[i * dofs + i];
    if (definite ? !(d > 0.0) : !(d >= 0.0))
      Value(*row.array().get(i), row.field() + "[" + std::to_string(i) + "]", origin)
          .refuse(std::string("expected a diagonal entry ") + (definite ? "> 0 " : ">= 0 ") + unit + ", found " +
                  num(d));
    for (std::size_t j = 0; j < i; ++j) {
      const double a = out[i * dofs + j];
      const double b = out[j * dofs + i];
      if (std::fabs(a - b) > 1e-9 * largest)
        Value(*row.array().get(j), row.field() + "[" + std::to_string(j) + "]", origin)
            .refuse("expected a symmetric matrix: " + num(a) + " here, " + num(b) + " at [" + std::to_string(j) +
                    "][" + std::to_string(i) + "]");
    }
  }
  if (definite && !cholesky_ok(out, dofs, 0.0))
    v.refuse(std::string("expected a positive definite matrix ") + unit +
             " (every floor restrained): a Cholesky pivot is <= 0");
  if (!definite && !cholesky_ok(out, dofs, 1e-9 * largest + 1e-300))
    v.refuse(std::string("expected a positive semi-definite matrix ") + unit +
             " (a damping that dissipates): a Cholesky pivot is < 0");
  return out;
}

/// The chain of element stiffnesses seen from a full matrix: k_i = −K(i,i−1)
/// for i ≥ 1, k_0 = K(0,0) − k_1 (the shear chain's own relation).
std::vector<double> chain_seen_from(const std::vector<double>& k, std::size_t n) {
  std::vector<double> e(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) e[i] = -k[i * n + i - 1];
  e[0] = k[0] - (n > 1 ? e[1] : 0.0);
  return e;
}

/// [building]: name, base, the arrays and the damping form. Returns the node
/// of element 0's stiffness (the full matrix's first entry).
const toml::node& read_building(const toml::table& root, const std::string& origin, BuildingParams& out) {
  const toml::node* n = root.get("building");
  if (!n) fail(origin, 1, "building", "missing table [building]");
  Keys b(Value(*n, "building", origin).table(), "building", origin);
  out.name = building_name(b.need("name", "the building's name"));
  if (const auto v = b.find("base")) out.base = base_named(*v);
  out.mass_kg = read_masses(b, origin);
  const std::size_t dofs = out.mass_kg.size();
  const std::optional<Value> k_matrix = b.find("stiffness_matrix_n_m");
  const toml::node* first_k = nullptr;
  if (k_matrix) {
    if (const auto chain = b.find("stiffness_n_m"))
      chain->refuse("not allowed with building.stiffness_matrix_n_m: give one of the two stiffness forms");
    out.stiffness_matrix_n_m = read_full_matrix(*k_matrix, origin, dofs, true, "N/m");
    out.story_stiffness_n_m = chain_seen_from(out.stiffness_matrix_n_m, dofs);
    first_k = k_matrix->array().get(0)->as_array()->get(0);
  } else {
    out.story_stiffness_n_m = read_stiffness(b, origin, dofs, out.base);
    first_k = b.need("stiffness_n_m", "").array().get(0);
  }
  const std::optional<Value> damping = b.find("damping_n_s_m");
  const std::optional<Value> rayleigh = b.find("rayleigh");
  const std::optional<Value> c_matrix = b.find("damping_matrix_n_s_m");
  if (damping && rayleigh)
    rayleigh->refuse("not allowed with building.damping_n_s_m: give one of the two damping forms");
  if (c_matrix && (damping || rayleigh))
    c_matrix->refuse("not allowed with building.damping_n_s_m or [building.rayleigh]: give one of the damping forms");
  if (!damping && !rayleigh && !c_matrix)
    fail(origin, b.table(), "building.damping_n_s_m",
         "missing key: give the element dashpots damping_n_s_m, a [building.rayleigh] table or a full "
         "damping_matrix_n_s_m");
  if (c_matrix) {
    out.damping_matrix_n_s_m = read_full_matrix(*c_matrix, origin, dofs, false, "N s/m");
    out.story_damping_n_s_m.assign(dofs, 0.0);  // unused with a full matrix
    out.rayleigh.reset();
  } else if (damping) {
    require_length(*damping, dofs);
    out.story_damping_n_s_m =
        numbers(*damping, origin, [](const Value& e) { return e.non_negative("N s/m (a dashpot)"); });
    out.rayleigh.reset();
  } else {
    out.rayleigh = read_rayleigh(*rayleigh, origin, dofs);
    out.story_damping_n_s_m.assign(dofs, 0.0);  // unused with Rayleigh damping
  }
  b.refuse_unknown(
      "name, base, mass_kg, stiffness_n_m, stiffness_matrix_n_m, damping_n_s_m, damping_matrix_n_s_m, rayleigh");
  return *first_k;
}

unsigned isolator_count(Keys& t) {
  return static_cast<unsigned>(
      t.need("count", "the number of identical bearings").integer_in(1, kMaxIsolatorCount, "a bearing count"));
}

double yield_displacement(Keys& t) {
  return t.need("yield_displacement_m", "D_y of the Bouc-Wen variable, m")
      .number_in(0.0, true, kMaxYieldDisplacement_m, false, "m (lead-rubber 0.01-0.03, friction pendulum 0.0001-0.001)");
}

void read_shape(Keys& t, double& exponent, double& capacity_m) {
  if (const auto v = t.find("exponent"))
    exponent = v->number_in(kMinExponent, false, kMaxExponent, false, "(the Bouc-Wen exponent n)");
  if (const auto v = t.find("displacement_capacity_m"))
    capacity_m = v->number_in(0.0, true, kMaxCapacity_m, false, "m (a bearing's displacement capacity)");
}

const std::set<std::string> kLeadRubberKeys{"characteristic_strength_n", "post_yield_stiffness_n_m"};
const std::set<std::string> kFrictionKeys{"radius_m", "friction_slow", "friction_fast", "rate_s_per_m", "weight_n"};

LeadRubberBearing read_lead_rubber(Keys& t) {
  LeadRubberBearing b;
  b.count = isolator_count(t);
  b.characteristic_strength_n =
      t.need("characteristic_strength_n", "Q, N per bearing").positive("N (Q, the force at zero displacement)");
  b.post_yield_stiffness_n_m =
      t.need("post_yield_stiffness_n_m", "k_p, N/m per bearing").non_negative("N/m (k_p)");
  b.yield_displacement_m = yield_displacement(t);
  read_shape(t, b.exponent, b.displacement_capacity_m);
  t.refuse_foreign(kFrictionKeys, "a friction_pendulum key, not allowed with kind = \"lead_rubber\"");
  t.refuse_unknown("kind, count, characteristic_strength_n, post_yield_stiffness_n_m, yield_displacement_m, "
                   "exponent, displacement_capacity_m");
  return b;
}

FrictionPendulumBearing read_friction_pendulum(Keys& t) {
  FrictionPendulumBearing b;
  b.count = isolator_count(t);
  b.radius_m = t.need("radius_m", "R of the sliding surface, m")
                   .number_in(0.0, true, kMaxRadius_m, false, "m (R; practice 1-6 m)");
  // Friction coefficients: PTFE-type liners 0.02-0.12; 1 would be a 45° slope.
  const Value slow = t.need("friction_slow", "mu at zero sliding velocity");
  b.friction_slow = slow.number_in(0.0, false, 1.0, true, "(a friction coefficient)");
  b.friction_fast = t.need("friction_fast", "mu at high sliding velocity")
                        .number_in(0.0, false, 1.0, true, "(a friction coefficient)");
  if (b.friction_slow > b.friction_fast)
    slow.refuse("expected at most friction_fast (" + num(b.friction_fast) + "): friction grows with velocity, found " +
                num(b.friction_slow));
  b.rate_s_per_m = t.need("rate_s_per_m", "a of mu(v), s/m").non_negative("s/m (a of mu(v))");
  b.yield_displacement_m = yield_displacement(t);
  if (const auto v = t.find("weight_n")) b.weight_n = v->positive("N (the load per bearing)");
  read_shape(t, b.exponent, b.displacement_capacity_m);
  t.refuse_foreign(kLeadRubberKeys, "a lead_rubber key, not allowed with kind = \"friction_pendulum\"");
  t.refuse_unknown("kind, count, radius_m, friction_slow, friction_fast, rate_s_per_m, yield_displacement_m, "
                   "exponent, weight_n, displacement_capacity_m");
  return b;
}

/// The tables of an array of tables `[[key]]`, or none when absent.
const toml::array* tables(const toml::table& root, const char* key, const std::string& origin) {
  const toml::node* n = root.get(key);
  if (!n) return nullptr;
  const toml::array* a = n->as_array();
  if (!a || !a->is_array_of_tables())
    fail(origin, *n, key, std::string("expected [[") + key + "]] tables, found " + found(*n));
  return a;
}

/// Where each isolator came from, for the checks across isolators.
struct IsolatorSource {
  const toml::table* table;
  std::string name;
};

void read_isolators(const toml::table& root, const std::string& origin, BuildingParams& out,
                    std::vector<IsolatorSource>& sources) {
  const toml::array* a = tables(root, "isolator", origin);
  if (!a) return;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::table& tt = *(*a)[i].as_table();
    Keys t(tt, "isolator[" + std::to_string(i) + "]", origin);
    const Value kind = t.need("kind", "\"lead_rubber\" or \"friction_pendulum\"");
    const std::string k = kind.string();
    if (k == "lead_rubber") {
      out.isolators.emplace_back(read_lead_rubber(t));
    } else if (k == "friction_pendulum") {
      out.isolators.emplace_back(read_friction_pendulum(t));
    } else {
      kind.refuse("expected \"lead_rubber\" or \"friction_pendulum\", found \"" + io::excerpt(k, 40) + "\"");
    }
    sources.push_back({&tt, t.name()});
  }
}

void read_dampers(const toml::table& root, const std::string& origin, BuildingParams& out) {
  const toml::array* a = tables(root, "damper", origin);
  if (!a) return;  // the default: one damper at element 0
  out.dampers.clear();
  std::vector<std::size_t> line_of_element(out.mass_kg.size(), 0);
  for (std::size_t i = 0; i < a->size(); ++i) {
    Keys t(*(*a)[i].as_table(), "damper[" + std::to_string(i) + "]", origin);
    DamperPlacement d;
    const Value element = t.need("element", "the element the damper acts in parallel with");
    d.element = static_cast<unsigned>(element.integer_in(0, static_cast<std::int64_t>(out.mass_kg.size()) - 1,
                                                         "an element index (0 joins DOF 0 to the ground)"));
    if (const std::size_t first = line_of_element[d.element])
      element.refuse("element " + std::to_string(d.element) + " already has a [[damper]] table (line " +
                     std::to_string(first) + "); give its count instead");
    line_of_element[d.element] = line_of(element.node());
    if (const auto v = t.find("count"))
      d.count = static_cast<unsigned>(v->integer_in(1, kMaxDamperCount, "a damper count"));
    t.refuse_unknown("element, count");
    out.dampers.push_back(d);
  }
}

// ---- checks across tables -------------------------------------------------------

double total_mass_kg(const BuildingParams& b) {
  double m = 0.0;
  for (const double x : b.mass_kg) m += x;
  return m;
}

/// The node of `key` in an isolator's table (its header line when absent).
const toml::node& node_of(const IsolatorSource& s, const char* key) {
  const toml::node* n = s.table->get(key);
  return n ? *n : *s.table;
}

void check_isolators(const BuildingParams& b, const std::vector<IsolatorSource>& src, const std::string& origin) {
  if (b.isolators.empty()) return;
  if (b.base == BaseKind::kFixed)
    fail(origin, *src.front().table, src.front().name,
         "not allowed with building.base = \"fixed\" (isolators act in parallel with element 0 of an isolated "
         "building)");
  const double weight_n = total_mass_kg(b) * kGravity_m_s2;
  double strength_n = 0.0;
  double load_n = 0.0;
  std::size_t pendulums = 0;
  const IsolatorSource* first_lead = nullptr;
  const IsolatorSource* last_load = nullptr;
  for (std::size_t i = 0; i < b.isolators.size(); ++i) {
    if (const auto* l = std::get_if<LeadRubberBearing>(&b.isolators[i])) {
      strength_n += l->count * l->characteristic_strength_n;
      if (!first_lead) first_lead = &src[i];
    } else {
      const auto& f = std::get<FrictionPendulumBearing>(b.isolators[i]);
      ++pendulums;
      load_n += f.weight_n > 0.0 ? f.count * f.weight_n : weight_n;
      last_load = &src[i];
    }
  }
  if (pendulums > 1) {
    for (std::size_t i = 0; i < b.isolators.size(); ++i) {
      const auto* f = std::get_if<FrictionPendulumBearing>(&b.isolators[i]);
      if (f && f->weight_n == 0.0)
        fail(origin, *src[i].table, src[i].name + ".weight_n",
             "missing key: with more than one friction_pendulum group each needs its load per bearing (the "
             "default, the building's weight / count, would put the whole weight on every group)");
    }
  }
  if (first_lead) {
    const double ratio = strength_n / weight_n;
    if (!(ratio >= kMinStrengthRatio && ratio <= kMaxStrengthRatio))
      fail(origin, node_of(*first_lead, "characteristic_strength_n"), first_lead->name + ".characteristic_strength_n",
           "the lead-rubber bearings' total strength sum(count Q) = " + num(strength_n) + " N is " +
               io::format_number("%.3g", ratio) + " of the building's weight " + io::format_number("%.6g", weight_n) +
               " N; expected " + num(kMinStrengthRatio) + " to " + num(kMaxStrengthRatio) +
               " of it (practice 0.03-0.10): is Q in N?");
  }
  if (last_load) {
    const double ratio = load_n / weight_n;
    if (!(ratio >= kMinLoadRatio && ratio <= kMaxLoadRatio))
      fail(origin, node_of(*last_load, "weight_n"), last_load->name + ".weight_n",
           "the friction pendulums carry sum(count W) = " + io::format_number("%.6g", load_n) + " N, " +
               io::format_number("%.3g", ratio) + " of the building's weight " + io::format_number("%.6g", weight_n) +
               " N; expected " + num(kMinLoadRatio) + " to " + num(kMaxLoadRatio) + " of it: is weight_n in N?");
  }
}

/// An isolated building needs a restoring force at element 0: its spring, a
/// lead-rubber bearing's post-yield stiffness or a friction pendulum.
void check_restoring(const BuildingParams& b, const std::vector<IsolatorSource>& src, const std::string& origin,
                     const toml::node& stiffness0) {
  if (!b.stiffness_matrix_n_m.empty()) {
    if (!src.empty())
      fail(origin, *src.front().table, src.front().name,
           "not allowed with building.stiffness_matrix_n_m (isolators act on element 0 of a shear chain)");
    return;  // a positive definite matrix restores every floor
  }
  if (b.base == BaseKind::kFixed) return;
  const double mass_kg = total_mass_kg(b);
  const double weight_n = mass_kg * kGravity_m_s2;
  double k_n_m = b.story_stiffness_n_m.front();
  const IsolatorSource* first_lead = nullptr;
  for (std::size_t i = 0; i < b.isolators.size(); ++i) {
    if (const auto* l = std::get_if<LeadRubberBearing>(&b.isolators[i])) {
      k_n_m += l->count * l->post_yield_stiffness_n_m;
      if (!first_lead) first_lead = &src[i];
    } else {
      const auto& f = std::get<FrictionPendulumBearing>(b.isolators[i]);
      const double w = f.weight_n > 0.0 ? f.weight_n : weight_n / f.count;
      k_n_m += f.count * w / f.radius_m;
    }
  }
  const toml::node& blame = first_lead ? node_of(*first_lead, "post_yield_stiffness_n_m") : stiffness0;
  const std::string field =
      first_lead ? first_lead->name + ".post_yield_stiffness_n_m" : std::string("building.stiffness_n_m[0]");
  if (!(k_n_m > 0.0))
    fail(origin, blame, field,
         "the building has no restoring force: element 0's stiffness is 0 and no isolator restores (a lead-rubber "
         "bearing needs post_yield_stiffness_n_m > 0; a friction pendulum always restores)");
  const double period_s = 2.0 * units::kPi * std::sqrt(mass_kg / k_n_m);
  if (!(period_s <= kMaxRestoringPeriod_s))
    fail(origin, blame, field,
         "the isolation layer's restoring stiffness (element 0 + bearings) is " + num(k_n_m) +
             " N/m: the building's period on it, " + io::format_number("%.3g", period_s) + " s, exceeds " +
             num(kMaxRestoringPeriod_s) + " s (practice 2-6 s): is a stiffness in kN/m?");
}

// ---- writing --------------------------------------------------------------------

/// A TOML float that reads back as exactly `v`: the shortest digits that do,
/// fixed from 0.001 to 10000 ("0.011", "25.0"), scientific otherwise with a
/// plain exponent ("3.2873e6", "5.0e-4"), as an engineer writes them.
std::string toml_float(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  const double a = std::fabs(v);
  const bool fixed = a == 0.0 || (a >= 1e-3 && a < 1e4);
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, fixed ? std::chars_format::fixed : std::chars_format::scientific);
  std::string s(buf, r.ptr);
  const std::size_t e = s.find('e');
  std::string mantissa = s.substr(0, e);
  if (mantissa.find('.') == std::string::npos) mantissa += ".0";
  if (e == std::string::npos) return mantissa;
  std::string exponent = s.substr(e + 1);  // "+06", "-04"
  const bool negative = exponent.front() == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return mantissa + "e" + (negative ? "-" : "") + (exponent.empty() ? "0" : exponent);
}

std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", u);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string toml_array(const std::vector<double>& v) {
  constexpr std::size_t kPerLine = 6;
  const bool long_array = v.size() > kPerLine;
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (long_array && i % kPerLine == 0) s += "\n  ";
    s += toml_float(v[i]);
    if (i + 1 < v.size()) s += (long_array && (i + 1) % kPerLine == 0) ? "," : ", ";
  }
  return s + (long_array ? ",\n]" : "]");
}

void write_isolator(std::string& t, const LeadRubberBearing& b) {
  t += "\n[[isolator]]  # F = count (k_p u + Q z)\n";
  t += "kind = \"lead_rubber\"\n";
  t += "count = " + std::to_string(b.count) + "\n";
  t += "characteristic_strength_n = " + toml_float(b.characteristic_strength_n) + "\n";
  t += "post_yield_stiffness_n_m = " + toml_float(b.post_yield_stiffness_n_m) + "\n";
  t += "yield_displacement_m = " + toml_float(b.yield_displacement_m) + "\n";
  t += "exponent = " + toml_float(b.exponent) + "\n";
  if (b.displacement_capacity_m > 0.0)
    t += "displacement_capacity_m = " + toml_float(b.displacement_capacity_m) + "\n";
}

void write_isolator(std::string& t, const FrictionPendulumBearing& b) {
  t += "\n[[isolator]]  # F = count (W / R u + mu(u') W z), mu(v) = fast - (fast - slow) exp(-rate |v|)\n";
  t += "kind = \"friction_pendulum\"\n";
  t += "count = " + std::to_string(b.count) + "\n";
  t += "radius_m = " + toml_float(b.radius_m) + "\n";
  t += "friction_slow = " + toml_float(b.friction_slow) + "\n";
  t += "friction_fast = " + toml_float(b.friction_fast) + "\n";
  t += "rate_s_per_m = " + toml_float(b.rate_s_per_m) + "\n";
  t += "yield_displacement_m = " + toml_float(b.yield_displacement_m) + "\n";
  t += "exponent = " + toml_float(b.exponent) + "\n";
  if (b.weight_n > 0.0) t += "weight_n = " + toml_float(b.weight_n) + "\n";
  if (b.displacement_capacity_m > 0.0)
    t += "displacement_capacity_m = " + toml_float(b.displacement_capacity_m) + "\n";
}

}  // namespace

BuildingParams parse_building_toml(std::string_view text, const std::string& origin) {
  toml::table root;
  try {
    root = toml::parse(io::strip_bom(text), origin);
  } catch (const toml::parse_error& e) {
    throw io::UsageError(io::line_prefix(origin, std::max<std::size_t>(e.source().begin.line, 1)) +
                         "not valid TOML: " + std::string(e.description()));
  }
  for (const auto& [k, v] : root) {
    const std::string key(k.str());
    if (key != "building" && key != "isolator" && key != "damper")
      fail(origin, v, key, "unknown table or key (expected [building], [[isolator]], [[damper]])");
  }
  BuildingParams out;
  const toml::node& stiffness0 = read_building(root, origin, out);
  std::vector<IsolatorSource> sources;
  read_isolators(root, origin, out, sources);
  read_dampers(root, origin, out);
  check_isolators(out, sources, origin);
  check_restoring(out, sources, origin, stiffness0);
  return out;
}

BuildingParams read_building_file(const std::filesystem::path& path) {
  return parse_building_toml(io::read_regular_file(path, kMaxBuildingFileBytes), io::file_label(path));
}

std::string building_toml(const BuildingParams& b) {
  if (b.dampers.empty())
    throw std::invalid_argument("building_toml: a building file always has at least one damper");
  std::string t;
  t += "# Building file (mrd --building FILE). SI units.\n";
  t += "\n[building]\n";
  t += "name = " + toml_string(b.name) + "\n";
  t += std::string("base = ") + (b.base == BaseKind::kFixed ? "\"fixed\"" : "\"isolated\"") + "\n";
  t += "# lumped masses, kg, DOF 0 first\n";
  t += "mass_kg = " + toml_array(b.mass_kg) + "\n";
  const auto full = [&](const std::vector<double>& m) {
    const std::size_t n = b.mass_kg.size();
    std::string s = "[";
    for (std::size_t i = 0; i < n; ++i)
      s += "\n  " + toml_array(std::vector<double>(m.begin() + static_cast<std::ptrdiff_t>(i * n),
                                                   m.begin() + static_cast<std::ptrdiff_t>((i + 1) * n))) + ",";
    return s + "\n]";
  };
  if (!b.stiffness_matrix_n_m.empty()) {
    t += "# the full stiffness matrix, N/m, row i for DOF i\n";
    t += "stiffness_matrix_n_m = " + full(b.stiffness_matrix_n_m) + "\n";
  } else {
    t += "# element i joins DOF i to DOF i-1; element 0 joins DOF 0 to the ground\n";
    t += "stiffness_n_m = " + toml_array(b.story_stiffness_n_m) + "\n";
  }
  if (!b.damping_matrix_n_s_m.empty()) {
    t += "# the full damping matrix, N s/m, row i for DOF i\n";
    t += "damping_matrix_n_s_m = " + full(b.damping_matrix_n_s_m) + "\n";
  } else if (b.rayleigh) {
    t += "\n[building.rayleigh]  # C = a0 M + a1 K, the ratio exact at the two modes\n";
    t += "ratio = " + toml_float(b.rayleigh->ratio) + "\n";
    t += "modes = [" + std::to_string(b.rayleigh->mode_a) + ", " + std::to_string(b.rayleigh->mode_b) + "]\n";
  } else {
    t += "damping_n_s_m = " + toml_array(b.story_damping_n_s_m) + "\n";
  }
  for (const Isolator& iso : b.isolators) std::visit([&](const auto& x) { write_isolator(t, x); }, iso);
  for (const DamperPlacement& d : b.dampers) {
    t += "\n[[damper]]\n";
    t += "element = " + std::to_string(d.element) + "\n";
    t += "count = " + std::to_string(d.count) + "\n";
  }
  return t;
}

}  // namespace mrd::structure
