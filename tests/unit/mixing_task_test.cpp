// The mixing task: the estimator and the scheduler composed as the board
// runs them. A settled fluid asks for a cycle, the cycle's measured stroke
// confirms it and the estimator counts it once; without an actuator the
// request becomes maintenance.
#include "firmware/app/mixing_task.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mrd/units.hpp"

namespace mrd::app {
namespace {

constexpr double kRtc0_s = 1.7e9;

MixingTaskConfig config_at(double period_s) {
  MixingTaskConfig c;
  c.estimator.period_s = period_s;
  return c;
}

TEST(MixingTask, TheSchedulerRunsOnTheEstimatorsPeriodAndFlowArea) {
  MixingTaskConfig c = config_at(0.01);
  c.estimator.model.pr.flow_area_m2 = 0.02;
  c.scheduler.period_s = 1.0;
  c.scheduler.flow_area_m2 = 0.5;
  MixingTask t;
  ASSERT_TRUE(t.init(c));
  EXPECT_EQ(t.scheduler().config().period_s, 0.01);
  EXPECT_EQ(t.scheduler().config().flow_area_m2, 0.02);
}

TEST(MixingTask, RefusesAnUnusableConfiguration) {
  MixingTaskConfig c = config_at(0.01);
  c.scheduler.capacity_threshold = 1.5;
  MixingTask t;
  EXPECT_FALSE(t.init(c));
}

TEST(MixingTask, ASettledFluidIsMixedAndTheCycleCountedOnce) {
  MixingTask t;
  ASSERT_TRUE(t.init(config_at(0.01)));
  t.boot_with(t.estimator().model().max_settling_time_s(), 0, kRtc0_s);

  MixingTaskInput in;
  in.rtc_s = kRtc0_s;
  const fw::MixingSchedulerOutput first = t.step(in);
  const double settled_capacity = t.estimator().estimate().capacity_fraction;
  ASSERT_EQ(first.state, fw::SchedulerState::kRequested);
  ASSERT_TRUE(first.request_active);
  const fw::MixingPlan plan = first.plan;
  ASSERT_GT(plan.cycles, 0u);

  // The actuator strokes the plan, sampled at 100 Hz.
  const auto ticks = static_cast<std::uint64_t>(std::ceil(plan.duration_s / 0.01));
  std::uint64_t k = 1;
  for (; k <= ticks; ++k) {
    in.tick = k;
    in.rtc_s = kRtc0_s + 0.01 * static_cast<double>(k);
    in.actuator_busy = true;
    in.damper_disp_m = plan.amplitude_m * std::sin(2.0 * units::kPi * plan.frequency_hz * 0.01 * static_cast<double>(k));
    t.step(in);
  }
  ASSERT_EQ(t.output().state, fw::SchedulerState::kConfirmed);
  EXPECT_FALSE(t.output().request_active);
  EXPECT_TRUE(t.save_due());
  // Confirmed stays for confirm_hold_s: the cycle is still counted once.
  in.actuator_busy = false;
  for (std::uint64_t end = k + 1000; k < end; ++k) {
    in.tick = k;
    t.step(in);
  }
  EXPECT_EQ(t.estimator().estimate().mixing_cycles, 1u);
  EXPECT_GT(t.estimator().estimate().mixing_volume_m3, 0.9 * plan.volume_m3);
  EXPECT_GT(t.estimator().estimate().capacity_fraction, settled_capacity + 0.3);
}

TEST(MixingTask, WithoutAnActuatorASettledFluidNeedsMaintenance) {
  MixingTaskConfig c = config_at(0.01);
  c.scheduler.actuator_fitted = false;
  MixingTask t;
  ASSERT_TRUE(t.init(c));
  t.boot_with(t.estimator().model().max_settling_time_s(), 0, kRtc0_s);
  MixingTaskInput in;
  in.rtc_s = kRtc0_s;
  in.actuator_ready = false;
  const fw::MixingSchedulerOutput& o = t.step(in);
  EXPECT_EQ(o.state, fw::SchedulerState::kMaintenanceRequired);
  EXPECT_TRUE(o.maintenance_required);
  EXPECT_FALSE(o.request_active);
}

// The float and fixed-point builds of the task on the same settled fluid: the
// same request and number of cycles as the double build, each cycle the
// thesis stroke (±76.2 mm at 0.2 Hz: 4·0.0762·0.01062 m³ = 3.237 L, 5 s =
// 500 ticks at 100 Hz), confirmed from the stroke, counted once.
template <class P>
void settled_fluid_is_mixed_once() {
  using Sample = typename fw::IdleArith<P>::Sample;
  using A = fw::IdleArith<P>;
  BasicMixingTask<P> t;
  ASSERT_TRUE(t.init(config_at(0.01)));
  const std::int64_t rtc0_ms = 1700000000000;
  t.boot_with(t.estimator().model().max_settling_time_s(), 0, rtc0_ms);
  BasicMixingTaskInput<P> in;
  in.rtc_ms = rtc0_ms;
  const auto first = t.step(in);
  const double settled_capacity = static_cast<double>(t.estimator().estimate().capacity_fraction);
  ASSERT_EQ(first.state, fw::SchedulerState::kRequested) << P::kName;
  const auto plan = first.plan;
  MixingTask reference;
  ASSERT_TRUE(reference.init(config_at(0.01)));
  reference.boot_with(reference.estimator().model().max_settling_time_s(), 0, kRtc0_s);
  MixingTaskInput ref_in;
  ref_in.rtc_s = kRtc0_s;
  const std::uint32_t cycles = reference.step(ref_in).plan.cycles;
  EXPECT_EQ(plan.cycles, cycles) << P::kName;
  EXPECT_NEAR(static_cast<double>(plan.amplitude_m), 0.0762, 1e-7);
  EXPECT_NEAR(static_cast<double>(plan.frequency_hz), 0.2, 1e-7);
  EXPECT_NEAR(A::vol_to_double(plan.volume_m3), cycles * 4.0 * 0.0762 * 0.01062, 1e-9);
  EXPECT_EQ(plan.duration_ticks, 500u * cycles);

  std::uint64_t k = 1;
  for (; k <= plan.duration_ticks; ++k) {
    in.tick = k;
    in.rtc_ms = rtc0_ms + 10 * static_cast<std::int64_t>(k);
    in.actuator_busy = true;
    in.damper_disp_m = static_cast<Sample>(0.0762 * std::sin(2.0 * units::kPi * 0.2 * 0.01 * static_cast<double>(k)));
    ASSERT_NE(t.output().state, fw::SchedulerState::kAborted) << P::kName << " tick " << k;
    t.step(in);
  }
  ASSERT_EQ(t.output().state, fw::SchedulerState::kConfirmed) << P::kName;
  in.actuator_busy = false;
  for (std::uint64_t end = k + 1000; k < end; ++k) {
    in.tick = k;
    t.step(in);
  }
  EXPECT_EQ(t.estimator().estimate().mixing_cycles, 1u);
  EXPECT_GT(static_cast<double>(t.estimator().estimate().mixing_volume_m3), 0.9 * cycles * 4.0 * 0.0762 * 0.01062);
  EXPECT_GT(static_cast<double>(t.estimator().estimate().capacity_fraction), settled_capacity + 0.3);
}

TEST(MixingTask, FloatBuildMixesASettledFluidOnce) { settled_fluid_is_mixed_once<num::Float32Policy>(); }
TEST(MixingTask, FixedPointBuildMixesASettledFluidOnce) { settled_fluid_is_mixed_once<num::Fixed32Policy>(); }

}  // namespace
}  // namespace mrd::app
