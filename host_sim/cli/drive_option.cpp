#include "host_sim/cli/drive_option.hpp"

namespace mrd::cli {

void add_drive_option(CLI::App& app, std::string& drive_file, const std::string& what) {
  app.add_option("--drive", drive_file,
                 "Drive file (TOML: bus, command scale, current limits, current loop; README \"Your drive\"): " + what +
                     "; default: the thesis's PWM drive (drives/thesis-pwm.toml)");
}

drive::DriveFile load_drive(const std::string& drive_file) {
  if (drive_file.empty()) return drive::thesis_drive();
  return drive::read_drive_file(drive_file);
}

drive::DriveFile drive_of_board(const app::BoardDrive& b, const std::string& origin) {
  drive::DriveFile d;
  d.name = b.name;
  d.source = "the board file's [drive]";
  d.origin = origin;
  plant::PwmDriveParams& p = d.params;
  p.bus_v = b.bus_v;
  p.command_limit_v = b.command_range_v;
  p.volts_per_amp = b.volts_per_amp;
  p.continuous_current_a = b.continuous_current_a;
  p.peak_current_a = b.peak_current_a;
  p.peak_time_s = b.peak_time_s;
  p.loop_bandwidth_rad_s = b.loop_bandwidth_rad_s;
  p.substep_s = b.loop_period_s;
  return d;
}

app::BoardDrive board_drive(const drive::DriveFile& d) {
  const plant::PwmDriveParams& p = d.params;
  app::BoardDrive b;
  b.name = d.name;
  b.bus_v = p.bus_v;
  b.command_range_v = p.command_limit_v;
  b.volts_per_amp = p.volts_per_amp;
  b.continuous_current_a = p.continuous_current_a;
  b.peak_current_a = p.peak_current_a;
  b.peak_time_s = p.peak_time_s;
  b.loop_bandwidth_rad_s = p.loop_bandwidth_rad_s;
  b.loop_period_s = p.substep_s;
  return b;
}

}  // namespace mrd::cli
