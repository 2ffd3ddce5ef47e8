#pragma once
/// Mixing scheduler: decides when a preventive mixing cycle is due, plans it
/// within the actuator's limits, requests it, confirms it from the measured
/// displaced volume, aborts it when shaking starts, and raises a maintenance
/// request where no actuator is fitted (or it keeps failing).
/// Builds freestanding: no heap, no exceptions, no I/O.
///
/// States (one step may pass through several when their conditions hold):
/// <pre>
///   idle ──forecast < threshold, no shaking for holdoff──▶ due
///   due ──no actuator──▶ maintenance-required
///   due ──actuator ready, accelerometers valid, no shaking──▶ requested   (request_active = true)
///   due ──forecast ≥ threshold again──▶ idle
///   requested ──actuator busy, or ≥ start_fraction of the planned volume measured──▶ running
///   requested/running ──seismic trigger or both accelerometers invalid──▶ aborted   (request withdrawn at once)
///   requested ──no start within start_timeout_s──▶ aborted (a failed attempt)
///   running ──≥ confirm_fraction of the planned volume measured──▶ confirmed
///   running ──not confirmed within duration·run_timeout_factor + run_margin_s──▶ aborted (a failed attempt)
///   confirmed ──after confirm_hold_s──▶ idle
///   aborted ──max_attempts failed in a row──▶ maintenance-required
///   aborted ──no shaking for holdoff_s──▶ idle
///   maintenance-required ──forecast ≥ threshold (someone mixed it)──▶ idle
/// </pre>
/// The forecast is the estimator's capacity after lead_time_s without motion
/// (maintenance_lead_time_s when no actuator is fitted: a visit takes longer).
/// confirm_hold_s must exceed the estimator's quiet_close_s: a second cycle
/// run inside the same episode could not pass that episode's ceiling b_PR.
///
/// Seismic trigger: |a_g| (or |a_base|) above its threshold for
/// seismic_samples consecutive valid samples. It must run at the control
/// rate (or at the rate the samples count was chosen for); the rest of the
/// logic only compares times and may run decimated.
///
/// Numeric builds: one template, BasicMixingScheduler<Policy>, built in
/// double (Float64Policy, the reference: `MixingScheduler`), float and fixed
/// point with the formats of idle_estimator_formats.hpp. Time is 64-bit
/// ticks; the configured durations become ticks at init(). The plan's
/// per-cycle volume, frequency and peaks are designed once at init(); a step
/// only picks the number of cycles (an integer division in the float and
/// fixed builds).

#include <cstdint>

#include "firmware/core/idle_estimator_formats.hpp"

namespace mrd::fw {

/// The scheduler's state (the diagram above); not the actuator's reported
/// protocol::MixingState.
enum class SchedulerState : std::uint8_t {
  kIdle = 0,
  kDue,
  kRequested,
  kRunning,
  kConfirmed,
  kAborted,
  kMaintenanceRequired,
};

constexpr const char* scheduler_state_name(SchedulerState s) noexcept {
  switch (s) {
    case SchedulerState::kIdle: return "idle";
    case SchedulerState::kDue: return "due";
    case SchedulerState::kRequested: return "requested";
    case SchedulerState::kRunning: return "running";
    case SchedulerState::kConfirmed: return "confirmed";
    case SchedulerState::kAborted: return "aborted";
    case SchedulerState::kMaintenanceRequired: return "maintenance-required";
  }
  return "unknown";
}

/// Why the last cycle ended or why maintenance is requested.
enum class MixingEndReason : std::uint8_t {
  kNone = 0,
  kConfirmed,
  kSeismic,            ///< shaking started: control handed back to the damper
  kSensorFault,        ///< both accelerometers invalid: shaking could not be seen
  kStartTimeout,       ///< the actuator did not start
  kIncomplete,         ///< the measured volume fell short of the plan
  kNoActuator,         ///< none fitted: maintenance
  kAttemptsExhausted,  ///< max_attempts failed cycles in a row: maintenance
};

constexpr const char* mixing_end_reason_name(MixingEndReason r) noexcept {
  switch (r) {
    case MixingEndReason::kNone: return "none";
    case MixingEndReason::kConfirmed: return "confirmed";
    case MixingEndReason::kSeismic: return "seismic";
    case MixingEndReason::kSensorFault: return "sensor-fault";
    case MixingEndReason::kStartTimeout: return "start-timeout";
    case MixingEndReason::kIncomplete: return "incomplete";
    case MixingEndReason::kNoActuator: return "no-actuator";
    case MixingEndReason::kAttemptsExhausted: return "attempts-exhausted";
  }
  return "unknown";
}

/// A sinusoidal stroke x(t) = A·sin(2πf t) for `cycles` periods, in the
/// boundary numbers of one build (double or float; the volume in the build's
/// Volume format).
template <class Policy>
struct BasicMixingPlan {
  using Sample = typename IdleArith<Policy>::Sample;
  Sample amplitude_m = 0;
  Sample frequency_hz = 0;
  std::uint32_t cycles = 0;
  typename IdleArith<Policy>::Volume volume_m3{};  ///< displaced volume it produces: cycles·4A·flow area, m³
  Sample duration_s = 0;           ///< cycles/f, s
  std::uint64_t duration_ticks = 0;  ///< the same in control ticks (rounded)
  Sample peak_velocity_m_s = 0;    ///< 2πfA, m/s
  Sample peak_accel_m_s2 = 0;      ///< (2πf)²A, m/s²
};
using MixingPlan = BasicMixingPlan<Float64Policy>;

struct MixingSchedulerConfig {
  double period_s = 1.0e-3;              ///< duration of one tick, s
  double capacity_threshold = 0.8;       ///< mix before the capacity falls below this fraction
  /// Forecast horizon with an actuator, s: covers the time between two
  /// evaluations, the actuator's start and the cycle itself.
  double lead_time_s = 2.0 * 3600.0;
  double maintenance_lead_time_s = 7.0 * 86400.0;  ///< forecast horizon without one, s
  bool actuator_fitted = true;
  // Actuator limits and the plan. Thesis §6.6: ±76.2 mm at 0.2 Hz.
  double max_amplitude_m = 0.0762;       ///< stroke limit of the mixing actuator (amplitude), m
  double max_velocity_m_s = 0.1;         ///< velocity limit, m/s
  double preferred_frequency_hz = 0.2;   ///< used unless the velocity limit asks for less, Hz
  double flow_area_m2 = 0.01062;         ///< must equal the estimator's (Eq. 5.9), m²
  double ceiling_gap_fraction = 0.01;    ///< plan for PR within this fraction·b_PR of b_PR
  std::uint32_t min_cycles = 1;
  std::uint32_t max_cycles = 20;
  // Seismic trigger.
  double ground_trigger_m_s2 = 0.05;
  double base_trigger_m_s2 = 0.05;
  std::uint32_t seismic_samples = 3;     ///< consecutive samples above a threshold
  /// The mixing actuator moves the base (not a decoupled damper): the base
  /// threshold then rises by the plan's peak acceleration while mixing.
  bool mixing_moves_base = false;
  // Confirmation, timeouts, retries.
  double start_fraction = 0.05;          ///< measured/planned volume that proves the actuator started
  double confirm_fraction = 0.9;         ///< measured/planned volume that confirms the cycle
  double start_timeout_s = 60.0;
  double run_timeout_factor = 1.5;
  double run_margin_s = 30.0;
  double confirm_hold_s = 120.0;         ///< > the estimator's quiet_close_s
  double holdoff_s = 600.0;              ///< quiet time after shaking or a failure before a new try, s
  std::uint32_t max_attempts = 3;
};

/// One tick's inputs. The estimator's values come from
/// BasicIdleEstimator::predicted_capacity(forecast_horizon_ticks()),
/// volume_to_ceiling(ceiling_gap()) and lifetime_volume() (in the reference
/// build also as predicted_capacity_fraction(forecast_horizon_s()),
/// volume_to_ceiling_m3(ceiling_gap_fraction), estimate().lifetime_volume_m3).
template <class Policy>
struct BasicMixingSchedulerInput {
  using A = IdleArith<Policy>;
  std::uint64_t tick = 0;
  typename A::Sample ground_accel_m_s2 = 0;
  bool ground_accel_valid = true;
  typename A::Sample base_accel_m_s2 = 0;
  bool base_accel_valid = true;
  bool actuator_ready = true;    ///< the actuator answers on the bus and reports no fault
  bool actuator_busy = false;    ///< the actuator reports it is stroking
  typename A::Ratio forecast_capacity_fraction = A::one();
  typename A::Volume volume_needed_m3{};
  typename A::Volume measured_volume_m3{};  ///< monotone counter of displaced volume, m³
};

template <class Policy>
struct BasicMixingSchedulerOutput {
  SchedulerState state = SchedulerState::kIdle;
  bool request_active = false;  ///< the actuator shall run `plan` (level); false: stop, damper in control
  bool abort = false;           ///< the request was withdrawn this step (edge)
  bool maintenance_required = false;
  bool shaking = false;         ///< seismic trigger active this step
  BasicMixingPlan<Policy> plan{};
  std::uint32_t request_id = 0;  ///< increments with each request
  MixingEndReason reason = MixingEndReason::kNone;
};

struct MixingCounters {
  std::uint32_t requested = 0;
  std::uint32_t confirmed = 0;
  std::uint32_t aborted_seismic = 0;
  std::uint32_t failed = 0;              ///< start timeouts, incomplete cycles, sensor faults
  std::uint32_t maintenance_raised = 0;
};

/// The cycle that displaces at least `volume_needed_m3` at the largest
/// amplitude allowed, at the preferred frequency unless the velocity limit
/// asks for less: f = min(f_pref, v_max/(2πA)), n = ⌈V/(4A·area)⌉ within
/// [min_cycles, max_cycles]. In double (design time, host side).
MixingPlan plan_mixing(const MixingSchedulerConfig& config, double volume_needed_m3) noexcept;

template <class Policy>
class BasicMixingScheduler {
 public:
  using A = IdleArith<Policy>;
  using Sample = typename A::Sample;
  using Ratio = typename A::Ratio;
  using Volume = typename A::Volume;
  using Accel = typename A::Accel;
  using Input = BasicMixingSchedulerInput<Policy>;
  using Output = BasicMixingSchedulerOutput<Policy>;
  using Plan = BasicMixingPlan<Policy>;

  /// Returns false for an unusable configuration (non-positive limits,
  /// threshold outside (0, 1), min_cycles > max_cycles, a constant outside
  /// its format, …).
  bool init(const MixingSchedulerConfig& config) noexcept;
  void reset() noexcept;
  /// One tick; O(1), no heap, no I/O.
  const Output& step(const Input& in) noexcept;

  /// The plan for `volume_needed` (what step() requests).
  Plan plan_for(Volume volume_needed) const noexcept;

  /// Forecast horizon the estimator should be asked for, s (host side) and ticks.
  double forecast_horizon_s() const noexcept {
    return c_.actuator_fitted ? c_.lead_time_s : c_.maintenance_lead_time_s;
  }
  std::uint64_t forecast_horizon_ticks() const noexcept { return horizon_; }
  /// ceiling_gap_fraction in this build's numbers.
  Ratio ceiling_gap() const noexcept { return gap_; }
  const Output& output() const noexcept { return out_; }
  const MixingCounters& counters() const noexcept { return counters_; }
  const MixingSchedulerConfig& config() const noexcept { return c_; }

 private:
  /// What the transitions of one step look at.
  struct Conditions {
    bool below = false;          ///< forecast under the threshold
    bool quiet = false;          ///< no shaking now, none for holdoff_s
    bool can_watch = false;      ///< an accelerometer is valid
    Volume measured{};           ///< volume measured since the request
    std::uint64_t in_state = 0;  ///< ticks in the present state
  };

  bool transition(const Input& in, std::uint64_t t) noexcept;
  void from_due(const Input& in, const Conditions& c, std::uint64_t t) noexcept;
  void from_requested(const Input& in, const Conditions& c, std::uint64_t t) noexcept;
  void from_running(const Conditions& c, std::uint64_t t) noexcept;
  void enter(SchedulerState next, std::uint64_t t) noexcept;
  void raise_maintenance(MixingEndReason why, std::uint64_t t) noexcept;
  void end_cycle(SchedulerState next, MixingEndReason why, std::uint64_t t) noexcept;

  MixingSchedulerConfig c_{};
  Output out_{};
  MixingCounters counters_{};
  // The configuration in this build's numbers and in ticks.
  Ratio threshold_{};
  Ratio gap_{};
  Ratio start_fraction_{};
  Ratio confirm_fraction_{};
  Accel ground_trigger_{};
  Accel base_trigger_{};
  Accel plan_peak_accel_{};
  Plan unit_plan_{};             ///< one cycle: amplitude, frequency, peaks, volume per cycle
  std::uint64_t cycle_q16_ = 0;  ///< ticks per cycle, ·2^16
  std::uint64_t run_limit_q16_ = 0;  ///< ticks per cycle × run_timeout_factor, ·2^16
  std::uint64_t horizon_ = 0;
  std::uint64_t start_timeout_ = 0;
  std::uint64_t run_margin_ = 0;
  std::uint64_t confirm_hold_ = 0;
  std::uint64_t holdoff_ = 0;
  // State.
  std::uint32_t ground_count_ = 0;
  std::uint32_t base_count_ = 0;
  bool shaking_ever_ = false;
  std::uint64_t last_shaking_ = 0;
  std::uint64_t state_since_ = 0;
  Volume volume_at_request_{};
  Volume start_volume_{};    ///< start_fraction of the plan
  Volume confirm_volume_{};  ///< confirm_fraction of the plan
  std::uint64_t run_limit_ = 0;  ///< ticks a running cycle may take
  std::uint32_t failed_in_row_ = 0;
};

/// The reference build (double) and its types; the float and fixed builds
/// are instantiated in mixing_scheduler_float.cpp and mixing_scheduler_fixed.cpp.
using MixingScheduler = BasicMixingScheduler<Float64Policy>;
using MixingSchedulerInput = BasicMixingSchedulerInput<Float64Policy>;
using MixingSchedulerOutput = BasicMixingSchedulerOutput<Float64Policy>;

extern template class BasicMixingScheduler<Float64Policy>;
extern template class BasicMixingScheduler<num::Float32Policy>;
extern template class BasicMixingScheduler<num::Fixed32Policy>;

}  // namespace mrd::fw
