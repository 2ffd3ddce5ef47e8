#pragma once
/// The board's discrete lines as the control task sees them. Values are
/// logical ("active" = enable the drive, fault present, maintenance due);
/// the adapter applies each line's electrical polarity from the board file.
/// Implementations: libgpiod 1.6 (firmware/platform/linux/gpiod_io), none
/// fitted (firmware/app/no_lines_fitted) and an in-memory fake
/// (firmware/platform/sim/memory_io).

#include <cstdint>

namespace mrd::hal {

enum class OutputLine : std::uint8_t {
  kDriveEnable = 0,     ///< to the PWM drive: output stage enabled when active
  kMaintenanceDue = 1,  ///< to the building's maintenance panel: mixing or service due
};

enum class InputLine : std::uint8_t {
  kDriveFault = 0,  ///< from the PWM drive: active while the drive reports a fault
};

inline constexpr int kOutputLineCount = 2;
inline constexpr int kInputLineCount = 1;

constexpr const char* line_name(OutputLine l) noexcept {
  return l == OutputLine::kDriveEnable ? "drive-enable" : "maintenance-due";
}
constexpr const char* line_name(InputLine) noexcept { return "drive-fault"; }

/// Setting and reading lines never blocks and never allocates.
class DigitalIo {
 public:
  virtual ~DigitalIo() = default;
  /// Drives `line` to its logical level; false on an I/O error.
  virtual bool write(OutputLine line, bool active) noexcept = 0;
  /// Reads the logical level of `line` into `active`; false on an I/O error
  /// (then `active` is left unchanged).
  virtual bool read(InputLine line, bool& active) noexcept = 0;
};

}  // namespace mrd::hal
