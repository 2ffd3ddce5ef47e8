// The control task allocates nothing per tick: global operator new is
// replaced to count, and 10 000 ticks with full traffic (sensor frames in,
// command and heartbeat out, line writes) must not call it; nor does the
// board runtime's tick with the mixing task and its state saves.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>

#include "firmware/app/control_task.hpp"
#include "firmware/app/runtime.hpp"
#include "firmware/core/damper_controller.hpp"
#include "firmware/platform/sim/memory_bus.hpp"
#include "firmware/platform/sim/manual_clock.hpp"
#include "firmware/platform/sim/memory_io.hpp"
#include "firmware/platform/sim/memory_state_store.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace mrd::app {
namespace {

/// One tick's inbound frames, as the DAQ (node 3) and the drive (node 2) send
/// them: a 20 mm, 1 rad/s sine stroke, the given ground and base
/// accelerations, and a following drive at 2 A.
void send_tick_inputs(hal::CanBus& peer, std::uint64_t k, float ground_m_s2, float base_m_s2) {
  const auto c = static_cast<std::uint8_t>(k);
  const float x = 0.02f * static_cast<float>(std::sin(1e-3 * static_cast<double>(k)));
  hal::CanFrame f;
  protocol::encode(protocol::DaqMotion{x, true, 1e6f * x, true, c}, 3, f);
  peer.send(f);
  protocol::encode(protocol::DaqAccel{ground_m_s2, true, base_m_s2, true, c}, 3, f);
  peer.send(f);
  protocol::encode(protocol::DriveStatus{2.0f, 2.0f, 0, protocol::DriveState::kFollowing, c}, 2, f);
  peer.send(f);
}

TEST(ControlTaskAllocations, NoneOverTenThousandTicks) {
  sim::MemoryBus bus;
  auto& ctrl = bus.attach(64);
  auto& peer = bus.attach(64);
  ctrl.set_filters(control_task_filters({}));
  sim::MemoryIo io;
  fw::DamperController<num::Float32Policy> core;
  fw::ControllerConfig cfg;
  cfg.mode = control::ControlMode::kSemiActive;
  ASSERT_EQ(core.init(cfg), fw::ConfigError::kNone);
  ControlTask<fw::DamperController<num::Float32Policy>> task(core, ctrl, io, ControlTaskConfig{});
  task.reset();
  task.request_mixing({protocol::MixingAction::kStart, 0.05f, 0.2f, 60.0f, 0});
  hal::CanFrame f;
  const long before = g_allocations.load();
  for (std::uint64_t k = 0; k < 10000; ++k) {
    send_tick_inputs(peer, k, 0.5f, 0.1f);
    task.run_tick();
    while (peer.receive(f) == hal::CanResult::kOk) {
    }
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(task.status().frames_accepted, 30000u);
}

TEST(BoardRuntimeAllocations, NoneOverTenThousandTicksWithTheMixingTask) {
  sim::MemoryBus bus;
  auto& ctrl = bus.attach(64);
  auto& peer = bus.attach(64);
  ctrl.set_filters(control_task_filters({}));
  sim::MemoryIo io;
  sim::ManualClock clock;
  sim::ManualWallClock rtc;
  rtc.set(1.7e9);
  sim::MemoryStateStore store;
  using Core = fw::DamperController<num::Float32Policy>;
  Core core;
  ASSERT_EQ(core.init(fw::default_controller_config(control::ControlMode::kSemiActive, 1e-3)), fw::ConfigError::kNone);
  MixingTask mixing;
  MixingTaskConfig mc;
  mc.estimator.save_interval_s = 1.0;  // a save every second
  ASSERT_TRUE(mixing.init(mc));
  mixing.boot_with(0.5 * mixing.estimator().model().max_settling_time_s(), 0, 1.7e9);
  RuntimePorts ports{clock, ctrl, io};
  ports.store = &store;
  ports.rtc = &rtc;
  BoardRuntime<Core> rt(core, ports, ControlTaskConfig{}, RuntimeConfig{});
  rt.attach_mixing(&mixing);
  hal::CanFrame f;
  const long before = g_allocations.load();
  for (std::uint64_t k = 0; k < 10000; ++k) {
    send_tick_inputs(peer, k, 0.01f, 0.01f);
    protocol::encode(protocol::MixingStatus{protocol::MixingState::kIdle, 0.0f, 0.0f, 0, static_cast<std::uint8_t>(k)}, 4, f);
    peer.send(f);
    rt.run_tick();
    rtc.advance_s(1e-3);
    while (peer.receive(f) == hal::CanResult::kOk) {
    }
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(rt.task().status().frames_accepted, 40000u);
  EXPECT_GE(store.saves(), 9u);
  EXPECT_GT(mixing.estimator().estimate().lifetime_volume_m3, 0.0);
}

}  // namespace
}  // namespace mrd::app
