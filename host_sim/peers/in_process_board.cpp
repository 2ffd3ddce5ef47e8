#include "host_sim/peers/in_process_board.hpp"

#include <stdexcept>
#include <string>

#include "firmware/core/controller_config.hpp"

namespace mrd::peers {

InProcessBoard::InProcessBoard(const app::BoardConfig& board, const plant::PlantSpec& plant, const DriveConfig& drive) {
  controller_ep_ = &bus_.attach();
  drive_ep_ = &bus_.attach();
  plant_ep_ = &bus_.attach();
  controller_ep_->set_filters(app::control_task_filters(board.nodes));
  drive_ep_->set_filters(drive_filters(board.nodes));
  plant_ep_->set_filters(plant_filters(board.nodes));
  const fw::ConfigError e = core_.init(board.controller_config());
  if (e != fw::ConfigError::kNone)
    throw std::invalid_argument(std::string("control core rejects the board configuration: ") +
                                fw::config_error_name(e));
  period_ns_ = static_cast<std::int64_t>(board.period_us) * 1000;
  app::RuntimeConfig rc;
  rc.period_ns = period_ns_;
  runtime_ = std::make_unique<Runtime>(core_, app::RuntimePorts{clock_, *controller_ep_, io_}, board.task_config(), rc);
  DriveConfig dc = drive;
  dc.nodes = board.nodes;
  drive_ = std::make_unique<DriveNode>(*drive_ep_, dc, board.period_s());
  plant_ = std::make_unique<PlantNode>(*plant_ep_, board.nodes, plant);
}

void InProcessBoard::step(double ground_accel_m_s2) {
  plant_->begin_tick(ground_accel_m_s2);
  drive_->poll();  // SimCoilState → DriveStatus
  // In lockstep every input of the tick is here unless a frame was lost on
  // the wire; the runtime then runs on what it has, as on a board.
  runtime_->run_tick();  // → CurrentCommand
  clock_.advance_ns(period_ns_);
  drive_->poll();  // command → SimCoilDrive
  if (drive_->awaiting_command()) drive_->decide_without_command();
  // A lost coil-drive frame: the coil keeps the drive's previous output.
  if (!plant_->try_finish_tick()) plant_->force_finish_tick();
}

double InProcessBoard::applied_current_a() const noexcept {
  const DriveOutput& o = drive_->logic().output();
  return o.output_on ? static_cast<double>(o.applied_current_a) : 0.0;
}

}  // namespace mrd::peers
