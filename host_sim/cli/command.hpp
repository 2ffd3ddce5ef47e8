#pragma once
/// How `mrd` subcommands plug into the program: each registers its options on
/// a CLI11 subcommand and returns the action to run once parsing succeeded.
/// An action checks its options, calls one function that computes and one
/// that writes the outputs, and prints a short summary.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "host_sim/report/path_ownership.hpp"

namespace mrd::cli {

struct Command {
  CLI::App* app = nullptr;
  std::function<void()> run;
};

/// What --help says about a subcommand.
struct CommandHelp {
  const char* name;
  const char* description;  ///< one line, listed by `mrd --help`
  const char* footer;       ///< after the options in `mrd <name> --help`: fields, units, files
};

/// Refuses an empty value ("--opt ''") for every option of `app` that takes
/// one: an empty value is an error, never a default or zero.
void refuse_empty_values(CLI::App& app);

/// Subcommand `help.name` of `parent` with an Options object that its
/// action keeps alive: `add_options` registers the options on it (each
/// refusing an empty value), and `execute` is the action, run once parsing
/// succeeded.
template <class Options>
Command make_command(CLI::App& parent, const CommandHelp& help, void (*add_options)(CLI::App&, Options&),
                     void (*execute)(const Options&)) {
  auto options = std::make_shared<Options>();
  CLI::App* app = parent.add_subcommand(help.name, help.description);
  add_options(*app, *options);
  refuse_empty_values(*app);
  app->footer(help.footer);
  return {app, [options, execute] { execute(*options); }};
}

Command add_settle_command(CLI::App& parent);
Command add_modal_command(CLI::App& parent);
Command add_sine_command(CLI::App& parent);
Command add_sim_command(CLI::App& parent);
Command add_sweep_command(CLI::App& parent);
Command add_study_command(CLI::App& parent);
Command add_discrepancy_command(CLI::App& parent);
Command add_calibrate_command(CLI::App& parent);
Command add_synth_command(CLI::App& parent);
Command add_schedule_command(CLI::App& parent);
Command add_fragility_command(CLI::App& parent);
Command add_risk_command(CLI::App& parent);
Command add_configure_command(CLI::App& parent);
Command add_rths_command(CLI::App& parent);

/// Checks the list options of the parsed subcommand `sub` (`args`: the
/// command line after the program name): an empty item ("0.1,,0.2") or a value
/// given twice (as text, or as the same number) is an io::UsageError naming
/// the option. CLI11 drops empty items itself, hence `args`.
void check_list_values(const CLI::App& sub, const std::vector<std::string>& args);

/// The inputs of the parsed subcommand `sub`: every value of an option other
/// than --out and --journal that names an existing path (resolved), for
/// report::declare_inputs.
std::vector<report::InputPath> input_paths(const CLI::App& sub);

/// With --out given to the parsed subcommand `sub`: report::check_output_folder
/// on it, so that a folder that is not mrd's or overlaps an input is refused
/// before any work.
void check_given_out(const CLI::App& sub);

/// Starts the transaction on the --out folder (report::begin_output) and
/// returns the staging folder the outputs go to; io::UsageError naming the
/// folder when it cannot be used. The result replaces the folder as a whole at
/// commit_out_dir, or at the end of a command that returns normally (`mrd`'s
/// main commits what is still open); an error or a signal leaves the folder as
/// it was.
std::filesystem::path open_out_dir(const std::string& out_dir);

/// Puts every written output folder in place (report::commit_outputs).
void commit_out_dir();

/// A path inside a staging folder as the user named it (report::shown_path).
std::filesystem::path shown_path(const std::filesystem::path& path);

/// open_out_dir when a folder was given; nullopt for an empty `out_dir`.
std::optional<std::filesystem::path> open_optional_out_dir(const std::string& out_dir);

/// Prints "mrd <command>: warning: <sentence>" on stderr for each warning
/// (results beyond the model's validity, run::validity_warnings).
void print_warnings(const char* command, const std::vector<std::string>& warnings);

/// Prints "mrd <command>: warning: plot not written: <problem>" on stderr
/// for each problem a writer returned.
void warn_plots_not_written(const char* command, const std::vector<std::string>& problems);

/// The steps of a subcommand whose --out is optional, once its options are
/// checked: opens the folder first (a bad folder fails before any work),
/// computes, prints the result, and with a folder writes the outputs, puts
/// them in place (commit_out_dir), warns about plots not drawn (when `write`
/// returns their problems) and prints `wrote_format` with the path of
/// summary.json.
template <class Compute, class Print, class Write>
void compute_print_write(const char* command, const std::string& out_dir, const Compute& compute, const Print& print,
                         const Write& write, const char* wrote_format = "wrote %s\n") {
  const auto out = open_optional_out_dir(out_dir);
  const auto result = compute();
  print(result);
  if (!out) return;
  if constexpr (std::is_void_v<decltype(write(*out, result))>) {
    write(*out, result);
    commit_out_dir();
  } else {
    const auto problems = write(*out, result);
    warn_plots_not_written(command, problems);
    commit_out_dir();
  }
  std::printf(wrote_format, (std::filesystem::path(out_dir) / "summary.json").c_str());
}

}  // namespace mrd::cli
