#pragma once
/// The control core's configuration on a board: the thesis defaults of
/// fw::ControllerConfig with the board file's mode and period. The same rule
/// as the host simulator's run::firmware_config(), so a board and `mrd sim`
/// run the same controller.

#include "firmware/app/board_config.hpp"
#include "firmware/core/controller_config.hpp"

namespace mrd::app {

inline fw::ControllerConfig core_config(const BoardConfig& board) noexcept {
  fw::ControllerConfig c;
  c.mode = board.mode;
  c.period_s = board.period_s();
  c.nominal_current_a = 2.5;  // passive-on, §6.4
  // The velocity estimate's cut-off stays below a quarter of the sampling rate.
  if (c.velocity_cutoff_hz > 0.25 / c.period_s) c.velocity_cutoff_hz = 0.25 / c.period_s;
  return c;
}

}  // namespace mrd::app
