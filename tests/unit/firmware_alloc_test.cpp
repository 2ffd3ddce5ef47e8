// No heap in the control step: this program replaces the global operator
// new/delete with counting versions and runs 100 000 steps of each numeric
// build, with clean and with faulty input, in every mode.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>

#include "firmware/core/damper_controller.hpp"

namespace {
std::atomic<long> g_allocations{0};

// Out of line so that the compiler does not pair an inlined free() with
// operator new (-Wmismatched-new-delete).
[[gnu::noinline]] void* counted_alloc(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void release(void* p) noexcept { std::free(p); }
}  // namespace

void* operator new(std::size_t n) { return counted_alloc(n); }
void* operator new[](std::size_t n) { return counted_alloc(n); }
void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }

namespace mrd::fw {
namespace {

TEST(FirmwareAlloc, TheCounterSeesAnAllocation) {
  // Without this the test below could pass with a counter that never counts.
  const long before = g_allocations.load();
  int* volatile p = new int(7);
  EXPECT_EQ(g_allocations.load(), before + 1);
  delete p;
}

template <class Policy>
long allocations_over_steps(control::ControlMode mode) {
  static DamperController<Policy> c;  // constructed before counting
  if (c.init(ControllerConfig{}) != ConfigError::kNone) return -1;
  (void)c.set_mode(mode);
  const long before = g_allocations.load();
  float sink = 0.0f;
  for (std::uint64_t k = 0; k < 100000; ++k) {
    const double t = static_cast<double>(k) * 1e-3;
    control::ControllerInput in;
    in.tick = k;
    in.damper_disp_m = static_cast<float>(0.05 * std::sin(1.6 * t));
    in.damper_force_n = static_cast<float>(8e4 * std::cos(1.6 * t));
    in.ground_accel_m_s2 = static_cast<float>(std::sin(9.0 * t));
    in.coil_current_a = static_cast<float>(2.0 + std::sin(20.0 * t));
    // Every 97th tick something is wrong: NaN, stale, drive fault.
    if (k % 97 == 0) in.damper_disp_m = std::numeric_limits<float>::quiet_NaN();
    if (k % 193 == 0) in.tick = k - 5;
    if (k % 1009 == 0) in.flags.drive_fault = true;
    const control::ControllerOutput out = c.step(in);
    sink += out.current_command_a + out.desired_force_n * 1e-6f;
  }
  const long count = g_allocations.load() - before;
  EXPECT_TRUE(std::isfinite(sink));
  EXPECT_EQ(c.status().ticks, 100000u);
  return count;
}

TEST(FirmwareAlloc, NoAllocationIn100000StepsOfEitherBuildInAnyMode) {
  for (auto mode : {control::ControlMode::kSemiActive, control::ControlMode::kPassiveOn,
                    control::ControlMode::kPassiveOff}) {
    EXPECT_EQ(allocations_over_steps<num::Float32Policy>(mode), 0) << control::mode_name(mode);
    EXPECT_EQ(allocations_over_steps<num::Fixed32Policy>(mode), 0) << control::mode_name(mode);
  }
}

}  // namespace
}  // namespace mrd::fw
