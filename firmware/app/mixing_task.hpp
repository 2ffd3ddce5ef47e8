#pragma once
/// The idle-time estimator and the mixing scheduler composed into one step:
/// the estimator takes the tick's sample, the scheduler decides on the
/// estimator's forecast and volumes, and a confirmed cycle is credited back
/// to the estimator.
///
/// <pre>
///   step(in):  estimator.step(tick, rtc, stroke, mixing = actuator busy)
///              forecast      = estimator.predicted_capacity_fraction(scheduler.forecast_horizon_s())
///              volume_needed = estimator.volume_to_ceiling_m3(ceiling_gap_fraction)
///              measured      = estimator.estimate().lifetime_volume_m3
///              out = scheduler.step(tick, accelerations, actuator, forecast, volume_needed, measured)
///              out confirms a new request → estimator.note_mixing_confirmed()
/// </pre>
///
/// Pure: step() does no I/O, no heap allocation and throws nothing. The
/// state store is touched only by boot() and save(), which the runtime calls
/// outside the control tick. Used by the board runtime (firmware/app/runtime)
/// and by `mrd schedule` (host_sim/schedule/service_life).
///
/// One template, BasicMixingTask<Policy>, in the estimator's and the
/// scheduler's numeric builds: double (`MixingTask`, the reference), float
/// and fixed point. Inside a step the estimator is asked per tick
/// (predicted_capacity(forecast_horizon_ticks()), volume_to_ceiling(gap),
/// lifetime_volume()), so the float and fixed builds' step has no double.

#include <cstdint>

#include "firmware/core/idle_estimator.hpp"
#include "firmware/core/mixing_scheduler.hpp"
#include "mrd/hal/state_store.hpp"

namespace mrd::app {

struct MixingTaskConfig {
  fw::IdleEstimatorConfig estimator{};
  /// Its period_s and flow_area_m2 are replaced by the estimator's (the
  /// scheduler's volumes are the estimator's, Eq. 5.9).
  fw::MixingSchedulerConfig scheduler{};
};

/// One tick's sample. The wall clock is `rtc_s` (double seconds) in the
/// reference build and `rtc_ms` (milliseconds) in the float and fixed builds.
template <class Policy>
struct BasicMixingTaskInput : fw::IdleArith<Policy>::RtcInput {
  using Sample = typename fw::IdleArith<Policy>::Sample;
  std::uint64_t tick = 0;         ///< control ticks since boot
  bool rtc_valid = true;
  Sample damper_disp_m = 0;       ///< damper stroke, m
  bool disp_valid = true;
  Sample ground_accel_m_s2 = 0;
  bool ground_accel_valid = true;
  Sample base_accel_m_s2 = 0;
  bool base_accel_valid = true;
  bool actuator_ready = true;     ///< the actuator answers and reports no fault
  bool actuator_busy = false;     ///< the actuator is stroking: its motion counts as mixing
};

template <class Policy>
class BasicMixingTask {
 public:
  using PolicyType = Policy;
  using Estimator = fw::BasicIdleEstimator<Policy>;
  using Scheduler = fw::BasicMixingScheduler<Policy>;
  using Input = BasicMixingTaskInput<Policy>;
  using Output = fw::BasicMixingSchedulerOutput<Policy>;
  using Rtc = typename fw::IdleArith<Policy>::Rtc;

  /// Initialises both blocks; false when either refuses its configuration.
  bool init(const MixingTaskConfig& config) noexcept;

  /// Restores the estimator's state from `store` (I/O: before the loop).
  fw::IdleBootReport boot(hal::StateStore& store, std::uint64_t tick, Rtc rtc, bool rtc_valid) noexcept {
    return estimator_.boot(store, tick, rtc, rtc_valid);
  }
  /// Starts from a known equivalent idle time, without a store.
  void boot_with(double equivalent_idle_s, std::uint64_t tick, Rtc rtc) noexcept {
    estimator_.boot_with(equivalent_idle_s, tick, rtc);
  }

  /// One tick; O(1), no heap, no I/O.
  const Output& step(const Input& in) noexcept;

  /// The estimator's state should be saved (see fw::BasicIdleEstimator::save_due).
  bool save_due() const noexcept { return estimator_.save_due(); }
  /// Saves through `store` (I/O: outside the control tick).
  fw::SaveOutcome save(hal::StateStore& store) noexcept { return estimator_.save(store); }

  const Output& output() const noexcept { return scheduler_.output(); }
  const Estimator& estimator() const noexcept { return estimator_; }
  const Scheduler& scheduler() const noexcept { return scheduler_; }

 private:
  Estimator estimator_{};
  Scheduler scheduler_{};
  std::uint32_t confirmed_id_ = 0;  ///< the last request credited as confirmed
};

/// The reference build (double) that the board runtime and the simulator use.
using MixingTask = BasicMixingTask<fw::Float64Policy>;
using MixingTaskInput = BasicMixingTaskInput<fw::Float64Policy>;

extern template class BasicMixingTask<fw::Float64Policy>;
extern template class BasicMixingTask<num::Float32Policy>;
extern template class BasicMixingTask<num::Fixed32Policy>;

}  // namespace mrd::app
