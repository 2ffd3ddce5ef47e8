/// `mrd`: the host command-line tool. Each subcommand writes DIR/summary.json
/// (and time series and plots where they apply) when given `--out DIR`.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "host_sim/cli/command.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/report/output_transaction.hpp"

namespace {
constexpr int kExitUsage = 2;

void print_error(const char* what) { std::fprintf(stderr, "mrd: error: %s\n", what); }
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "mrd: controller and host tools for a 200 kN MR damper in a base-isolated building.\n"
      "Units are SI unless a field name says otherwise (_kn, _mm, _years).",
      "mrd"};
  app.require_subcommand(1);
  app.footer("Run 'mrd <subcommand> --help' for its options, output fields and units.");

  std::vector<mrd::cli::Command> commands;
  commands.push_back(mrd::cli::add_settle_command(app));
  commands.push_back(mrd::cli::add_modal_command(app));
  commands.push_back(mrd::cli::add_sine_command(app));
  commands.push_back(mrd::cli::add_sim_command(app));
  commands.push_back(mrd::cli::add_sweep_command(app));
  commands.push_back(mrd::cli::add_study_command(app));
  commands.push_back(mrd::cli::add_discrepancy_command(app));
  commands.push_back(mrd::cli::add_calibrate_command(app));
  commands.push_back(mrd::cli::add_synth_command(app));
  commands.push_back(mrd::cli::add_schedule_command(app));
  commands.push_back(mrd::cli::add_fragility_command(app));
  commands.push_back(mrd::cli::add_risk_command(app));
  commands.push_back(mrd::cli::add_configure_command(app));
  commands.push_back(mrd::cli::add_rths_command(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    print_error(e.what());
    return kExitUsage;
  }

  try {
    const std::vector<std::string> args(argv + 1, argv + argc);
    for (const auto& c : commands) {
      if (!c.app->parsed()) continue;
      mrd::cli::check_list_values(*c.app, args);
      mrd::report::declare_inputs(mrd::cli::input_paths(*c.app));
      mrd::cli::check_given_out(*c.app);
      c.run();
    }
    mrd::report::commit_outputs();
  } catch (const mrd::io::UsageError& e) {
    mrd::report::abandon_outputs();
    print_error(e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    mrd::report::abandon_outputs();
    print_error(e.what());
    return 1;
  }
  return 0;
}
