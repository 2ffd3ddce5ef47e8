#pragma once
/// Many closed-loop earthquake runs stepped together: the runs share the
/// plant (building, damper, step) and differ in ground motion, its scaling,
/// idle time and control mode. They are laid side by side in SIMD lanes
/// (8 with AVX-512, 4 with AVX2, 2 otherwise), so every load of the
/// building's matrices serves all lanes; a lane whose run ends takes the
/// next run, so runs of any lengths mix.
///
/// Each result equals run::run_closed_loop() of the same run: the lanes do
/// the scalar plant's IEEE operations in the same order (exp() included:
/// see lane_kernel.hpp), and the semi-active lanes call the same firmware
/// control core, one core per lane.

#include <cstddef>
#include <span>
#include <vector>

#include "host_sim/plant/plant.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/controller.hpp"
#include "mrd/control/io.hpp"

namespace mrd::batch {

/// One run of a batch.
struct BatchRun {
  /// Ground acceleration at the plant's step, m/s²; the caller keeps it alive.
  std::span<const double> ground_accel_m_s2;
  /// a_g[n] = ground_scale · ground_accel_m_s2[n] (the same product a scaled copy holds).
  double ground_scale = 1.0;
  double idle_time_s = 0.0;  ///< idle time before the run, s (sets SQ, Eq. 5.4–5.5)
  control::ControlMode mode = control::ControlMode::kPassiveOff;
  /// Optional time series, filled as run::run_closed_loop() fills it. Slower:
  /// a batch with a record steps tick by tick.
  run::ClosedLoopRecord* record = nullptr;
};

/// Which kernel steps the lanes.
enum class LaneIsa {
  kAuto,      ///< the widest this CPU runs
  kGeneric,   ///< any CPU: 2 lanes a register (the thesis shape: four registers, 8 lanes), glibc's exp() per lane
  kX86_64V3,  ///< AVX2 + FMA: 4 lanes a register (the thesis shape: two registers, 8 lanes)
  kX86_64V4,  ///< AVX-512: 8 lanes
};

struct BatchOptions {
  run::NumericKind numeric = run::NumericKind::kFloat;  ///< the firmware core's build
  LaneIsa isa = LaneIsa::kAuto;
  /// false: no run reports peak_story_drift_m (it is NaN), and passive runs
  /// of the thesis's shape skip the six 12-term sums a tick the drifts take
  /// (about a quarter of their run-step).
  bool story_drift = true;
};

/// Runs `runs` on `plant` (a thesis plant on any building; its idle_time_s
/// is ignored: each run has its own). Result i equals
/// <pre>
///   run::run_closed_loop(plant with idle_time_s = runs[i].idle_time_s,
///                        ground_scale · ground_accel_m_s2,
///                        *run::make_controller(runs[i].mode, plant.step_s, options.numeric),
///                        runs[i].record)
/// </pre>
/// (peak_story_drift_m aside when options.story_drift is false).
/// One thread; independent calls may run on separate threads. Throws
/// std::invalid_argument for a hardware plant, a bad step, an invalid
/// building, or an ISA that is not available
/// (lane_isa_available()); io::UsageError when the control core rejects
/// the step.
std::vector<plant::PlantSummary> run_closed_loop_batch(const plant::PlantSpec& plant, std::span<const BatchRun> runs,
                                                       const BatchOptions& options = {});

/// True when the lanes step `damper`'s force in their registers: the bingham
/// laws (Eq. 4.4's transition and the tanh one) with any shape a calibration
/// gives them (physics::LawShape) but a series compliance. The other laws
/// (Bouc–Wen, Spencer) and a law behind a series compliance (a solve per
/// step) are stepped in the lanes by the scalar damper itself
/// (physics::MrDamper), one per damper and lane, the building still in the lanes.
bool lanes_vectorize(const physics::MrDamperParams& damper) noexcept;

/// "auto" | "generic" | "x86-64-v3" | "x86-64-v4".
const char* lane_isa_name(LaneIsa isa) noexcept;

/// True when this CPU (and the OS) has every instruction `isa`'s kernel may use.
bool lane_isa_cpu_runs(LaneIsa isa);

/// True when this CPU runs `isa`'s kernel and, for the FMA kernels, its
/// exp() agrees bit for bit with the C library's on a set of test values.
bool lane_isa_available(LaneIsa isa);

/// What kAuto picks on this CPU.
LaneIsa auto_lane_isa();

/// Lanes the kernel of `isa` steps at once: on a building of the thesis's
/// shape, or (`any_building`) on any other building's lanes.
int lane_count(LaneIsa isa, bool any_building = false);

}  // namespace mrd::batch
