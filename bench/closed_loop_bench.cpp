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
//  - BM_BatchNoDrift/<mode>: 64 runs without the story drifts' peak.
//  - BM_BatchIsa/<isa>/<mode>: 64 runs with each lane kernel this CPU runs
//    (0 generic, 1 x86-64-v3, 2 x86-64-v4), passive-on (1) and semi-active (2).
//  - BM_LeadRubber20Dof: a 20-DOF building on 40 lead-rubber bearings
//    (lead_rubber_20dof() below), semi-active with the firmware control core,
//    one run at a time, as `mrd sim --building` runs it.
//  - BM_BatchLeadRubber20Dof/<mode>: the same building, 64 runs in SIMD
//    lanes (any building's lanes, host_sim/batch/lane_kernel_any.hpp), equal
//    to the scalar runs bit for bit; 0 passive-off, 1 passive-on, 2 semi-active.
//  - BM_Modes/<building>/<mode>/<path>: the table of every mode, scalar and
//    batch, on both buildings, in one run (--benchmark_filter=BM_Modes):
//    building 0 the thesis's, 1 the 20-DOF lead-rubber one; mode 0
//    passive-off, 1 passive-on, 2 semi-active; path 0 one run at a time
//    (run::run_closed_loop, the float core), 1 the batch's lanes (64 runs).
#include <benchmark/benchmark.h>

#include <numbers>
#include <stdexcept>
#include <string>
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

/// A 20-DOF base-isolated building on lead-rubber bearings (a design
/// example for the benchmark, not a real building):
/// - masses: the base slab 3.0e5 kg, 19 floors of 2.0e5 kg; the whole mass
///   M = 3.0e5 + 19 x 2.0e5 = 4.1e6 kg, the weight W = M g = 4.1e6 x 9.80665
///   = 40.21e6 N;
/// - stories: element i (1..19) from 6.0e8 N/m at the first story to 2.5e8 N/m
///   at the roof, linearly: k_i = 6.0e8 - (i - 1) x 3.5e8 / 18; element 0 has
///   no linear spring (the bearings carry the isolation layer);
/// - 40 lead-rubber bearings, Q = 0.05 W / 40 = 0.05 x 40.21e6 / 40 = 50.3 kN
///   each (a total of 5 % of the weight); k_p from a post-yield period of
///   3 s, the building rigid on the bearings: 40 k_p = M (2 pi / 3 s)^2
///   = 4.1e6 x 4.386 = 17.98e6 N/m, k_p = 449.6 kN/m; D_y = 0.015 m, n = 2;
/// - damping: 2 % Rayleigh on modes 1 and 2 of (M, K), K holding the bearings'
///   post-yield stiffness;
/// - one MR damper in parallel with element 0.
/// With the superstructure flexible the first period is 3.32 s (then 0.846 s,
/// 0.448 s: `mrd modal` on the same building written as a file).
/// Its largest tangent stiffness 40 Q / D_y = 134 MN/m on the base mass gives
/// ω_0 = 21 rad/s, so the plant's sub-step is the 0.2 ms cap: 5 per 1 ms tick.
mrd::structure::BuildingParams lead_rubber_20dof() {
  constexpr int kDofs = 20;
  constexpr double kBaseMass_kg = 3.0e5, kFloorMass_kg = 2.0e5;
  constexpr double kBottomStory_n_m = 6.0e8, kTopStory_n_m = 2.5e8;
  constexpr int kBearings = 40;
  constexpr double kPostYieldPeriod_s = 3.0;
  mrd::structure::BuildingParams b;
  b.name = "lead-rubber-20dof";
  b.mass_kg.assign(kDofs, kFloorMass_kg);
  b.mass_kg[0] = kBaseMass_kg;
  b.story_stiffness_n_m.assign(kDofs, 0.0);
  for (int i = 1; i < kDofs; ++i) {
    b.story_stiffness_n_m[i] =
        kBottomStory_n_m - (kBottomStory_n_m - kTopStory_n_m) * static_cast<double>(i - 1) / (kDofs - 2);
  }
  b.story_damping_n_s_m.assign(kDofs, 0.0);
  b.rayleigh = mrd::structure::RayleighDamping{0.02, 1, 2};
  double mass_kg = 0.0;
  for (double m : b.mass_kg) mass_kg += m;
  const double weight_n = mass_kg * mrd::units::kStandardGravity_m_s2;
  const double omega_rad_s = 2.0 * std::numbers::pi / kPostYieldPeriod_s;
  mrd::structure::LeadRubberBearing lrb;
  lrb.count = kBearings;
  lrb.characteristic_strength_n = 0.05 * weight_n / kBearings;
  lrb.post_yield_stiffness_n_m = mass_kg * omega_rad_s * omega_rad_s / kBearings;
  lrb.yield_displacement_m = 0.015;
  lrb.exponent = 2.0;
  b.isolators = {lrb};
  b.dampers = {mrd::structure::DamperPlacement{0, 1}};
  return b;
}

void run(benchmark::State& state, mrd::run::Controller& controller,
         const mrd::structure::BuildingParams& building = {}) {
  mrd::plant::PlantSpec spec;
  spec.idle_time_s = mrd::units::years_to_s(0.5);
  spec.building = building;
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

void BM_LeadRubber20Dof(benchmark::State& state) {
  const auto building = lead_rubber_20dof();
  auto controller = mrd::run::make_controller(mrd::control::ControlMode::kSemiActive, 1e-3);
  run(state, *controller, building);
  state.SetLabel("semi-active, scalar, 20 DOFs, 40 lead-rubber bearings, " +
                 std::to_string(mrd::plant::structural_substeps(building, 1e-3)) + " sub-steps per tick");
}
BENCHMARK(BM_LeadRubber20Dof)->Unit(benchmark::kMillisecond);

void run_batch(benchmark::State& state, mrd::control::ControlMode mode, std::size_t runs, mrd::batch::LaneIsa isa,
               const mrd::structure::BuildingParams& building = {}, bool story_drift = true) {
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
  options.story_drift = story_drift;
  mrd::plant::PlantSpec spec;
  spec.building = building;
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

/// 64 runs without the story drifts' peak (BatchOptions::story_drift = false).
void BM_BatchNoDrift(benchmark::State& state) {
  run_batch(state, static_cast<mrd::control::ControlMode>(state.range(0)), 64, mrd::batch::LaneIsa::kAuto, {}, false);
}
BENCHMARK(BM_BatchNoDrift)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_BatchIsa(benchmark::State& state) {
  const mrd::batch::LaneIsa isas[] = {mrd::batch::LaneIsa::kGeneric, mrd::batch::LaneIsa::kX86_64V3,
                                      mrd::batch::LaneIsa::kX86_64V4};
  run_batch(state, static_cast<mrd::control::ControlMode>(state.range(1)), 64, isas[state.range(0)]);
}
BENCHMARK(BM_BatchIsa)->ArgsProduct({{0, 1, 2}, {1, 2}})->ArgNames({"isa", "mode"})->Unit(benchmark::kMillisecond);

/// The 20-DOF lead-rubber building in SIMD lanes, 64 runs.
void BM_BatchLeadRubber20Dof(benchmark::State& state) {
  static const auto building = lead_rubber_20dof();
  run_batch(state, static_cast<mrd::control::ControlMode>(state.range(0)), 64, mrd::batch::LaneIsa::kAuto, building);
  state.SetLabel(std::string(mrd::control::mode_name(static_cast<mrd::control::ControlMode>(state.range(0)))) +
                 ", 20 DOFs, 40 lead-rubber bearings, " + mrd::batch::lane_isa_name(mrd::batch::auto_lane_isa()));
}
BENCHMARK(BM_BatchLeadRubber20Dof)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

/// Every mode, scalar and batch, on the thesis building and the 20-DOF one.
void BM_Modes(benchmark::State& state) {
  static const auto lead_rubber = lead_rubber_20dof();
  const bool twenty_dofs = state.range(0) == 1;
  const auto mode = static_cast<mrd::control::ControlMode>(state.range(1));
  const bool batch = state.range(2) == 1;
  const mrd::structure::BuildingParams building = twenty_dofs ? lead_rubber : mrd::structure::BuildingParams{};
  std::string what;
  if (batch) {
    run_batch(state, mode, 64, mrd::batch::LaneIsa::kAuto, building);
    const mrd::batch::LaneIsa isa = mrd::batch::auto_lane_isa();
    what = std::string("batch, 64 runs, ") + mrd::batch::lane_isa_name(isa) + ", " +
           std::to_string(mrd::batch::lane_count(isa, twenty_dofs)) + " lanes";
  } else {
    auto controller = mrd::run::make_controller(mode, 1e-3);
    run(state, *controller, building);
    what = "scalar";
  }
  state.SetLabel(std::string(twenty_dofs ? "20-DOF lead-rubber" : "thesis") + ", " + mrd::control::mode_name(mode) +
                 ", " + what);
}
BENCHMARK(BM_Modes)
    ->ArgsProduct({{0, 1}, {0, 1, 2}, {0, 1}})
    ->ArgNames({"building", "mode", "batch"})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
