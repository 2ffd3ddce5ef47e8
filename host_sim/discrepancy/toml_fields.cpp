#include "host_sim/discrepancy/toml_fields.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <utility>

#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::discrepancy {

std::string toml_number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, r.ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string range_text(const PhysicalRange& r) {
  std::string t = std::string(r.what) + " in [" + io::format_number("%.6g", r.min) + ", " +
                  io::format_number("%.6g", r.max) + "]";
  if (*r.unit != '\0') t += std::string(" ") + r.unit;
  return t;
}

void fail_at(const std::string& origin, const toml::source_region& where, const std::string& field,
             const std::string& problem) {
  throw io::UsageError(origin + ":" + std::to_string(std::max<toml::source_index>(where.begin.line, 1)) + ": " +
                       field + ": " + problem);
}

toml::table parse_toml(const std::string& text, const std::string& origin) {
  try {
    return toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw io::UsageError(origin + ":" + std::to_string(std::max<toml::source_index>(e.source().begin.line, 1)) +
                         ": " + std::string(e.description()));
  }
}

TomlTable::TomlTable(const toml::table& t, std::string name, const std::string& origin)
    : t_(t), name_(std::move(name)), origin_(origin) {}

double TomlTable::in(const char* key, const PhysicalRange& r) {
  const toml::node& n = need(key);
  const std::optional<double> v = n.is_number() ? n.value<double>() : std::nullopt;
  if (!v) fail_at(origin_, n.source(), field(key), "expected a number");
  if (!std::isfinite(*v)) fail_at(origin_, n.source(), field(key), "expected a finite number");
  if (!r.contains(*v))
    fail_at(origin_, n.source(), field(key), "expected " + range_text(r) + ", got " + toml_number(*v));
  return *v;
}

std::optional<double> TomlTable::optional_in(const char* key, const PhysicalRange& r) {
  asked_.insert(key);
  if (!has(key)) return std::nullopt;
  return in(key, r);
}

bool TomlTable::boolean(const char* key) {
  const toml::node& n = need(key);
  if (!n.is_boolean()) fail_at(origin_, n.source(), field(key), "expected true or false");
  return *n.value<bool>();
}

std::string TomlTable::string(const char* key) {
  const toml::node& n = need(key);
  if (!n.is_string()) fail_at(origin_, n.source(), field(key), "expected a string");
  return *n.value<std::string>();
}

std::vector<std::string> TomlTable::strings(const char* key) {
  const toml::node& n = need(key);
  const toml::array* a = n.as_array();
  if (!a) fail_at(origin_, n.source(), field(key), "expected an array of strings");
  std::vector<std::string> out;
  for (const toml::node& e : *a) {
    if (!e.is_string()) fail_at(origin_, e.source(), field(key), "expected an array of strings");
    out.push_back(*e.value<std::string>());
  }
  return out;
}

std::size_t TomlTable::count(const char* key, std::size_t max) {
  const toml::node& n = need(key);
  // value<int64_t>() of a float node converts it (undefined beyond int64's range): integers only.
  const auto v = n.is_integer() ? n.value<std::int64_t>() : std::nullopt;
  if (!v || *v < 0 || static_cast<std::uint64_t>(*v) > max)
    fail_at(origin_, n.source(), field(key), "expected an integer in [0, " + std::to_string(max) + "]");
  return static_cast<std::size_t>(*v);
}

const toml::source_region& TomlTable::where(const char* key) const {
  const toml::node* n = t_.get(key);
  return n ? n->source() : t_.source();
}

void TomlTable::no_unknown_keys() const {
  for (const auto& [k, v] : t_) {
    const std::string key(k.str());
    if (!asked_.count(key)) fail_at(origin_, v.source(), field(key.c_str()), "unknown key");
  }
}

const toml::node& TomlTable::need(const char* key) {
  asked_.insert(key);
  const toml::node* n = t_.get(key);
  if (!n) fail_at(origin_, t_.source(), field(key), "missing key");
  return *n;
}

const toml::table& required_table(const toml::table& root, const char* name, const std::string& origin) {
  const toml::table* t = optional_table(root, name, origin);
  if (!t) throw io::UsageError(origin + ":1: [" + std::string(name) + "]: missing table");
  return *t;
}

const toml::table* optional_table(const toml::table& root, const char* name, const std::string& origin) {
  const toml::node* n = root.get(name);
  if (!n) return nullptr;
  const toml::table* t = n->as_table();
  if (!t) fail_at(origin, n->source(), name, std::string("expected a table [") + name + "]");
  return t;
}

void no_unknown_tables(const toml::table& root, const std::vector<const char*>& known, const std::string& origin) {
  for (const auto& [k, v] : root) {
    const std::string key(k.str());
    if (std::any_of(known.begin(), known.end(), [&](const char* name) { return key == name; })) continue;
    std::string list;
    for (std::size_t i = 0; i < known.size(); ++i) {
      list += (i == 0 ? "" : (i + 1 == known.size() ? " or " : ", "));
      list += known[i];
    }
    fail_at(origin, v.source(), key, "unknown table (expected " + list + ")");
  }
}

}  // namespace mrd::discrepancy
