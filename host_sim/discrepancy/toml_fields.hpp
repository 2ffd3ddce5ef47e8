#pragma once
/// Reading the tables of a damper.toml or a fluid file (TOML) field by
/// field: every refusal is an io::UsageError `origin:LINE: table.key: what
/// was expected`, and a number is checked against its physical range
/// (physical_ranges.hpp), whose text the message quotes.

#include <toml++/toml.h>

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "host_sim/discrepancy/physical_ranges.hpp"

namespace mrd::discrepancy {

/// Shortest text that reads back as exactly `v`, always a TOML float
/// ("0.5", "4100.0", "1e-06").
[[nodiscard]] std::string toml_number(double v);

/// "a force in [0.001, 1e+09] N": what a number of range `r` must be.
[[nodiscard]] std::string range_text(const PhysicalRange& r);

/// Throws io::UsageError "origin:LINE: field: problem" (line 1 when the
/// region has none).
[[noreturn]] void fail_at(const std::string& origin, const toml::source_region& where, const std::string& field,
                          const std::string& problem);

/// Parses TOML text; a syntax error is thrown as "origin:LINE: what".
[[nodiscard]] toml::table parse_toml(const std::string& text, const std::string& origin);

/// The keys of one table; refuses keys it was never asked for.
class TomlTable {
 public:
  TomlTable(const toml::table& t, std::string name, const std::string& origin);

  /// A finite number inside the physical range `r` (integers accepted).
  double in(const char* key, const PhysicalRange& r);
  /// in(), or nullopt when the key is absent.
  std::optional<double> optional_in(const char* key, const PhysicalRange& r);
  bool boolean(const char* key);
  std::string string(const char* key);
  std::vector<std::string> strings(const char* key);
  /// An integer in [0, max].
  std::size_t count(const char* key, std::size_t max);

  [[nodiscard]] bool has(const char* key) const { return t_.get(key) != nullptr; }
  /// Where `key` is (the table's header when absent).
  [[nodiscard]] const toml::source_region& where(const char* key) const;
  void no_unknown_keys() const;
  [[nodiscard]] std::string field(const char* key) const { return name_ + "." + key; }
  [[noreturn]] void refuse(const char* key, const std::string& problem) const {
    fail_at(origin_, where(key), field(key), problem);
  }

 private:
  const toml::node& need(const char* key);

  const toml::table& t_;
  std::string name_;
  const std::string& origin_;
  std::set<std::string> asked_;
};

/// The table `name` of `root`: "origin:1: [name]: missing table" when
/// absent, "expected a table [name]" when it is not one.
[[nodiscard]] const toml::table& required_table(const toml::table& root, const char* name, const std::string& origin);

/// The table `name` of `root`, or nullptr when absent ("expected a table
/// [name]" when it is something else).
[[nodiscard]] const toml::table* optional_table(const toml::table& root, const char* name, const std::string& origin);

/// Refuses a top-level key of `root` other than `known` (their list, for the
/// message: "unknown table (expected ...)").
void no_unknown_tables(const toml::table& root, const std::vector<const char*>& known, const std::string& origin);

}  // namespace mrd::discrepancy
