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
#include <type_traits>

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
/// For N lanes (LanePolicy<N>) every counter counts per lane.
template <class Set>
struct BasicDamperControllerStatus {
  using Count = typename Set::Count;
  using Faults = typename BasicInputGuard<Set>::Faults;
  typename Set::Tick ticks{};  ///< step() calls since reset()
  control::ControlMode mode = control::ControlMode::kPassiveOff;
  bool initialized = false;
  ConfigError config_error = ConfigError::kNone;  ///< the last init()'s verdict
  /// Ticks on which a signal had a fault, by kind (index InputFault; kNone unused).
  std::array<Count, kInputFaultKinds> invalid_by_kind{};
  /// Ticks on which a signal had a fault, by signal (index InputSignal).
  std::array<Count, kInputSignals> invalid_by_signal{};
  Count stale_inputs{};           ///< ticks whose sample was stale
  Count drive_fault_ticks{};      ///< ticks with the drive's fault line asserted
  Count drive_disabled_ticks{};   ///< ticks the drive was disabled (fault + re-enable delay)
  Count held_ticks{};             ///< SAFE-2: last command repeated
  Count fallback_ticks{};         ///< SAFE-2: fallback current
  Count desired_force_clamps{};   ///< ticks with |F_d| clamped to the limit (saturation)
  std::array<Count, kOdbdcoBranches> branch_ticks{};  ///< ODBDCO branch taken (index OdbdcoBranch)
  Faults last_faults{};           ///< the latest tick's fault per signal
  typename Set::Mask last_input_stale{};

  constexpr Count invalid(InputFault k) const noexcept { return invalid_by_kind[static_cast<int>(k)]; }
  constexpr Count invalid(InputSignal s) const noexcept { return invalid_by_signal[static_cast<int>(s)]; }
  constexpr Count branch(OdbdcoBranch b) const noexcept { return branch_ticks[static_cast<int>(b)]; }

  /// Counters and the latest tick's state back to zero in the lanes of `m`.
  constexpr void clear(typename Set::Mask m) noexcept {
    const auto zero = [m](auto& v) { v = num::select(m, std::remove_reference_t<decltype(v)>{}, v); };
    zero(ticks);
    for (Count& c : invalid_by_kind) zero(c);
    for (Count& c : invalid_by_signal) zero(c);
    for (Count* c : {&stale_inputs, &drive_fault_ticks, &drive_disabled_ticks, &held_ticks, &fallback_ticks,
                     &desired_force_clamps}) {
      zero(*c);
    }
    for (Count& c : branch_ticks) zero(c);
    for (auto& f : last_faults) zero(f);
    zero(last_input_stale);
  }
};

using DamperControllerStatus = BasicDamperControllerStatus<LaneSet<1>>;

template <class Policy>
class DamperController {
 public:
  using Disp = typename Formats<Policy>::Disp;
  using Velocity = typename Formats<Policy>::Velocity;
  using Force = typename Formats<Policy>::Force;
  using Current = typename Formats<Policy>::Current;
  static constexpr int kLanes = LaneTypes<Policy>::kLanes;
  using Mask = typename LaneTypes<Policy>::Mask;
  using Count = typename LaneTypes<Policy>::Count;
  using Tick = typename LaneTypes<Policy>::Tick;
  using Sample = typename LaneTypes<Policy>::Sample;
  using Set = typename LaneTypes<Policy>::Self;
  using Guard = BasicInputGuard<Set>;
  using Faults = typename Guard::Faults;
  using Status = BasicDamperControllerStatus<Set>;
  using Input = typename ControlIo<Set>::Input;
  using Output = typename ControlIo<Set>::Output;

  /// Validates and applies `config`, then reset(). On an error the
  /// controller is left uninitialized (0 A, drive disabled).
  ConfigError init(const ControllerConfig& config) noexcept;

  /// Starts an episode: filters at rest, counters and tick count at zero
  /// (lanes: in the lanes of `m`, the others run on).
  void reset(Mask m = num::all_set<Mask>()) noexcept;

  /// Switches the control mode; the filters keep running.
  bool set_mode(control::ControlMode mode) noexcept;

  Output step(const Input& in) noexcept;

  const Status& status() const noexcept { return status_; }
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
  Guard guard_{};
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
  Tick max_input_age_ticks_{};
  Count drive_reenable_delay_ticks_{};

  Tick ticks_{};
  Mask have_sample_{};
  Tick last_sample_tick_{};
  Mask primed_{};
  Mask disp_gap_{};
  Force desired_n_{};
  Current last_command_a_{};
  Count bad_run_{};
  Count drive_hold_{};
  bool faults_clear_ = false;  ///< status_.last_faults holds no fault in any lane
  Status status_{};

  // The parts of step(), always inlined: step() stays one function, as
  // measured (bench/) and cross-checked (tests/cross/core_cross_check.sh).
  // Each is written with masks: `m ? a : b` per lane, and a block of state
  // changes runs when some lane needs it (`num::any`).
  /// The tick after the input guard; kClean: no signal of any lane has a
  /// fault (`faults` all kNone), which the compiler then knows.
  template <bool kClean>
  [[gnu::always_inline]] Output step_checked(const Input& in, Tick now, const Faults& faults) noexcept;
  /// Counts the guard's faults and judges the sample's age; true when stale.
  template <bool kClean>
  [[gnu::always_inline]] Mask step_guard(const Input& in, Tick now, const Faults& faults) noexcept;
  /// RILD and the velocity estimate on a usable stroke.
  [[gnu::always_inline]] void step_filters(const Input& in, Mask disp_ok) noexcept;
  /// The mode's command (SAFE-2 in semi-active on bad input) in the lanes of
  /// `live` (the drive enabled); sets F_d in `out`.
  template <bool kClean>
  [[gnu::always_inline]] Current step_law(const Input& in, const Faults& faults, Mask disp_ok, Mask live,
                                          Output& out) noexcept;
  /// True where `signal` has no fault.
  template <bool kClean>
  static constexpr Mask ok(const Faults& faults, InputSignal signal) noexcept {
    if constexpr (kClean) {
      return num::all_set<Mask>();
    } else {
      return faults[Guard::idx(signal)] == Guard::fault(InputFault::kNone);
    }
  }

  static constexpr void bump(std::uint32_t& c) noexcept {
    if (c != 0xffffffffu) ++c;
  }
  /// counts[index] + 1 where `m` is set (index per lane for lanes).
  template <std::size_t K, class Index>
  static constexpr void bump_at(std::array<Count, K>& counts, Index index, Mask m) noexcept {
    if constexpr (kLanes == 1) {
      if (m) bump(counts[static_cast<int>(index)]);
    } else {
      for (std::size_t k = 0; k < K; ++k) num::bump_where(counts[k], m && index == static_cast<int>(k));
    }
  }
};

template <class Policy>
ConfigError DamperController<Policy>::init(const ControllerConfig& config) noexcept {
  const ConfigError e = validate_config<LaneScalarPolicy<Policy>>(config);
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
  scales_ = core_scales<LaneScalarPolicy<Policy>>(config);
  const double sd = scales_.disp_m();
  const double sf = scales_.force_n();
  const double si = scales_.current_a();
  disp_in_ = static_cast<float>(1.0 / sd);
  force_in_ = static_cast<float>(1.0 / sf);
  force_out_ = static_cast<float>(sf);
  current_in_ = static_cast<float>(1.0 / si);
  current_out_ = static_cast<float>(si);
  max_input_age_ticks_ = num::splat<Tick>(config.max_input_age_ticks);
  drive_reenable_delay_ticks_ = num::splat<Count>(config.drive_reenable_delay_ticks);
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
void DamperController<Policy>::reset(Mask m) noexcept {
  rild_.reset(m);
  velocity_.reset(m);
  law_.reset(m);
  i2t_.reset(m);
  guard_.reset(m);
  ticks_ = num::select(m, Tick{}, ticks_);
  have_sample_ = num::select(m, Mask{}, have_sample_);
  last_sample_tick_ = num::select(m, Tick{}, last_sample_tick_);
  primed_ = num::select(m, Mask{}, primed_);
  disp_gap_ = num::select(m, Mask{}, disp_gap_);
  desired_n_ = num::select(m, Force{}, desired_n_);
  last_command_a_ = num::select(m, fallback_a_, last_command_a_);
  bad_run_ = num::select(m, Count{}, bad_run_);
  drive_hold_ = num::select(m, Count{}, drive_hold_);
  status_.clear(m);
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
  bad_run_ = Count{};
  return true;
}

template <class Policy>
typename DamperController<Policy>::Output DamperController<Policy>::step(const Input& in) noexcept {
  Output out;
  const Tick now = ticks_;
  ticks_ = ticks_ + 1u;
  status_.ticks = ticks_;
  if (!initialized_) {
    out.current_command_a = Sample{};
    out.drive_enable = Mask{};
    return out;
  }

  // 1. Input guard; the rest of the tick knows when no signal has a fault.
  bool clean = false;
  const Faults faults = guard_.check(in, clean);
  if (clean) return step_checked<true>(in, now, Faults{});
  return step_checked<false>(in, now, faults);
}

template <class Policy>
template <bool kClean>
inline typename DamperController<Policy>::Output DamperController<Policy>::step_checked(const Input& in, Tick now,
                                                                                const Faults& faults) noexcept {
  Output out;
  // Staleness.
  const Mask stale = step_guard<kClean>(in, now, faults);

  // 2. Filters on a usable stroke.
  const Mask disp_ok = !stale && ok<kClean>(faults, InputSignal::kDisp);
  step_filters(in, disp_ok);

  // 3. Output: SAFE-1 (the drive's fault line) first, then the mode's law.
  const Mask drive_fault = in.flags.drive_fault;
  const Mask holding = !drive_fault && drive_hold_ > 0u;
  const Mask live = !drive_fault && !holding;
  if (!num::all(live)) {
    num::bump_where(status_.drive_fault_ticks, drive_fault);
    drive_hold_ = num::select(drive_fault, drive_reenable_delay_ticks_,
                              num::select(holding, drive_hold_ - 1u, drive_hold_));
    num::bump_where(status_.drive_disabled_ticks, !live);
  }
  Current command{};
  if (num::any(live)) command = step_law<kClean>(in, faults, disp_ok, live, out);
  last_command_a_ = num::select(live, command, Current{});
  out.current_command_a = num::select(live, num::to_float(command) * current_out_, Sample{});
  out.drive_enable = live;
  return out;
}

template <class Policy>
template <bool kClean>
inline typename DamperController<Policy>::Mask DamperController<Policy>::step_guard(const Input& in, Tick now,
                                                                              const Faults& faults) noexcept {
  if constexpr (kClean) {
    if (!faults_clear_) status_.last_faults = Faults{};
  } else {
    for (int s = 0; s < kInputSignals; ++s) {
      const Mask bad = faults[s] != Guard::fault(InputFault::kNone);
      if (num::any(bad)) {
        bump_at(status_.invalid_by_kind, faults[s], bad);
        num::bump_where(status_.invalid_by_signal[s], bad);
      }
    }
    status_.last_faults = faults;
  }
  faults_clear_ = kClean;
  const Mask stale = in.tick > now || now - in.tick > max_input_age_ticks_ ||
                     (have_sample_ && in.tick <= last_sample_tick_);
  status_.last_input_stale = stale;
  num::bump_where(status_.stale_inputs, stale);
  have_sample_ = have_sample_ || !stale;
  last_sample_tick_ = num::select(stale, last_sample_tick_, in.tick);
  return stale;
}

template <class Policy>
inline void DamperController<Policy>::step_filters(const Input& in, Mask disp_ok) noexcept {
  if (num::any(disp_ok)) {
    const Sample x_units = in.damper_disp_m * disp_in_;
    const Disp x = num::from_float<Disp>(x_units);
    const Mask first = disp_ok && !primed_;
    if (num::any(first)) {
      rild_.prime(x, first);
      velocity_.prime(x_units, first);
      primed_ = primed_ || first;
    }
    const Mask gap = disp_ok && !first && disp_gap_;
    if (num::any(gap)) velocity_.resync(x_units, gap);
    const Force fd = rild_.step(x, disp_ok);
    const Force clamped = num::clamp(fd, -desired_limit_n_, desired_limit_n_);
    num::bump_where(status_.desired_force_clamps, disp_ok && !(clamped == fd));
    desired_n_ = num::select(disp_ok, clamped, desired_n_);
    (void)velocity_.step(x_units, disp_ok);
  }
  disp_gap_ = !disp_ok;
}

template <class Policy>
template <bool kClean>
inline typename DamperController<Policy>::Current DamperController<Policy>::step_law(const Input& in,
                                                                             const Faults& faults, Mask disp_ok,
                                                                             Mask live, Output& out) noexcept {
  const Mask coil_ok = ok<kClean>(faults, InputSignal::kCoilCurrent);
  const Mask usable = disp_ok && coil_ok && ok<kClean>(faults, InputSignal::kForce);
  const Current coil_a = num::from_float<Current>(in.coil_current_a * current_in_);
  const Mask heat = live && coil_ok;
  if (num::any(heat)) i2t_.step(coil_a, heat);
  const Mask lawful = live && usable;
  OdbdcoDecision<Policy> d;
  if (num::any(lawful)) {
    d = law_.step(odbdco_, desired_n_, num::from_float<Force>(in.damper_force_n * force_in_), coil_a,
                  velocity_.per_tick(), i2t_.ceiling_a(), lawful);
  }
  if (mode_ == control::ControlMode::kPassiveOn) return nominal_a_;
  if (mode_ != control::ControlMode::kSemiActive) return Current{};  // passive-off
  if (num::any(lawful)) {
    bad_run_ = num::select(lawful, Count{}, bad_run_);
    bump_at(status_.branch_ticks, d.branch, lawful);
    out.desired_force_n = num::select(lawful, num::to_float(desired_n_) * force_out_, out.desired_force_n);
  }
  if (num::all(usable)) return d.command_a;
  // SAFE-2
  const Mask bad = live && !usable;
  num::bump_where(bad_run_, bad);
  const Mask held = bad && bad_run_ <= config_.fault_hold_ticks;
  num::bump_where(status_.held_ticks, held);
  num::bump_where(status_.fallback_ticks, bad && !held);
  return num::select(usable, d.command_a, num::select(held, last_command_a_, fallback_a_));
}

extern template class DamperController<num::Float32Policy>;
extern template class DamperController<num::Fixed32Policy>;
extern template class DamperController<Float64Policy>;

}  // namespace mrd::fw
