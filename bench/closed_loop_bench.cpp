// Closed-loop speed at 1 kHz on one core, in simulated seconds per wall
// second ("x_real_time").
//  - BM_Plant: the plant alone (6-DOF structure, exact ZOH, damper with idle
//    effects, coil dynamics) under a constant 2.5 A command; target ≥ 10 000.
//  - BM_ClosedLoop/<mode>: the same plant with the firmware control core
//    (float build) in the loop, as `mrd sim` and `mrd sweep` run it.
//  - BM_Batch<Mode>/<runs>: <runs> such closed loops stepped together in
//    SIMD lanes (host_sim/batch), equal to BM_ClosedLoop's run by run; the
//    runs differ in scaling and idle time. x_real_time counts the simulated
//    seconds of all runs, on one core. Issue 13's goal for the passive
//    modes: ≥ 100 000 (its floor ≈ 90 000).
//  - BM_BatchIsa/<isa>: passive-on, 64 runs, with each lane kernel this CPU
//    runs (0 generic, 1 x86-64-v3, 2 x86-64-v4).
#include <benchmark/benchmark.h>

#include <vector>

#include "host_sim/batch/batch_run.hpp"
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

void run_batch(benchmark::State& state, mrd::control::ControlMode mode, std::size_t runs, mrd::batch::LaneIsa isa) {
  if (!mrd::batch::lane_isa_available(isa)) {
    state.SkipWithError("this CPU lacks the instruction set");
    return;
  }
  std::vector<mrd::batch::BatchRun> batch(runs);
  for (std::size_t i = 0; i < runs; ++i) {
    batch[i].ground_accel_m_s2 = motion().accel_m_s2;
    batch[i].ground_scale = 0.5 + 0.05 * static_cast<double>(i % 31);
    batch[i].idle_time_s = mrd::units::years_to_s(0.25 * static_cast<double>(i % 11));
    batch[i].mode = mode;
  }
  mrd::batch::BatchOptions options;
  options.isa = isa;
  const mrd::plant::PlantSpec spec;
  double simulated_s = 0.0;
  for (auto _ : state) {
    const auto s = mrd::batch::run_closed_loop_batch(spec, batch, options);
    for (const auto& r : s) simulated_s += r.duration_s;
    benchmark::DoNotOptimize(s.data());
  }
  const double steps = static_cast<double>(motion().accel_m_s2.size() * runs) * static_cast<double>(state.iterations());
  state.counters["x_real_time"] = benchmark::Counter(simulated_s, benchmark::Counter::kIsRate);
  state.counters["ns_per_step"] = benchmark::Counter(steps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  const mrd::batch::LaneIsa used = isa == mrd::batch::LaneIsa::kAuto ? mrd::batch::auto_lane_isa() : isa;
  state.SetLabel(std::string(mrd::control::mode_name(mode)) + ", " + mrd::batch::lane_isa_name(used) + ", " +
                 std::to_string(mrd::batch::lane_count(used)) + " lanes");
}

void BM_BatchPassiveOff(benchmark::State& state) {
  run_batch(state, mrd::control::ControlMode::kPassiveOff, static_cast<std::size_t>(state.range(0)),
            mrd::batch::LaneIsa::kAuto);
}
void BM_BatchPassiveOn(benchmark::State& state) {
  run_batch(state, mrd::control::ControlMode::kPassiveOn, static_cast<std::size_t>(state.range(0)),
            mrd::batch::LaneIsa::kAuto);
}
void BM_BatchSemiActive(benchmark::State& state) {
  run_batch(state, mrd::control::ControlMode::kSemiActive, static_cast<std::size_t>(state.range(0)),
            mrd::batch::LaneIsa::kAuto);
}
BENCHMARK(BM_BatchPassiveOff)->Arg(8)->Arg(64)->Arg(250)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BatchPassiveOn)->Arg(8)->Arg(64)->Arg(250)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BatchSemiActive)->Arg(8)->Arg(64)->Unit(benchmark::kMillisecond);

void BM_BatchIsa(benchmark::State& state) {
  const mrd::batch::LaneIsa isas[] = {mrd::batch::LaneIsa::kGeneric, mrd::batch::LaneIsa::kX86_64V3,
                                      mrd::batch::LaneIsa::kX86_64V4};
  run_batch(state, mrd::control::ControlMode::kPassiveOn, 64, isas[state.range(0)]);
}
BENCHMARK(BM_BatchIsa)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
