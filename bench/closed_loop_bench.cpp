// Closed-loop speed: plant (6-DOF structure, exact ZOH) + damper with idle
// effects + coil dynamics at 1 kHz, one core. Reports simulated seconds per
// wall second ("x_real_time"); target ≥ 10 000.
#include <benchmark/benchmark.h>

#include "run/closed_loop.hpp"
#include "run/controller.hpp"
#include "run/motions.hpp"

namespace {

const mrd::run::StudyMotion& motion() {
  // A synthetic 40 s motion: the benchmark needs no shared data.
  static const mrd::run::StudyMotion m = mrd::run::synthetic_study_motion(1, mrd::run::kThesisPga_g, 1e-3, 40.0);
  return m;
}

void BM_ClosedLoop(benchmark::State& state) {
  const auto mode = static_cast<mrd::control::ControlMode>(state.range(0));
  mrd::run::ClosedLoopSpec spec;
  spec.idle_years = 0.5;
  auto controller = mrd::run::make_controller(mode, spec.step_s);
  double simulated_s = 0.0;
  for (auto _ : state) {
    const auto s = mrd::run::run_closed_loop(spec, motion().accel_m_s2, *controller);
    benchmark::DoNotOptimize(s.peak_base_displacement_m);
    simulated_s += s.duration_s;
  }
  state.counters["x_real_time"] = benchmark::Counter(simulated_s, benchmark::Counter::kIsRate);
  state.counters["ns_per_step"] = benchmark::Counter(
      static_cast<double>(motion().accel_m_s2.size()) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.SetLabel(mrd::control::mode_name(mode));
}
BENCHMARK(BM_ClosedLoop)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
