#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "firmware/app/board_config.hpp"
#include "firmware/platform/linux/regular_file.hpp"
#include "host_sim/cli/building_option.hpp"
#include "host_sim/cli/command.hpp"
#include "host_sim/cli/damper_option.hpp"
#include "host_sim/cli/drive_option.hpp"
#include "host_sim/cli/fluid_option.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/configure/configure.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/report/output_dir.hpp"

namespace mrd::cli {
namespace configure_command {
namespace {

constexpr CommandHelp kConfigureHelp{
    "configure", "A board file configured for your building, damper and fluid, with how each number was derived",
    R"(Writes DIR/board.toml: the --board file with its [controller], [damper] and [fluid] tables (and the
[mixing] amplitude, velocity and dead band) derived from --building, --damper and --fluid, and
DIR/configure.md: every derived number, its rule and inputs. mrd-firmware runs that board file as
it is (validated at boot), and `mrd sim --board DIR/board.toml` simulates the same configuration.
Rules: RILD's k is the effective stiffness of the first damper's element (an isolation layer with
bearings: its springs plus the bearings' secant stiffness at --design-displacement-m, default half
the damper's rated stroke), ω_f the building's fundamental mode with that layer linear, η = 0.8
(§6.3); |F_d| <= 2 F_rated, load-cell guard 2.5 F_rated, deadband 1 % F_rated; I_r = I_nom = the
rated current, forcing ±min(4 I_r, the drive's command range: --drive-command-limit-a, default the
thesis rig's 10 A), band 4 % I_r; the drive's continuous and peak currents (--drive-continuous-limit-a,
--drive-peak-limit-a, default 15 and 30 A) are the core's limits; --drive FILE gives all three from a
drive file (README "Your drive": command_range_v / volts_per_amp, continuous_current_a,
peak_current_a); direction thresholds 10 and 5 σ_v of the
velocity estimate on the stroke sensor's noise (--disp-noise-m, 16-bit over the rated stroke);
mixing within 0.26 × the stroke and 0.4 × the rated velocity. The control core's own checks run
before anything is written: a configuration it (or the fixed-point build) would refuse is an error.)"};

struct ConfigureOptions {
  std::string building, damper, fluid, board, out_dir;
  double design_displacement_m = 0.0;
  double disp_noise_m = 2.0e-6;
  configure::DriveLimits drive{};
  std::string drive_file;
  bool drive_limit_given = false;  ///< one of --drive-*-limit-a
};

void add_options(CLI::App& app, ConfigureOptions& o) {
  add_building_option(app, o.building);
  add_damper_option(app, o.damper);
  add_fluid_option(app, o.fluid);
  app.add_option("--board", o.board, "The board file to configure (boards/<name>/board.toml)")->required();
  add_out_option(app, o.out_dir, "Folder for board.toml and configure.md (created if missing)")->required();
  app.add_option("--design-displacement-m", o.design_displacement_m,
                 "Design displacement of the isolation layer for the bearings' secant stiffness, m (default: half "
                 "the damper's rated stroke)")
      ->check(CLI::PositiveNumber);
  app.add_option("--disp-noise-m", o.disp_noise_m, "RMS noise of the stroke sensor, m (default: the thesis LVDT's)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  add_drive_option(app, o.drive_file, "the core's command range, continuous and peak currents are its");
  const auto given = [&o](const std::string&) { o.drive_limit_given = true; };
  app.add_option("--drive-command-limit-a", o.drive.command_limit_a,
                 "The current drive's command range, ±A (default: the thesis rig's, 10 V at 1 V/A)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->each(given);
  app.add_option("--drive-continuous-limit-a", o.drive.continuous_limit_a,
                 "The drive's continuous current, A (default: the thesis rig's)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->each(given);
  app.add_option("--drive-peak-limit-a", o.drive.peak_limit_a,
                 "The drive's peak current, A, also the coil's current limit (default: the thesis rig's)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->each(given);
}

/// --drive FILE's limits: its command range (command_range_v / volts_per_amp),
/// continuous and peak currents, in the core's order.
configure::DriveLimits file_drive_limits(const std::string& label, const drive::DriveFile& d) {
  const plant::PwmDriveParams& p = d.params;
  configure::DriveLimits l;
  l.command_limit_a = drive::command_limit_a(p);
  l.continuous_limit_a = p.continuous_current_a;
  l.peak_limit_a = p.peak_current_a;
  if (!(l.command_limit_a <= l.continuous_limit_a))
    throw io::UsageError(label + ": drive.command_range_v: the command range ±" +
                         io::format_number("%g", l.command_limit_a) + " A (command_range_v / volts_per_amp) exceeds "
                         "continuous_current_a (" + io::format_number("%g", l.continuous_limit_a) +
                         " A): the control core commands within the continuous current (give the limits with "
                         "--drive-command-limit-a, --drive-continuous-limit-a, --drive-peak-limit-a instead)");
  return l;
}

/// The drive's three limits in the core's order: command range <= continuous <= peak.
void check_drive(const configure::DriveLimits& d) {
  if (!(d.command_limit_a <= d.continuous_limit_a))
    throw io::UsageError("--drive-command-limit-a: expected at most the continuous current --drive-continuous-limit-a (" +
                         io::format_number("%g", d.continuous_limit_a) + " A), got " +
                         io::format_number("%g", d.command_limit_a));
  if (!(d.continuous_limit_a <= d.peak_limit_a))
    throw io::UsageError("--drive-continuous-limit-a: expected at most the peak current --drive-peak-limit-a (" +
                         io::format_number("%g", d.peak_limit_a) + " A), got " +
                         io::format_number("%g", d.continuous_limit_a));
}

std::string stem_or(const std::string& path, const char* fallback) {
  return path.empty() ? fallback : std::filesystem::path(path).stem().string();
}

void execute(const ConfigureOptions& o) {
  configure::Inputs in;
  try {
    in.board = app::parse_board_config(io::read_regular_file(o.board, app::kMaxBoardFileBytes),
                                       io::file_label(o.board));
  } catch (const app::BoardConfigError& e) {
    throw io::UsageError(e.what());
  }
  // The drive: --drive FILE, else the board's own [drive], else the three limits (the thesis rig's by default).
  std::optional<drive::DriveFile> drive_file;
  std::string drive_label;
  if (!o.drive_file.empty()) {
    drive_file = load_drive(o.drive_file);
    drive_label = io::file_label(o.drive_file);
  } else if (in.board.drive) {
    drive_label = io::file_label(o.board) + " [drive]";
    drive_file = drive_of_board(*in.board.drive, drive_label);
  }
  if (drive_file) {
    if (o.drive_limit_given)
      throw io::UsageError(std::string("--drive-command-limit-a, --drive-continuous-limit-a, --drive-peak-limit-a "
                                       "cannot be given with ") +
                           (o.drive_file.empty() ? "a board file that has a [drive] table: it decides them (--drive "
                                                   "FILE replaces it)"
                                                 : "--drive: the drive file decides them"));
    in.drive = file_drive_limits(drive_label, *drive_file);
    in.drive_source = "the drive file's, " + drive_file->name;
    in.board.drive = board_drive(*drive_file);
  } else {
    check_drive(o.drive);
    in.drive = o.drive;
  }
  in.building = load_building(o.building);
  in.building_name = in.building.name.empty() ? stem_or(o.building, "thesis-6dof") : in.building.name;
  const DamperAndFluid df = load_damper_and_fluid("configure", o.damper, o.fluid);
  in.damper = df.params;
  in.damper_name = df.damper.name;
  in.settling = df.settling;
  in.fluid_name = stem_or(o.fluid, "thesis-model-fluid");
  if (drive_file) {
    // The drive on this damper's coil at the board's control period, as `mrd sim --plant hardware` runs it.
    std::vector<std::string> warnings = drive::check_drive_fit(
        *drive_file, plant::coil_params(in.damper.coil_heat.resistance_ohm, in.damper.coil_inductance),
        in.damper.rating.current_a, in.board.period_s());
    for (std::string& w : warnings) w = drive_label + ": " + w;
    print_warnings("configure", warnings);
  }
  in.design_displacement_m = o.design_displacement_m;
  in.sensor.noise_rms_m = o.disp_noise_m;
  const configure::Result r = configure::configure(in);
  const std::string toml = app::board_toml(
      r.board, "Board file configured by `mrd configure` for building " + in.building_name + ", damper " +
                   in.damper_name + ", fluid " + in.fluid_name + ".\nHow each number was derived: configure.md.");
  // What the board reads back is what was derived: parse it as mrd-firmware will.
  try {
    (void)app::parse_board_config(toml, "board.toml");
  } catch (const app::BoardConfigError& e) {
    throw io::UsageError(std::string("configure: the configured board file does not read back: ") + e.what());
  }
  const auto out = open_optional_out_dir(o.out_dir);
  report::write_file_atomically(*out / "board.toml", toml);
  report::write_file_atomically(*out / "configure.md", configure::configure_markdown(in, r));
  commit_out_dir();
  for (const configure::Derived& d : r.derived) {
    std::printf("  %-36s %14.6g %-6s\n", d.field.c_str(), d.value, d.unit.c_str());
  }
  for (const std::string& n : r.notes) std::printf("note: %s\n", n.c_str());
  std::printf("wrote %s and %s\n", (std::filesystem::path(o.out_dir) / "board.toml").c_str(),
              (std::filesystem::path(o.out_dir) / "configure.md").c_str());
}

}  // namespace
}  // namespace configure_command

Command add_configure_command(CLI::App& parent) {
  using namespace configure_command;
  return make_command(parent, kConfigureHelp, add_options, execute);
}

}  // namespace mrd::cli
