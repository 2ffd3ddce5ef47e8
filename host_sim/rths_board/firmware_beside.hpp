#pragma once
/// The board's firmware control task beside the RTHS runtime in one
/// process: the control core (fw::DamperController, the board file's
/// [controller] at its [control] period and mode) and the board runtime's
/// control task (app::BoardRuntime), exactly as `mrd-firmware` builds them,
/// on their own CAN endpoint (a second SocketCAN socket on the board, or an
/// in-memory endpoint). DamperLoop calls tick() once per loop tick, after
/// the laboratory's DaqMotion/DriveStatus and the runtime's DaqAccel for the
/// tick have been sent.

#include <stdexcept>
#include <string>

#include "firmware/app/board_config.hpp"
#include "firmware/app/no_lines_fitted.hpp"
#include "firmware/app/runtime.hpp"
#include "firmware/core/controller_config.hpp"
#include "firmware/core/damper_controller.hpp"

namespace mrd::rths_board {

template <class Policy>
class FirmwareBeside {
 public:
  using Core = fw::DamperController<Policy>;

  /// Throws std::invalid_argument naming the core's objection when it
  /// rejects the board's configuration.
  FirmwareBeside(const app::BoardConfig& board, hal::CanBus& bus, hal::Clock& clock) {
    const fw::ConfigError e = core_.init(board.controller_config());
    if (e != fw::ConfigError::kNone)
      throw std::invalid_argument(std::string("the control core rejects the board configuration: ") +
                                  fw::config_error_name(e));
    app::RuntimeConfig rc;
    rc.period_ns = static_cast<std::int64_t>(board.period_us) * 1000;
    rc.name = "mrd-rths";
    runtime_ = std::make_unique<app::BoardRuntime<Core>>(core_, app::RuntimePorts{clock, bus, io_},
                                                         board.task_config(), rc);
  }

  /// One control tick on what has arrived (the runtime's run_tick).
  control::ControllerOutput tick() noexcept { return runtime_->run_tick(); }
  const app::ControlTaskStatus& status() const noexcept { return runtime_->task().status(); }

 private:
  Core core_;
  app::NoLinesFitted io_;
  std::unique_ptr<app::BoardRuntime<Core>> runtime_;
};

}  // namespace mrd::rths_board
