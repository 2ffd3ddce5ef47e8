#pragma once
/// The damper controller: the pure control core that runs unchanged in unit
/// tests, in the host simulator and on the board.
///
/// `init(config)` once, `reset()` at the start of an episode, then
/// `step(input) -> output` once per period T (1 kHz default); `status()`
/// reports counters. Time is the integer number of `step()` calls since
/// `reset()`. No heap, no exceptions, no I/O, no logging. One source builds
/// in float (`num::Float32Policy`) and in fixed point (`num::Fixed32Policy`).
///
/// Units: inputs and outputs are SI. Inside, strokes count in units of
/// s_D m, forces in units of s_F N and currents in units of s_I A, the
/// powers of two `init()` chooses from the configuration (core_scales,
/// numeric_formats.hpp), so that a 1 kN damper with a 25 mm stroke and a
/// 2 MN damper, a 0.5 A and a 10 A coil all fit the fixed-point formats
/// with the thesis's relative resolution: the measured stroke, force and
/// coil current are multiplied by 1/s_D, 1/s_F and 1/s_I as they enter
/// (exact in float), every configured length, force, gain and current is
/// divided by its scale at `init()`, and the command leaves multiplied by
/// s_I (F_d by s_F). The float build runs at s_D = s_F = s_I = 1.
///
/// One tick, in order:
///  1. input guard (input_guard.hpp): each signal's fault; the sample is
///     stale when its tick is not newer than the last sample's, lies in the
///     future, or is older than `max_input_age_ticks`;
///  2. filters, in every mode so that switching modes is bumpless, on a
///     usable stroke x (valid and not stale; otherwise they are frozen):
///     causal RILD F_d = H(z) x (rild_filter.hpp, Eq. 6.1), clamped to
///     ±`desired_force_limit_n`; velocity estimate (velocity_estimator.hpp).
///     The first usable sample primes both at rest;
///  3. output by mode:
///     - passive-off: 0 A;  passive-on: I_nom (2.5 A);
///     - semi-active: ODBDCO (odbdco.hpp) from F_d, F_m, i_m and the velocity,
///       when stroke, force and coil current are all usable, under the coil
///       I²t ceiling (coil_i2t.hpp). The law's state and the I²t estimate
///       run in every mode on usable input, so switching modes is bumpless
///       and the coil's heating in passive-on is counted.
/// Safe outputs (SAFE-1 … SAFE-4), whatever the mode; SAFE-1 comes first in 3.:
///     - SAFE-1 drive fault line asserted: 0 A, drive disabled, and it stays
///       disabled `drive_reenable_delay_ticks` after the line clears;
///     - SAFE-2 semi-active, stroke / force / coil current unusable (flagged,
///       NaN, infinite, out of range, stuck) or the sample stale: the last
///       command is repeated for up to `fault_hold_ticks` consecutive bad
///       ticks (a lost frame should not jolt the coil), then
///       `fallback_current_a` (2.5 A: the damper becomes the passive-on
///       damper, which bounds the base displacement); F_d is reported as 0.
///       The first good tick returns to ODBDCO;
///     - SAFE-3 passive modes ignore the sensors: bad input is only counted;
///     - SAFE-4 accelerations are not used by the law: a bad ground or base
///       acceleration is counted, and a bad ground acceleration also
///       suspends the stuck-sensor test;
///     - before a successful `init()`: 0 A, drive disabled.
/// Every fault is counted in `status()`.

#include <array>
#include <cstdint>

#include "firmware/core/coil_i2t.hpp"
#include "firmware/core/controller_config.hpp"
#include "firmware/core/input_guard.hpp"
#include "firmware/core/numeric_formats.hpp"
#include "firmware/core/odbdco.hpp"
#include "firmware/core/rild_filter.hpp"
#include "firmware/core/velocity_estimator.hpp"
#include "mrd/control/io.hpp"

namespace mrd::fw {

/// The control core's own counters and state (what `status()` returns); not
/// the CAN heartbeat protocol::ControllerStatus, which the control task sends.
struct DamperControllerStatus {
  std::uint64_t ticks = 0;  ///< step() calls since reset()
  control::ControlMode mode = control::ControlMode::kPassiveOff;
  bool initialized = false;
  ConfigError config_error = ConfigError::kNone;  ///< the last init()'s verdict
  /// Ticks on which a signal had a fault, by kind (index InputFault; kNone unused).
  std::array<std::uint32_t, kInputFaultKinds> invalid_by_kind{};
  /// Ticks on which a signal had a fault, by signal (index InputSignal).
  std::array<std::uint32_t, kInputSignals> invalid_by_signal{};
  std::uint32_t stale_inputs = 0;           ///< ticks whose sample was stale
  std::uint32_t drive_fault_ticks = 0;      ///< ticks with the drive's fault line asserted
  std::uint32_t drive_disabled_ticks = 0;   ///< ticks the drive was disabled (fault + re-enable delay)
  std::uint32_t held_ticks = 0;             ///< SAFE-2: last command repeated
  std::uint32_t fallback_ticks = 0;         ///< SAFE-2: fallback current
  std::uint32_t desired_force_clamps = 0;   ///< ticks with |F_d| clamped to the limit (saturation)
  std::array<std::uint32_t, kOdbdcoBranches> branch_ticks{};  ///< ODBDCO branch taken (index OdbdcoBranch)
  InputGuard::Faults last_faults{};         ///< the latest tick's fault per signal
  bool last_input_stale = false;

  constexpr std::uint32_t invalid(InputFault k) const noexcept { return invalid_by_kind[static_cast<int>(k)]; }
  constexpr std::uint32_t invalid(InputSignal s) const noexcept { return invalid_by_signal[static_cast<int>(s)]; }
  constexpr std::uint32_t branch(OdbdcoBranch b) const noexcept { return branch_ticks[static_cast<int>(b)]; }
};

template <class Policy>
class DamperController {
 public:
  using Disp = typename Formats<Policy>::Disp;
  using Velocity = typename Formats<Policy>::Velocity;
  using Force = typename Formats<Policy>::Force;
  using Current = typename Formats<Policy>::Current;

  /// Validates and applies `config`, then reset(). On an error the
  /// controller is left uninitialized (0 A, drive disabled).
  ConfigError init(const ControllerConfig& config) noexcept;

  /// Starts an episode: filters at rest, counters and tick count at zero.
  void reset() noexcept;

  /// Switches the control mode; the filters keep running.
  bool set_mode(control::ControlMode mode) noexcept;

  control::ControllerOutput step(const control::ControllerInput& in) noexcept;

  const DamperControllerStatus& status() const noexcept { return status_; }
  /// The coil I²t estimate (its ceiling and heating); currents in units of
  /// current_scale_a(), squares in its square.
  const CoilI2t<Policy>& coil_i2t() const noexcept { return i2t_; }
  /// The ODBDCO law's state (direction, target); currents in units of current_scale_a().
  const Odbdco<Policy>& law() const noexcept { return law_; }
  /// s_D: one unit of the core's strokes, m (the last successful init()'s; 1 before).
  double disp_scale_m() const noexcept { return scales_.disp_m(); }
  /// s_F: one unit of the core's forces, N (the last successful init()'s; 1 before).
  double force_scale_n() const noexcept { return scales_.force_n(); }
  /// s_I: one unit of the core's currents, A (the last successful init()'s; 1 before).
  double current_scale_a() const noexcept { return scales_.current_a(); }
  const ControllerConfig& config() const noexcept { return config_; }
  bool initialized() const noexcept { return initialized_; }

 private:
  ControllerConfig config_{};
  bool initialized_ = false;
  control::ControlMode mode_ = control::ControlMode::kPassiveOff;

  RildFilter<Policy> rild_{};
  VelocityEstimator<Policy> velocity_{};
  InputGuard guard_{};
  OdbdcoParams<Policy> odbdco_{};
  Odbdco<Policy> law_{};
  CoilI2t<Policy> i2t_{};
  Force desired_limit_n_{};
  Current nominal_a_{};
  Current fallback_a_{};
  CoreScales scales_{};
  float disp_in_ = 1.0f;      ///< 1/s_D, exact (a power of two)
  float force_in_ = 1.0f;     ///< 1/s_F
  float force_out_ = 1.0f;    ///< s_F
  float current_in_ = 1.0f;   ///< 1/s_I
  float current_out_ = 1.0f;  ///< s_I

  std::uint64_t ticks_ = 0;
  bool have_sample_ = false;
  std::uint64_t last_sample_tick_ = 0;
  bool primed_ = false;
  bool disp_gap_ = false;
  Force desired_n_{};
  Current last_command_a_{};
  std::uint32_t bad_run_ = 0;
  std::uint32_t drive_hold_ = 0;
  DamperControllerStatus status_{};

  // The parts of step(), always inlined: step() stays one function, as
  // measured (bench/) and cross-checked (tests/cross/core_cross_check.sh).
  /// Counts the guard's faults and judges the sample's age; true when stale.
  [[gnu::always_inline]] bool step_guard(const control::ControllerInput& in, std::uint64_t now,
                                         const InputGuard::Faults& faults) noexcept;
  /// RILD and the velocity estimate on a usable stroke.
  [[gnu::always_inline]] void step_filters(const control::ControllerInput& in, bool disp_ok) noexcept;
  /// The mode's command (SAFE-2 in semi-active on bad input); sets F_d in `out`.
  [[gnu::always_inline]] Current step_law(const control::ControllerInput& in, const InputGuard::Faults& faults,
                                          bool disp_ok, control::ControllerOutput& out) noexcept;

  static constexpr void bump(std::uint32_t& c) noexcept {
    if (c != 0xffffffffu) ++c;
  }
};

template <class Policy>
ConfigError DamperController<Policy>::init(const ControllerConfig& config) noexcept {
  const ConfigError e = validate_config<Policy>(config);
  if (e != ConfigError::kNone) {
    initialized_ = false;
    reset();
    status_.config_error = e;
    return e;
  }
  config_ = config;
  mode_ = config.mode;
  // Unit scales: powers of two, so every division below and every float
  // product with disp_in_ … current_out_ is exact.
  scales_ = core_scales<Policy>(config);
  const double sd = scales_.disp_m();
  const double sf = scales_.force_n();
  const double si = scales_.current_a();
  disp_in_ = static_cast<float>(1.0 / sd);
  force_in_ = static_cast<float>(1.0 / sf);
  force_out_ = static_cast<float>(sf);
  current_in_ = static_cast<float>(1.0 / si);
  current_out_ = static_cast<float>(si);
  rild_.init(config.stiffness_n_m * sd / sf, config.loss_factor, config.filter_freq_rad_s, config.period_s);
  const double sv = scales_.velocity_m();
  velocity_.init(config.velocity_cutoff_hz, config.period_s, static_cast<float>(sd / sv));
  InputGuardLimits limits;
  limits.disp_limit_m = static_cast<float>(config.disp_limit_m);
  limits.force_limit_n = static_cast<float>(config.force_limit_n);
  limits.accel_limit_m_s2 = static_cast<float>(config.accel_limit_m_s2);
  limits.coil_current_limit_a = static_cast<float>(config.coil_current_limit_a);
  limits.stuck_ticks = config.stuck_ticks;
  limits.shaking_threshold_m_s2 = static_cast<float>(config.shaking_threshold_m_s2);
  guard_.init(limits);
  odbdco_.overdrive_a = num::from_double<Current>(config.overdrive_current_a / si);
  odbdco_.backdrive_a = num::from_double<Current>(config.backdrive_current_a / si);
  odbdco_.band_a = num::from_double<Current>(config.current_band_a / si);
  odbdco_.deadband_n = num::from_double<Force>(config.force_deadband_n / sf);
  odbdco_.velocity_on = num::from_double<Velocity>(config.velocity_on_m_s * config.period_s / sv);
  odbdco_.velocity_off = num::from_double<Velocity>(config.velocity_off_m_s * config.period_s / sv);
  odbdco_.dwell_ticks = static_cast<std::uint32_t>(config.target_dwell_s / config.period_s + 0.5);
  odbdco_.rest_ticks = static_cast<std::uint32_t>(config.rest_release_s / config.period_s + 0.5);
  i2t_.init(config.coil_thermal_time_constant_s, config.period_s, config.rated_current_a / si,
            config.coil_derate_fraction);
  desired_limit_n_ = num::from_double<Force>(config.desired_force_limit_n / sf);
  nominal_a_ = num::from_double<Current>(config.nominal_current_a / si);
  fallback_a_ = num::from_double<Current>(config.fallback_current_a / si);
  initialized_ = true;
  status_.config_error = ConfigError::kNone;
  reset();
  return ConfigError::kNone;
}

template <class Policy>
void DamperController<Policy>::reset() noexcept {
  rild_.reset();
  velocity_.reset();
  law_.reset();
  i2t_.reset();
  guard_.reset();
  ticks_ = 0;
  have_sample_ = false;
  last_sample_tick_ = 0;
  primed_ = false;
  disp_gap_ = false;
  desired_n_ = Force{};
  last_command_a_ = fallback_a_;
  bad_run_ = 0;
  drive_hold_ = 0;
  const ConfigError err = status_.config_error;
  status_ = DamperControllerStatus{};
  status_.config_error = err;
  status_.initialized = initialized_;
  status_.mode = mode_;
}

template <class Policy>
bool DamperController<Policy>::set_mode(control::ControlMode mode) noexcept {
  if (mode != control::ControlMode::kPassiveOff && mode != control::ControlMode::kPassiveOn &&
      mode != control::ControlMode::kSemiActive) {
    return false;
  }
  mode_ = mode;
  status_.mode = mode;
  bad_run_ = 0;
  return true;
}

template <class Policy>
control::ControllerOutput DamperController<Policy>::step(const control::ControllerInput& in) noexcept {
  control::ControllerOutput out;
  const std::uint64_t now = ticks_;
  ++ticks_;
  status_.ticks = ticks_;
  if (!initialized_) {
    out.current_command_a = 0.0f;
    out.drive_enable = false;
    return out;
  }

  // 1. Input guard and staleness.
  const InputGuard::Faults faults = guard_.check(in);
  const bool stale = step_guard(in, now, faults);

  // 2. Filters on a usable stroke.
  const bool disp_ok = !stale && faults[InputGuard::idx(InputSignal::kDisp)] == InputFault::kNone;
  step_filters(in, disp_ok);

  // 3. Output: SAFE-1 (the drive's fault line) first, then the mode's law.
  if (in.flags.drive_fault) {
    bump(status_.drive_fault_ticks);
    drive_hold_ = config_.drive_reenable_delay_ticks;
  } else if (drive_hold_ > 0) {
    --drive_hold_;
  } else {
    const Current command = step_law(in, faults, disp_ok, out);
    last_command_a_ = command;
    out.current_command_a = num::to_float(command) * current_out_;
    out.drive_enable = true;
    return out;
  }
  bump(status_.drive_disabled_ticks);
  last_command_a_ = Current{};
  out.current_command_a = 0.0f;
  out.drive_enable = false;
  return out;
}

template <class Policy>
inline bool DamperController<Policy>::step_guard(const control::ControllerInput& in, std::uint64_t now,
                                          const InputGuard::Faults& faults) noexcept {
  for (int s = 0; s < kInputSignals; ++s) {
    if (faults[s] != InputFault::kNone) {
      bump(status_.invalid_by_kind[static_cast<int>(faults[s])]);
      bump(status_.invalid_by_signal[s]);
    }
  }
  status_.last_faults = faults;
  const bool stale = in.tick > now || now - in.tick > config_.max_input_age_ticks ||
                     (have_sample_ && in.tick <= last_sample_tick_);
  status_.last_input_stale = stale;
  if (stale) {
    bump(status_.stale_inputs);
  } else {
    have_sample_ = true;
    last_sample_tick_ = in.tick;
  }
  return stale;
}

template <class Policy>
inline void DamperController<Policy>::step_filters(const control::ControllerInput& in, bool disp_ok) noexcept {
  if (disp_ok) {
    const float x_units = in.damper_disp_m * disp_in_;
    const Disp x = num::from_float<Disp>(x_units);
    if (!primed_) {
      rild_.prime(x);
      velocity_.prime(x_units);
      primed_ = true;
    } else if (disp_gap_) {
      velocity_.resync(x_units);
    }
    const Force fd = rild_.step(x);
    const Force clamped = num::clamp(fd, -desired_limit_n_, desired_limit_n_);
    if (!(clamped == fd)) bump(status_.desired_force_clamps);
    desired_n_ = clamped;
    (void)velocity_.step(x_units);
  }
  disp_gap_ = !disp_ok;
}

template <class Policy>
inline typename DamperController<Policy>::Current DamperController<Policy>::step_law(const control::ControllerInput& in,
                                                                             const InputGuard::Faults& faults,
                                                                             bool disp_ok,
                                                                             control::ControllerOutput& out) noexcept {
  const bool coil_ok = faults[InputGuard::idx(InputSignal::kCoilCurrent)] == InputFault::kNone;
  const bool usable = disp_ok && coil_ok && faults[InputGuard::idx(InputSignal::kForce)] == InputFault::kNone;
  const Current coil_a = num::from_float<Current>(in.coil_current_a * current_in_);
  if (coil_ok) i2t_.step(coil_a);
  OdbdcoDecision<Policy> d;
  if (usable) {
    d = law_.step(odbdco_, desired_n_, num::from_float<Force>(in.damper_force_n * force_in_), coil_a,
                  velocity_.per_tick(), i2t_.ceiling_a());
  }
  if (mode_ == control::ControlMode::kPassiveOn) return nominal_a_;
  if (mode_ != control::ControlMode::kSemiActive) return Current{};  // passive-off
  if (usable) {
    bad_run_ = 0;
    bump(status_.branch_ticks[static_cast<int>(d.branch)]);
    out.desired_force_n = num::to_float(desired_n_) * force_out_;
    return d.command_a;
  }
  // SAFE-2
  bump(bad_run_);
  if (bad_run_ <= config_.fault_hold_ticks) {
    bump(status_.held_ticks);
    return last_command_a_;
  }
  bump(status_.fallback_ticks);
  return fallback_a_;
}

extern template class DamperController<num::Float32Policy>;
extern template class DamperController<num::Fixed32Policy>;
extern template class DamperController<Float64Policy>;

}  // namespace mrd::fw
