#pragma once
/// Option checks for the board programs (mrd-firmware) and the peer
/// simulators, as `mrd` checks its own: an empty value, NaN, infinity or a
/// number outside the option's physical range is refused with a message that
/// names the option (CLI11 prefixes it) and the range, before any work starts
/// (so no infinite or NaN value reaches an int64 nanosecond cast or a limit).

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace mrd::app {

/// A number in [lo, hi] (`unit` is appended to the bounds in the message).
inline CLI::Validator finite_in(double lo, double hi, const std::string& unit) {
  return CLI::Validator(
      [lo, hi, unit](std::string& text) -> std::string {
        char bounds[128];
        std::snprintf(bounds, sizeof bounds, "a number from %g to %g%s%s", lo, hi, unit.empty() ? "" : " ",
                      unit.c_str());
        double v = 0.0;
        std::size_t used = 0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          return "expected " + std::string(bounds) + ", got '" + text + "'";
        }
        if (used != text.size() || !std::isfinite(v) || v < lo || v > hi) {
          return "expected " + std::string(bounds) + ", got '" + text + "'";
        }
        return {};
      },
      "", "finite range");
}

/// A number > 0 and ≤ hi: for options whose absence means "no limit" or "the
/// default", so that zero is refused rather than read as the default.
inline CLI::Validator positive_up_to(double hi, const std::string& unit) {
  return CLI::Validator(
      [hi, unit](std::string& text) -> std::string {
        char bounds[128];
        std::snprintf(bounds, sizeof bounds, "a number > 0 and at most %g%s%s", hi, unit.empty() ? "" : " ",
                      unit.c_str());
        double v = 0.0;
        std::size_t used = 0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          return "expected " + std::string(bounds) + ", got '" + text + "'";
        }
        if (used != text.size() || !std::isfinite(v) || !(v > 0.0) || v > hi) {
          return "expected " + std::string(bounds) + ", got '" + text + "'";
        }
        return {};
      },
      "", "positive");
}

/// Refuses an empty value given to any option that takes one (`--state ''`,
/// `--can=`): an empty value is an error naming the option, never "the
/// default". Call right after app.parse(); throws CLI::ValidationError
/// ("--state: expected a value, got an empty one").
inline void refuse_empty_values(const CLI::App& app) {
  for (const CLI::Option* option : app.get_options()) {
    if (option->get_items_expected_min() == 0) continue;  // a flag: takes no value
    for (const std::string& value : option->results()) {
      if (value.empty()) throw CLI::ValidationError(option->get_name(), "expected a value, got an empty one");
    }
  }
}

/// Longest time any of these programs waits or runs, s (int64 nanoseconds hold 292 years).
inline constexpr double kMaxProgramTime_s = 1.0e7;

}  // namespace mrd::app
