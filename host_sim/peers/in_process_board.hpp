#pragma once
/// The `sim` board: the firmware's board runtime (control task and control
/// core), the drive node and the DAQ + plant node on an in-memory CAN bus in
/// one process, in lockstep. The firmware side is the runtime the Linux board
/// runs; only the adapters differ (in-memory bus and lines and a manual clock
/// instead of SocketCAN, libgpiod and CLOCK_MONOTONIC). Every tick goes
/// through real frames and the shared codec.

#include <memory>

#include "firmware/app/board_config.hpp"
#include "firmware/app/runtime.hpp"
#include "firmware/core/damper_controller.hpp"
#include "firmware/platform/sim/manual_clock.hpp"
#include "firmware/platform/sim/memory_bus.hpp"
#include "firmware/platform/sim/memory_io.hpp"
#include "host_sim/peers/peer_nodes.hpp"

namespace mrd::peers {

class InProcessBoard {
 public:
  using Core = fw::DamperController<num::Float32Policy>;
  using Runtime = app::BoardRuntime<Core>;

  /// Throws std::invalid_argument when the core rejects the board's
  /// configuration (naming the field).
  InProcessBoard(const app::BoardConfig& board, const plant::PlantSpec& plant, const DriveConfig& drive);

  /// One lockstep tick at ground acceleration `ag`: plant → drive status →
  /// controller → command → drive → plant. A command lost on the wire makes
  /// the drive decide without it (its timeout rule); a lost coil-drive frame
  /// leaves the coil on the drive's previous output.
  void step(double ground_accel_m_s2);

  plant::PlantSummary summary() const noexcept { return plant_->model().summary(); }
  const app::ControlTaskStatus& task_status() const noexcept { return runtime_->task().status(); }
  const DriveLogic& drive() const noexcept { return drive_->logic(); }
  const plant::Plant& plant() const noexcept { return plant_->model(); }

  // Fault injection.
  sim::MemoryBus& bus() noexcept { return bus_; }
  sim::MemoryCanEndpoint& controller_endpoint() noexcept { return *controller_ep_; }
  sim::MemoryIo& io() noexcept { return io_; }
  DriveNode& drive_node() noexcept { return *drive_; }
  /// The current the drive applied over the last tick (0 when its output is off), A.
  double applied_current_a() const noexcept;

 private:
  sim::MemoryBus bus_;
  sim::MemoryCanEndpoint* controller_ep_ = nullptr;
  sim::MemoryCanEndpoint* drive_ep_ = nullptr;
  sim::MemoryCanEndpoint* plant_ep_ = nullptr;
  sim::MemoryIo io_;
  sim::ManualClock clock_;
  std::int64_t period_ns_ = 0;
  Core core_;
  std::unique_ptr<Runtime> runtime_;
  std::unique_ptr<DriveNode> drive_;
  std::unique_ptr<PlantNode> plant_;
};

}  // namespace mrd::peers
