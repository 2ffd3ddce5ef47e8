// Closed-loop speed at 1 kHz on one core, in simulated seconds per wall
// second ("x_real_time").
//  - BM_Plant: the plant alone (6-DOF structure, exact ZOH, damper with idle
//    effects, coil dynamics) under a constant 2.5 A command; target ≥ 10 000.
//  - BM_ClosedLoop/<mode>: the same plant with the firmware control core
//    (float build) in the loop, as `mrd sim` and `mrd sweep` run it.
#include <benchmark/benchmark.h>

#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/motions.hpp"
#include "mrd/units.hpp"

namespace {

const mrd::run::StudyMotion& motion() {
  // A synthetic 40 s motion: the benchmark needs no shared data.
  static const mrd::run::StudyMotion m = mrd::run::synthetic_study_motion(1, mrd::run::kThesisPga_g, 1e-3, 40.0);
  return m;
}

void run(benchmark::State& state, mrd::run::Controller& controller) {
  mrd::plant::PlantSpec spec;
  spec.idle_time_s = mrd::units::years_to_s(0.5);
  double simulated_s = 0.0;
  for (auto _ : state) {
    const auto s = mrd::run::run_closed_loop(spec, motion().accel_m_s2, controller);
    benchmark::DoNotOptimize(s.peak_base_displacement_m);
    simulated_s += s.duration_s;
  }
  state.counters["x_real_time"] = benchmark::Counter(simulated_s, benchmark::Counter::kIsRate);
  state.counters["ns_per_step"] = benchmark::Counter(
      static_cast<double>(motion().accel_m_s2.size()) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Plant(benchmark::State& state) {
  mrd::run::ConstantCurrentController c(mrd::fw::kPassiveOnCurrent_a);
  run(state, c);
}
BENCHMARK(BM_Plant)->Unit(benchmark::kMillisecond);

void BM_ClosedLoop(benchmark::State& state) {
  const auto mode = static_cast<mrd::control::ControlMode>(state.range(0));
  auto controller = mrd::run::make_controller(mode, 1e-3);
  run(state, *controller);
  state.SetLabel(mrd::control::mode_name(mode));
}
BENCHMARK(BM_ClosedLoop)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
