// Costs of the board's per-tick work: the codec, one control-task tick
// (drain rx → decode → core step → encode → tx → lines) on an in-memory bus,
// and one lockstep tick of the whole sim board (plant, drive, controller).
#include <benchmark/benchmark.h>

#include <cmath>

#include "firmware/app/board_config.hpp"
#include "firmware/app/control_task.hpp"
#include "firmware/core/damper_controller.hpp"
#include "host_sim/peers/in_process_board.hpp"
#include "firmware/platform/sim/memory_bus.hpp"
#include "firmware/platform/sim/memory_io.hpp"

namespace {

using namespace mrd;

void BM_EncodeDecodeDaqMotion(benchmark::State& state) {
  hal::CanFrame f;
  protocol::DaqMotion m{0.0123f, true, -150000.5f, true, 0};
  for (auto _ : state) {
    m.counter = static_cast<std::uint8_t>(m.counter + 1);
    protocol::encode(m, 3, f);
    protocol::DaqMotion out;
    benchmark::DoNotOptimize(protocol::decode(f, 3, out));
    benchmark::DoNotOptimize(out);
  }
}
BENCHMARK(BM_EncodeDecodeDaqMotion);

void BM_ControlTaskTick(benchmark::State& state) {
  sim::MemoryBus bus;
  auto& ctrl = bus.attach(1024);
  auto& peer = bus.attach(1024);
  ctrl.set_filters(app::control_task_filters({}));
  sim::MemoryIo io;
  fw::DamperController<num::Float32Policy> core;
  fw::ControllerConfig cfg;
  cfg.mode = control::ControlMode::kSemiActive;
  core.init(cfg);
  app::ControlTask<fw::DamperController<num::Float32Policy>> task(core, ctrl, io, {});
  task.reset();
  std::uint64_t k = 0;
  hal::CanFrame f;
  // Each iteration also encodes and queues the tick's three inbound frames
  // (what the DAQ and the drive would send), so it is an upper bound.
  for (auto _ : state) {
    const auto c = static_cast<std::uint8_t>(k);
    const float x = 0.02f * static_cast<float>(std::sin(1e-3 * static_cast<double>(k)));
    protocol::encode(protocol::DaqMotion{x, true, 1e6f * x, true, c}, 3, f);
    peer.send(f);
    protocol::encode(protocol::DaqAccel{0.5f, true, 0.1f, true, c}, 3, f);
    peer.send(f);
    protocol::encode(protocol::DriveStatus{2.0f, 2.0f, 0, protocol::DriveState::kFollowing, c}, 2, f);
    peer.send(f);
    while (peer.receive(f) == hal::CanResult::kOk) {
    }
    ++k;
    benchmark::DoNotOptimize(task.run_tick());
  }
}
BENCHMARK(BM_ControlTaskTick);

void BM_SimBoardLockstepTick(benchmark::State& state) {
  app::BoardConfig b;
  b.name = "bench";
  b.mode = control::ControlMode::kSemiActive;
  peers::InProcessBoard board(b, plant::PlantSpec{}, peers::drive_config(b));
  int k = 0;
  for (auto _ : state) board.step(0.5 * std::sin(2.0 * 3.14159 * 1e-3 * ++k));
  state.counters["sim_s_per_wall_s"] =
      benchmark::Counter(1e-3 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimBoardLockstepTick);

}  // namespace

BENCHMARK_MAIN();
