#pragma once
/// The board file (boards/<name>/board.toml): CAN interface and node ids,
/// GPIO chip and lines (or `fitted = false` for a board without them),
/// control period and mode, real-time settings, where the idle-time
/// estimator's state is kept ([state]), the mixing scheduler's settings
/// ([mixing]), and the configuration `mrd configure` derives for one
/// building, damper and fluid: the control core's constants ([controller],
/// fw::ControllerConfig's fields by name), the damper ([damper]) and the
/// fluid ([fluid]), and the current drive it commands ([drive], optional;
/// the controller's limits are checked against it). Without those tables a
/// board runs the thesis's controller, damper and fluid. Read once at start-up; every error names
/// the file, the line and the field, and a [controller] the control core
/// would refuse (fw::validate_config, for the board's numeric build) is
/// refused here, naming the keys it concerns.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <map>
#include <optional>

#include "firmware/app/control_task.hpp"
#include "firmware/app/mixing_task.hpp"
#include "firmware/core/controller_config.hpp"
#include "mrd/control/io.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/settling.hpp"
#include "mrd/protocol/messages.hpp"

namespace mrd::app {

/// A bad board file: what() is one line "FILE:LINE: field: problem".
class BoardConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One GPIO line: an offset on the chip, or a line name the chip knows.
struct GpioLine {
  int offset = -1;          ///< ≥ 0 when given as a number
  std::string name;         ///< non-empty when given as a name
  bool active_low = false;  ///< electrical level 0 means "active"
  bool configured() const noexcept { return offset >= 0 || !name.empty(); }
};

/// The current drive the board commands ([drive], optional): what `mrd
/// configure --drive` read from a drive file (host_sim/drive), so that the
/// board's controller is checked against it at boot and `mrd sim --board
/// --plant hardware` simulates it. The firmware commands through CAN and does
/// not use these numbers otherwise.
struct BoardDrive {
  std::string name;
  double bus_v = 72.0;                  ///< DC bus, V
  double command_range_v = 10.0;        ///< the command input's range, ±V
  double volts_per_amp = 1.0;           ///< command scale, V/A
  double continuous_current_a = 15.0;   ///< A
  double peak_current_a = 30.0;         ///< A
  double peak_time_s = 2.0;             ///< time at the peak its I²t budget allows, s
  double loop_bandwidth_rad_s = 200.0;  ///< ω_c of its PI current loop
  double loop_period_s = 1.0e-4;        ///< its current loop's period, s
  /// The command range in amperes: command_range_v / volts_per_amp.
  double command_limit_a() const noexcept { return command_range_v / volts_per_amp; }
};

struct BoardConfig {
  std::string name;
  std::string description;
  // [control]
  std::uint32_t period_us = 1000;
  control::ControlMode mode = control::ControlMode::kSemiActive;
  bool fixed_point = false;  ///< numeric = "fixed"
  std::uint32_t sensor_timeout_ticks = 10;
  std::uint32_t drive_status_timeout_ticks = 10;
  std::uint32_t heartbeat_period_ticks = 100;
  // [can]
  std::string can_interface;  ///< e.g. "can0", "vcan0"; empty for the in-process board
  protocol::NodeIds nodes{};
  // [gpio]: required; either the chip and its lines or `fitted = false`
  bool gpio_fitted = false;  ///< false: the board has no discrete lines (app::NoLinesFitted)
  std::string gpio_chip;     ///< e.g. "gpiochip0"
  GpioLine drive_enable, drive_fault, maintenance_due;
  // [realtime]
  int sched_fifo_priority = 0;  ///< 1..99 asks for SCHED_FIFO; 0 leaves the scheduler alone
  bool lock_memory = false;     ///< mlockall(MCL_CURRENT | MCL_FUTURE)
  int cpu = -1;                 ///< pin the control thread to this CPU; −1 leaves it free
  // [state]
  std::string state_path = "/var/lib/mrd/state.bin";  ///< absolute; its folder must exist (systemd StateDirectory=mrd)
  double save_every_s = 3600.0;  ///< the estimator saves at least this often while running, s
  // [mixing]: the scheduler's settings (period and flow area come from the estimator)
  fw::MixingSchedulerConfig mixing{};
  double dead_band_m = 1.0e-4;  ///< estimator's play operator half-width, m (above the stroke sensor's noise)
  // [controller]: the control core's constants; keys not given keep
  // fw::default_controller_config(mode, period)'s. Its period and mode are [control]'s.
  fw::ControllerConfig controller{};
  // [damper]: its laws (Table 4.1 names), coil, rating, mixing area and the
  // geometry the settling model uses; [fluid]: Table 5.3, Table 5.6 and an
  // optional measured maximum settling time.
  std::string damper_name = "thesis-200kn";
  std::string fluid_name = "thesis-model-fluid";
  physics::MrDamperParams damper{};
  physics::SettlingParams settling{};  ///< fluid (Table 5.3) and damper geometry (Table 3.1, 5.4)
  // [drive]: the current drive (absent: not stated; the controller's limits are [controller]'s).
  std::optional<BoardDrive> drive;

  double period_s() const noexcept { return static_cast<double>(period_us) * 1e-6; }
  ControlTaskConfig task_config() const noexcept;
  /// The idle-time estimator and the mixing scheduler at the control period,
  /// with the board's damper and fluid.
  MixingTaskConfig mixing_task_config() const noexcept;
  /// What the control core runs: [controller] at [control]'s period and mode
  /// (as they are now: a program's --mode overrides the file's).
  fw::ControllerConfig controller_config() const noexcept {
    fw::ControllerConfig c = controller;
    c.mode = mode;
    c.period_s = period_s();
    return c;
  }
};

/// What is wrong with an existing path as the state file, in the words of
/// the reader policy ("is a pipe (FIFO), expected a regular file"), or empty
/// when it is a regular file or does not exist yet. The programs pass the
/// platform's check (posix::non_regular_problem, firmware/platform/linux/
/// regular_file.hpp).
using StatePathCheck = std::string (*)(const std::string& path);

/// Parses TOML text; `origin` names the file in error messages. [state] path
/// must be an absolute file path without a NUL character; with
/// `check_state_path`, one that names a folder, a FIFO or a device is refused
/// too (without, only the text is checked: parsing alone touches no file).
BoardConfig parse_board_config(const std::string& text, const std::string& origin,
                               StatePathCheck check_state_path = nullptr);

/// The board file of `c`: every table with every value, numbers written so
/// that they read back exactly (parse_board_config(board_toml(c)) == c).
/// `header` is written first as comment lines (each prefixed "# ").
std::string board_toml(const BoardConfig& c, const std::string& header = "");

/// Largest board file read, bytes. The programs read the board file under
/// the reader policy (posix::read_regular_file: a regular file, opened
/// without blocking, at most this long) and hand its text to
/// parse_board_config() with posix::non_regular_problem.
inline constexpr std::size_t kMaxBoardFileBytes = std::size_t{1} << 20;

}  // namespace mrd::app
