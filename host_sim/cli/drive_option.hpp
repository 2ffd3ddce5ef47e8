#pragma once
/// `--drive FILE`: the current drive that feeds the coil (a drive file,
/// host_sim/drive/drive_file.hpp; README "Your drive"). Without it, the
/// thesis's drive (drives/thesis-pwm.toml).

#include <CLI/CLI.hpp>

#include <string>

#include "firmware/app/board_config.hpp"
#include "host_sim/drive/drive_file.hpp"

namespace mrd::cli {

/// Registers --drive FILE on `app`; `what` says what the command does with it.
void add_drive_option(CLI::App& app, std::string& drive_file, const std::string& what);

/// The drive `drive_file` describes (io::UsageError with file:line:field for
/// a bad file); the thesis drive for an empty name.
drive::DriveFile load_drive(const std::string& drive_file);

/// A board file's [drive] as a drive (origin: the board file's label).
drive::DriveFile drive_of_board(const app::BoardDrive& b, const std::string& origin);

/// A drive as a board file's [drive].
app::BoardDrive board_drive(const drive::DriveFile& d);

}  // namespace mrd::cli
