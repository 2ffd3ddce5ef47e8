#pragma once
/// Options of the `mrd` subcommands: the checks their values get, and the
/// options several subcommands share, registered in one place with their
/// check. The `help` argument says what an option means for its subcommand.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

namespace mrd::cli {

/// Checks a parsed number: finite and, if `min_inclusive` is given, not below
/// it. Throws io::UsageError naming the option.
void require_finite_at_least(const std::string& option, double value, double min_inclusive);

/// Checks a parsed number is finite and > 0; throws io::UsageError
/// naming the option and `what` ("a PGA", "a duration", ...) otherwise.
void require_positive(const std::string& option, double value, const std::string& what);

/// Checks `value` ≤ `max` (NaN fails too); throws io::UsageError "<option>: expected at
/// most <limit>" otherwise (`limit` says the bound in words, e.g. "0.02 s").
void require_at_most(const std::string& option, double value, double max, const std::string& limit);

/// Checks --step-s: finite, at least 1 µs and at most `max_s` (`limit` says
/// that bound in words).
void require_step_s(double step_s, double max_s, const std::string& limit);

/// Checks `value` is one of `choices`; throws io::UsageError "<option>:
/// expected a, b or c, got '<value>'" otherwise.
void require_choice(const std::string& option, const std::string& value, std::initializer_list<const char*> choices);

/// Largest --pga-g, g, --idle-years (and idle grids), years, and --threads.
inline constexpr double kMaxPga_g = 100.0;
inline constexpr double kMaxIdleYears = 1000.0;
inline constexpr unsigned kMaxThreads = 1024;
/// Longest simulated run, s (--duration-s of sim and sine).
inline constexpr double kMaxDuration_s = 1.0e5;

/// --pga-g G, default shown: the PGA motions are scaled to, g.
void add_pga_g_option(CLI::App& app, double& pga_g, const std::string& help);

/// Checks --pga-g: finite, > 0 and at most kMaxPga_g.
void check_pga_g(double pga_g);

/// --idle-years Y, default shown: an idle time, years.
void add_idle_years_option(CLI::App& app, double& idle_years, const std::string& help);

/// Checks --idle-years: finite, >= 0 and at most kMaxIdleYears.
void check_idle_years(double idle_years);

/// --step-s S, default shown: the simulation step, s (checked by require_step_s).
void add_step_s_option(CLI::App& app, double& step_s, const std::string& help);

/// --threads N, default shown: worker threads, 0 for all cores, at most kMaxThreads.
void add_threads_option(CLI::App& app, unsigned& threads, const std::string& help);

/// Largest seed: 2^64 - 1, the widest seed of the random generators.
inline constexpr std::uint64_t kMaxSeed = std::numeric_limits<std::uint64_t>::max();

/// The seed `text` writes: decimal digits only (no sign, fraction, exponent,
/// hex prefix or space; leading zeros are decimal) from 0 to kMaxSeed.
/// nullopt for anything else, the empty text included.
[[nodiscard]] std::optional<std::uint64_t> parse_seed(std::string_view text);

/// `name` SEED, default shown: a seed read by parse_seed. Anything else is
/// refused before the command runs (exit 2) with "<name>: expected a decimal
/// whole number from 0 to 18446744073709551615, got '<text>'"; nothing is
/// wrapped or rounded.
CLI::Option* add_seed_option(CLI::App& app, std::uint64_t& seed, const std::string& help,
                             const std::string& name = "--seed");

/// --out DIR: the folder of the outputs.
CLI::Option* add_out_option(CLI::App& app, std::string& out_dir, const std::string& help);

}  // namespace mrd::cli
