// Cost of the idle-time estimator and mixing scheduler per control step.
// Run: build/<release>/firmware/mrd_bench_idle
#include <benchmark/benchmark.h>

#include <cmath>

#include "firmware/core/idle_estimator.hpp"
#include "firmware/core/mixing_scheduler.hpp"

namespace {

using namespace mrd::fw;

// Damper moving (an open episode: Eq. 5.9 with one exp per step).
void BM_IdleEstimatorStepMoving(benchmark::State& state) {
  IdleEstimator est;
  est.init({});
  est.boot_with(86400.0, 0, 1.7e9);
  IdleEstimatorInput in;
  std::uint64_t tick = 0;
  for (auto _ : state) {
    in.tick = ++tick;
    in.rtc_s = 1.7e9 + static_cast<double>(tick) * 1e-3;
    in.damper_disp_m = 0.02 * std::sin(static_cast<double>(tick) * 5e-3);
    est.step(in);
    benchmark::DoNotOptimize(est.estimate().participant_ratio);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_IdleEstimatorStepMoving);

// Damper still (settled phase: Eq. 5.6 with one exp per step).
void BM_IdleEstimatorStepIdle(benchmark::State& state) {
  IdleEstimator est;
  est.init({});
  est.boot_with(86400.0, 0, 1.7e9);
  IdleEstimatorInput in;
  std::uint64_t tick = 0;
  for (auto _ : state) {
    in.tick = ++tick;
    in.rtc_s = 1.7e9 + static_cast<double>(tick) * 1e-3;
    est.step(in);
    benchmark::DoNotOptimize(est.estimate().participant_ratio);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_IdleEstimatorStepIdle);

// Estimator forecast + needed volume + scheduler step: what the runtime adds
// on top of the estimator's step each tick.
void BM_SchedulerStepWithForecast(benchmark::State& state) {
  IdleEstimator est;
  est.init({});
  est.boot_with(86400.0, 0, 1.7e9);
  MixingScheduler sch;
  sch.init({});
  MixingSchedulerInput in;
  std::uint64_t tick = 0;
  for (auto _ : state) {
    in.tick = ++tick;
    in.forecast_capacity_fraction = est.predicted_capacity_fraction(sch.forecast_horizon_s());
    in.volume_needed_m3 = est.volume_to_ceiling_m3(0.01);
    in.measured_volume_m3 = est.estimate().lifetime_volume_m3;
    benchmark::DoNotOptimize(sch.step(in).state);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SchedulerStepWithForecast);

}  // namespace

BENCHMARK_MAIN();
