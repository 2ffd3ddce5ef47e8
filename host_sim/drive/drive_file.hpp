#pragma once
/// The drive file of `--drive FILE`: the current drive that feeds the
/// damper's coil (§3.2), as the hardware plant simulates it
/// (plant/pwm_drive.hpp) and as `mrd configure` limits the controller's
/// commands to it. README "Your drive".
///
/// <pre>
///   [drive]   name, source (where the numbers come from)
///             bus_v                 DC bus, V
///             command_range_v       the command input's range, ±V
///             volts_per_amp         command scale, V/A
///             continuous_current_a  A
///             peak_current_a        A (at least the continuous current)
///             peak_time_s           time at the peak the I²t budget allows, s
///             loop_bandwidth_rad_s  ω_c of the PI current loop
///             loop_period_s         the current loop's period, s
/// </pre>
/// Without a file, the thesis's drive (drives/thesis-pwm.toml, which reads
/// back to exactly plant::PwmDriveParams{}).

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "host_sim/plant/coil.hpp"
#include "host_sim/plant/pwm_drive.hpp"

namespace mrd::drive {

/// Largest drive file read, bytes: a file is well under 2 kB.
inline constexpr std::size_t kMaxDriveFileBytes = std::size_t{1} << 20;

struct DriveFile {
  std::string name = "thesis-pwm";
  std::string source = "thesis §3.2: 30A8 analog servo drive (PWM) on a 72 V DC supply, 15 A continuous, 30 A peak, ±10 V at 1 V/A";
  plant::PwmDriveParams params{};
  /// Where the file states the current loop (for the refusal of a loop the
  /// coil makes ring, check_drive_fit); "" and 0 for the thesis drive.
  std::string origin;
  std::size_t loop_bandwidth_line = 0;
};

/// The thesis's drive without a file: plant::PwmDriveParams{}.
[[nodiscard]] DriveFile thesis_drive();

/// Parses a drive file's text. Errors read `origin:LINE: drive.key: what was
/// expected` and are thrown as io::UsageError: a syntax error, a missing or
/// unknown table or key, a wrong type, a non-finite number, a number outside
/// its physical range (drive_ranges.hpp; the message states the range), a
/// peak current below the continuous one.
[[nodiscard]] DriveFile parse_drive_toml(const std::string& text, const std::string& origin);

/// Reads a drive file (a regular file of at most kMaxDriveFileBytes).
[[nodiscard]] DriveFile read_drive_file(const std::filesystem::path& path);

/// The drive's command range in amperes: command_range_v / volts_per_amp.
[[nodiscard]] double command_limit_a(const plant::PwmDriveParams& d) noexcept;

/// The drive `d` on the coil `coil` (whose rating is `rated_current_a`) at
/// the control step `step_s`. Throws io::UsageError, naming the file, line
/// and field, when the sampled current loop would ring: K_p·T/L_min =
/// ω_c L(1 A) T / L_min above kMaxLoopStepGain. Returns warnings, one
/// sentence each: a bus that cannot drive the rated current through the
/// coil's resistance; a loop period that is not a whole fraction of the step
/// (the loop then runs at the nearest one).
[[nodiscard]] std::vector<std::string> check_drive_fit(const DriveFile& d, const plant::CoilParams& coil,
                                                       double rated_current_a, double step_s);

}  // namespace mrd::drive
