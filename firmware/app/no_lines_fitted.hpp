#pragma once
/// The discrete lines of a board that has none (`[gpio] fitted = false` in
/// its board file): writes are accepted and go nowhere, and the drive-fault
/// input reads inactive, so the drive's own fault report over CAN is the
/// only fault the controller sees.

#include "mrd/hal/digital_io.hpp"

namespace mrd::app {

class NoLinesFitted final : public hal::DigitalIo {
 public:
  bool write(hal::OutputLine, bool) noexcept override { return true; }
  bool read(hal::InputLine, bool& active) noexcept override {
    active = false;
    return true;
  }
};

}  // namespace mrd::app
