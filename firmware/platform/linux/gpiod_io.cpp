#include "firmware/platform/linux/gpiod_io.hpp"

#include <gpiod.hpp>

#include <stdexcept>
#include <system_error>

namespace mrd::posix {

struct GpiodIo::Lines {
  gpiod::chip chip;
  gpiod::line drive_enable, drive_fault, maintenance_due;
  bool has_maintenance = false;
};

namespace {

gpiod::line find(const gpiod::chip& chip, const std::string& chip_name, const char* role, const GpiodLineSpec& s) {
  gpiod::line l = s.offset >= 0 ? chip.get_line(static_cast<unsigned>(s.offset)) : chip.find_line(s.name);
  if (!l) {
    throw std::runtime_error("GPIO chip '" + chip_name + "': no line '" + s.name + "' for " + role);
  }
  return l;
}

void request(gpiod::line& l, const std::string& chip_name, const char* role, const GpiodLineSpec& s,
             const std::string& consumer, bool output) {
  gpiod::line_request req;
  req.consumer = consumer;
  req.request_type = output ? gpiod::line_request::DIRECTION_OUTPUT : gpiod::line_request::DIRECTION_INPUT;
  if (s.active_low) req.flags = gpiod::line_request::FLAG_ACTIVE_LOW;
  try {
    l.request(req, 0);  // outputs start inactive: the drive stays off until the first tick
  } catch (const std::system_error& e) {
    throw std::runtime_error("GPIO chip '" + chip_name + "' line " + std::to_string(l.offset()) + " (" + role +
                             "): cannot request it: " + e.what() +
                             (l.is_used() ? " (in use by '" + l.consumer() + "')" : std::string()));
  }
}

}  // namespace

GpiodIo::GpiodIo(const GpiodSpec& spec) : lines_(std::make_unique<Lines>()) {
  try {
    lines_->chip.open(spec.chip, gpiod::chip::OPEN_LOOKUP);
  } catch (const std::system_error& e) {
    throw std::runtime_error("GPIO chip '" + spec.chip + "': cannot open it: " + e.what() +
                             " (see `gpiodetect`; the board needs /dev/gpiochip*)");
  }
  if (!spec.drive_enable.configured() || !spec.drive_fault.configured())
    throw std::runtime_error("GPIO chip '" + spec.chip + "': drive_enable and drive_fault lines are required");
  lines_->drive_enable = find(lines_->chip, spec.chip, "drive-enable", spec.drive_enable);
  lines_->drive_fault = find(lines_->chip, spec.chip, "drive-fault", spec.drive_fault);
  request(lines_->drive_enable, spec.chip, "drive-enable", spec.drive_enable, spec.consumer, true);
  request(lines_->drive_fault, spec.chip, "drive-fault", spec.drive_fault, spec.consumer, false);
  if (spec.maintenance_due.configured()) {
    lines_->maintenance_due = find(lines_->chip, spec.chip, "maintenance-due", spec.maintenance_due);
    request(lines_->maintenance_due, spec.chip, "maintenance-due", spec.maintenance_due, spec.consumer, true);
    lines_->has_maintenance = true;
  }
}

GpiodIo::~GpiodIo() {
  // Leave the drive disabled when the program ends normally.
  try {
    if (lines_ && lines_->drive_enable.is_requested()) lines_->drive_enable.set_value(0);
  } catch (...) {
  }
}

bool GpiodIo::write(hal::OutputLine line, bool active) noexcept {
  try {
    if (line == hal::OutputLine::kDriveEnable) {
      lines_->drive_enable.set_value(active ? 1 : 0);
    } else if (lines_->has_maintenance) {
      lines_->maintenance_due.set_value(active ? 1 : 0);
    }
    return true;
  } catch (...) {
    return false;
  }
}

bool GpiodIo::read(hal::InputLine, bool& active) noexcept {
  try {
    active = lines_->drive_fault.get_value() != 0;
    return true;
  } catch (...) {
    return false;
  }
}

std::string GpiodIo::describe() const {
  std::string s = lines_->chip.name() + " [" + lines_->chip.label() + "]: drive-enable line " +
                  std::to_string(lines_->drive_enable.offset()) + ", drive-fault line " +
                  std::to_string(lines_->drive_fault.offset());
  if (lines_->has_maintenance) s += ", maintenance-due line " + std::to_string(lines_->maintenance_due.offset());
  return s;
}

}  // namespace mrd::posix
