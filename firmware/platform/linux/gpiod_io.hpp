#pragma once
/// hal::DigitalIo on a Linux GPIO character device through libgpiod 1.6
/// (C++ bindings). Lines are requested once, at construction (libgpiod
/// allocates there); write() and read() only set and get values. The only
/// file that includes <gpiod.hpp>; libgpiod v2 would replace this file alone.

#include <memory>
#include <string>

#include "mrd/hal/digital_io.hpp"

namespace mrd::posix {

struct GpiodLineSpec {
  int offset = -1;          ///< line offset, or −1 to look the line up by `name`
  std::string name;         ///< line name (device tree / ACPI), used when offset < 0
  bool active_low = false;  ///< logical "active" is electrical 0
  bool configured() const noexcept { return offset >= 0 || !name.empty(); }
};

struct GpiodSpec {
  std::string chip;  ///< "gpiochip0", "/dev/gpiochip0" or a chip label
  GpiodLineSpec drive_enable;
  GpiodLineSpec drive_fault;
  GpiodLineSpec maintenance_due;  ///< optional
  std::string consumer = "mrd-firmware";
};

class GpiodIo final : public hal::DigitalIo {
 public:
  /// Opens the chip and requests drive-enable (output, inactive), drive-fault
  /// (input) and, if configured, maintenance-due (output, inactive). Throws
  /// std::runtime_error naming the chip, the line and the reason (no such
  /// chip, line busy, …).
  explicit GpiodIo(const GpiodSpec& spec);
  ~GpiodIo() override;
  GpiodIo(const GpiodIo&) = delete;
  GpiodIo& operator=(const GpiodIo&) = delete;

  bool write(hal::OutputLine line, bool active) noexcept override;
  bool read(hal::InputLine line, bool& active) noexcept override;

  /// The chip's name and label, and the line offsets in use, for the log.
  std::string describe() const;

 private:
  struct Lines;
  std::unique_ptr<Lines> lines_;
};

}  // namespace mrd::posix
