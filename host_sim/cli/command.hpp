#pragma once
/// How `mrd` subcommands plug into the program: each registers its options on
/// a CLI11 subcommand and returns the action to run once parsing succeeded.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace mrd::cli {

struct Command {
  CLI::App* app = nullptr;
  std::function<void()> run;
};

Command add_settle_command(CLI::App& parent);
Command add_modal_command(CLI::App& parent);
Command add_sine_command(CLI::App& parent);
Command add_sim_command(CLI::App& parent);
Command add_sweep_command(CLI::App& parent);
Command add_study_command(CLI::App& parent);
Command add_discrepancy_command(CLI::App& parent);
Command add_synth_command(CLI::App& parent);
Command add_schedule_command(CLI::App& parent);

/// Checks a parsed number: finite and, if `min_inclusive` is given, not below
/// it. Throws io::UsageError naming the option.
void require_finite_at_least(const std::string& option, double value, double min_inclusive);

/// Checks a parsed number is finite and > 0; throws io::UsageError
/// naming the option and `what` ("a PGA", "a duration", ...) otherwise.
void require_positive(const std::string& option, double value, const std::string& what);

}  // namespace mrd::cli
