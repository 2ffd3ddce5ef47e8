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

}  // namespace mrd::cli
