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

/// One tick's sample.
struct MixingTaskInput {
  std::uint64_t tick = 0;         ///< control ticks since boot
  double rtc_s = 0.0;             ///< wall clock, s
  bool rtc_valid = true;
  double damper_disp_m = 0.0;     ///< damper stroke, m
  bool disp_valid = true;
  double ground_accel_m_s2 = 0.0;
  bool ground_accel_valid = true;
  double base_accel_m_s2 = 0.0;
  bool base_accel_valid = true;
  bool actuator_ready = true;     ///< the actuator answers and reports no fault
  bool actuator_busy = false;     ///< the actuator is stroking: its motion counts as mixing
};

class MixingTask {
 public:
  /// Initialises both blocks; false when either refuses its configuration.
  bool init(const MixingTaskConfig& config) noexcept;

  /// Restores the estimator's state from `store` (I/O: before the loop).
  fw::IdleBootReport boot(hal::StateStore& store, std::uint64_t tick, double rtc_s, bool rtc_valid) noexcept;
  /// Starts from a known equivalent idle time, without a store.
  void boot_with(double equivalent_idle_s, std::uint64_t tick, double rtc_s) noexcept;

  /// One tick; O(1), no heap, no I/O.
  const fw::MixingSchedulerOutput& step(const MixingTaskInput& in) noexcept;

  /// The estimator's state should be saved (see fw::IdleEstimator::save_due).
  bool save_due() const noexcept { return estimator_.save_due(); }
  /// Saves through `store` (I/O: outside the control tick).
  fw::SaveOutcome save(hal::StateStore& store) noexcept { return estimator_.save(store); }

  const fw::MixingSchedulerOutput& output() const noexcept { return scheduler_.output(); }
  const fw::IdleEstimator& estimator() const noexcept { return estimator_; }
  const fw::MixingScheduler& scheduler() const noexcept { return scheduler_; }

 private:
  fw::IdleEstimator estimator_{};
  fw::MixingScheduler scheduler_{};
  std::uint32_t confirmed_id_ = 0;  ///< the last request credited as confirmed
};

}  // namespace mrd::app
