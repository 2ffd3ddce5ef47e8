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

#include <cstdint>

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

/// A sinusoidal stroke x(t) = A·sin(2πf t) for `cycles` periods.
struct MixingPlan {
  double amplitude_m = 0.0;
  double frequency_hz = 0.0;
  std::uint32_t cycles = 0;
  double volume_m3 = 0.0;          ///< displaced volume it produces: cycles·4A·flow area, m³
  double duration_s = 0.0;         ///< cycles/f, s
  double peak_velocity_m_s = 0.0;  ///< 2πfA, m/s
  double peak_accel_m_s2 = 0.0;    ///< (2πf)²A, m/s²
};

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
/// IdleEstimator::predicted_capacity_fraction(forecast_horizon_s()),
/// volume_to_ceiling_m3(ceiling_gap_fraction) and estimate().lifetime_volume_m3.
struct MixingSchedulerInput {
  std::uint64_t tick = 0;
  double ground_accel_m_s2 = 0.0;
  bool ground_accel_valid = true;
  double base_accel_m_s2 = 0.0;
  bool base_accel_valid = true;
  bool actuator_ready = true;    ///< the actuator answers on the bus and reports no fault
  bool actuator_busy = false;    ///< the actuator reports it is stroking
  double forecast_capacity_fraction = 1.0;
  double volume_needed_m3 = 0.0;
  double measured_volume_m3 = 0.0;  ///< monotone counter of displaced volume, m³
};

struct MixingSchedulerOutput {
  SchedulerState state = SchedulerState::kIdle;
  bool request_active = false;  ///< the actuator shall run `plan` (level); false: stop, damper in control
  bool abort = false;           ///< the request was withdrawn this step (edge)
  bool maintenance_required = false;
  bool shaking = false;         ///< seismic trigger active this step
  MixingPlan plan{};
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
/// [min_cycles, max_cycles].
MixingPlan plan_mixing(const MixingSchedulerConfig& config, double volume_needed_m3) noexcept;

class MixingScheduler {
 public:
  /// Returns false for an unusable configuration (non-positive limits,
  /// threshold outside (0, 1), min_cycles > max_cycles, …).
  bool init(const MixingSchedulerConfig& config) noexcept;
  void reset() noexcept;
  /// One tick; O(1), no heap, no I/O.
  const MixingSchedulerOutput& step(const MixingSchedulerInput& in) noexcept;

  /// Forecast horizon the estimator should be asked for, s.
  double forecast_horizon_s() const noexcept {
    return c_.actuator_fitted ? c_.lead_time_s : c_.maintenance_lead_time_s;
  }
  const MixingSchedulerOutput& output() const noexcept { return out_; }
  const MixingCounters& counters() const noexcept { return counters_; }
  const MixingSchedulerConfig& config() const noexcept { return c_; }

 private:
  /// What the transitions of one step look at.
  struct Conditions {
    bool below = false;        ///< forecast under the threshold
    bool quiet = false;        ///< no shaking now, none for holdoff_s
    bool can_watch = false;    ///< an accelerometer is valid
    double measured_m3 = 0.0;  ///< volume measured since the request, m³
    double in_state_s = 0.0;   ///< time in the present state, s
  };

  /// One transition if its condition holds; true when the state changed.
  bool transition(const MixingSchedulerInput& in, double t_s) noexcept;
  void from_due(const MixingSchedulerInput& in, const Conditions& c, double t_s) noexcept;
  void from_requested(const MixingSchedulerInput& in, const Conditions& c, double t_s) noexcept;
  void from_running(const Conditions& c, double t_s) noexcept;
  void enter(SchedulerState next, double t_s) noexcept;
  void raise_maintenance(MixingEndReason why, double t_s) noexcept;
  void end_cycle(SchedulerState next, MixingEndReason why, double t_s) noexcept;

  MixingSchedulerConfig c_{};
  MixingSchedulerOutput out_{};
  MixingCounters counters_{};
  std::uint32_t ground_count_ = 0;
  std::uint32_t base_count_ = 0;
  bool shaking_ever_ = false;
  double last_shaking_s_ = 0.0;
  double state_since_s_ = 0.0;
  double volume_at_request_m3_ = 0.0;
  std::uint32_t failed_in_row_ = 0;
};

}  // namespace mrd::fw
