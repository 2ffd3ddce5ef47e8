#pragma once
/// Configuration of the damper controller, with the thesis's defaults, and
/// its validation (no exceptions: an error code).

#include <cstdint>
#include <type_traits>

#include "firmware/core/numeric_formats.hpp"
#include "mrd/control/io.hpp"
#include "mrd/units.hpp"

namespace mrd::fw {

/// Passive-on current, A (thesis §6.4): the passive-on command, the
/// controller's fallback on bad input and the drive's safe current when
/// commands stop.
inline constexpr double kPassiveOnCurrent_a = 2.5;

struct ControllerConfig {
  double period_s = 1.0e-3;  ///< control period T (1 kHz)
  control::ControlMode mode = control::ControlMode::kSemiActive;

  // Causal RILD, Eq. 6.1.
  double stiffness_n_m = 3287.0e3;                                ///< k, isolation stiffness (3287 kN/m)
  double loss_factor = 0.8;                                       ///< η (§6.3)
  double filter_freq_rad_s = 2.0 * units::kPi * 0.2508;           ///< ω_f, fundamental mode (`mrd modal`)
  double desired_force_limit_n = 400.0e3;                         ///< |F_d| clamp: 2× the 200 kN rating

  // Velocity direction for ODBDCO (hysteresis, odbdco.hpp).
  double velocity_cutoff_hz = 30.0;        ///< f_v of the differentiating low-pass
  double velocity_on_m_s = 6.0e-3;         ///< v_on: beyond it the direction is known
  double velocity_off_m_s = 3.0e-3;        ///< v_off: below it a known direction becomes unknown

  // ODBDCO, §6.3 and Phillips & Spencer 2012, held to the coil's rating (law in odbdco.hpp).
  double nominal_current_a = kPassiveOnCurrent_a;  ///< passive-on current (§6.4)
  double rated_current_a = kPassiveOnCurrent_a;    ///< I_r: the steady ceiling (Table 4.1's laws span 0–2.5 A)
  double overdrive_current_a = 10.0;    ///< I_od: voltage forcing while the coil is short of the target
  double backdrive_current_a = -10.0;   ///< I_bd: voltage forcing while the coil is above the target
  double current_band_a = 0.1;          ///< I_band: within it of the target, the command is the target
  double force_deadband_n = 2.0e3;      ///< F_db
  double target_dwell_s = 0.030;        ///< minimum time between target changes
  double rest_release_s = 1.0;          ///< direction unknown this long → target 0 A

  // Coil I²t (coil_i2t.hpp): the rating is the rise at I_r held continuously.
  double coil_thermal_time_constant_s = 1200.0;  ///< τ of the coil (20 min)
  double coil_derate_fraction = 0.8;             ///< derating starts at this fraction of the rated rise

  // PWM drive (§3.2; SPEC): command ±10 A at 1 V/A; 15 A continuous, 30 A peak.
  double command_limit_a = 10.0;
  double drive_continuous_limit_a = 15.0;
  double drive_peak_limit_a = 30.0;
  /// After the drive's fault line clears, the drive stays disabled this long.
  std::uint32_t drive_reenable_delay_ticks = 1000;

  // Input guard (input_guard.hpp).
  double disp_limit_m = 0.30;
  double force_limit_n = 500.0e3;
  double accel_limit_m_s2 = 50.0;
  double coil_current_limit_a = 30.0;
  std::uint32_t stuck_ticks = 500;
  double shaking_threshold_m_s2 = 0.1;
  /// Inputs sampled more than this many ticks before the present tick are stale.
  std::uint32_t max_input_age_ticks = 2;
  /// Semi-active with bad input: repeat the last command this many ticks, then fall back.
  std::uint32_t fault_hold_ticks = 5;
  /// Semi-active with bad input beyond the hold: this current (passive-on's 2.5 A).
  double fallback_current_a = kPassiveOnCurrent_a;
};

/// The controller every board and the simulator run: the thesis defaults
/// above at `period_s`, in `mode`. The velocity estimate's cut-off (30 Hz)
/// is lowered to a quarter of the sampling rate for periods above 1/120 s.
constexpr ControllerConfig default_controller_config(control::ControlMode mode, double period_s) noexcept {
  ControllerConfig c;
  c.mode = mode;
  c.period_s = period_s;
  if (c.velocity_cutoff_hz > 0.25 / period_s) c.velocity_cutoff_hz = 0.25 / period_s;
  return c;
}

enum class ConfigError : std::uint8_t {
  kNone = 0,
  kPeriod,           ///< T not in [1e−5, 0.1] s
  kMode,             ///< unknown control mode
  kStiffness,        ///< k not > 0
  kLossFactor,       ///< η not in (0, 10]
  kFilterFrequency,  ///< ω_f not in (0, π/T)
  kForceLimit,       ///< F_d limit not > 0
  kVelocityFilter,   ///< f_v not in (0, 1/(2T)), or not 0 ≤ v_off ≤ v_on
  kCurrentLevels,    ///< currents out of order (see validate_config)
  kDeadband,         ///< F_db < 0, dwell or rest time not in [0, 60] s
  kThermal,          ///< τ not > 0 or derate fraction not in (0, 1)
  kSensorLimits,     ///< guard limits not > 0, stuck_ticks < 2
  kFixedPointRange,  ///< a constant does not fit its fixed-point format
};

constexpr const char* config_error_name(ConfigError e) noexcept {
  switch (e) {
    case ConfigError::kNone: return "none";
    case ConfigError::kPeriod: return "period_s";
    case ConfigError::kMode: return "mode";
    case ConfigError::kStiffness: return "stiffness_n_m";
    case ConfigError::kLossFactor: return "loss_factor";
    case ConfigError::kFilterFrequency: return "filter_freq_rad_s";
    case ConfigError::kForceLimit: return "desired_force_limit_n";
    case ConfigError::kVelocityFilter: return "velocity_cutoff_hz/velocity_on_m_s/velocity_off_m_s";
    case ConfigError::kCurrentLevels: return "current levels";
    case ConfigError::kDeadband: return "force_deadband_n/target_dwell_s/rest_release_s";
    case ConfigError::kThermal: return "coil_thermal_time_constant_s/coil_derate_fraction";
    case ConfigError::kSensorLimits: return "sensor limits";
    case ConfigError::kFixedPointRange: return "fixed-point range";
  }
  return "unknown";
}

namespace detail {
constexpr bool finite_positive(double v) noexcept { return v > 0.0 && v < 1.0e300; }
constexpr bool finite(double v) noexcept { return v > -1.0e300 && v < 1.0e300; }
}  // namespace detail

/// The largest force the core must hold for `c`, N: the desired-force
/// limit, the load cell's guard limit or the deadband.
constexpr double largest_force_n(const ControllerConfig& c) noexcept {
  double f = c.desired_force_limit_n;
  if (c.force_limit_n > f) f = c.force_limit_n;
  if (c.force_deadband_n > f) f = c.force_deadband_n;
  return f;
}

/// The unit scales the core runs `c` at (numeric_formats.hpp): s_D from the
/// stroke limit, s_F from the largest force and kη, s_I from the rated
/// current, s_V from s_D and the period; all 1 in float.
template <class Policy>
constexpr CoreScales core_scales(const ControllerConfig& c) noexcept {
  return select_core_scales<Policy>(c.disp_limit_m, largest_force_n(c), c.stiffness_n_m * c.loss_factor,
                                    c.rated_current_a, c.period_s);
}

/// Counts of Force the desired-force limit spans at least (2^22: F_d resolved
/// to 2.4e−7 of its limit). It spans more than 2^30 when it sets s_F, more
/// than 2^29 under the thesis's load-cell limit of 1.25 times it; fewer only
/// when kη (kη s_D above about 8192 /m × the limit: F_d would reach its
/// limit within s_D/8192 of stroke, 37 µm for the thesis) or a load-cell
/// limit more than 512 times it sets s_F.
inline constexpr double kMinDesiredForceCounts = 4194304.0;

/// Checks that every constant of `c`, and every intermediate the blocks
/// document, fits its format of Policy at the scales core_scales<Policy>(c).
/// nullptr when all fit; otherwise a text naming the first constant that does
/// not and its format's limit (for error messages: `mrd configure`, board
/// files). Expects `c` to pass validate_config's other checks.
template <class Policy>
constexpr const char* fixed_point_misfit(const ControllerConfig& c) noexcept {
  using F = Formats<Policy>;
  constexpr bool kFixed = !std::is_floating_point_v<typename F::Force>;
  const CoreScales scales = core_scales<Policy>(c);
  const double sd = scales.disp_m();
  const double sf = scales.force_n();
  const double si = scales.current_a();
  // RILD: |w + x| < 4 max|x| (rild_filter.hpp).
  if (!representable<typename F::Disp>(4.0 * c.disp_limit_m / sd)) {
    return "disp_limit_m: the RILD state reaches 4 × disp_limit_m, which must fit Disp Q3.28 at the stroke "
           "scale s_D ≤ 2^24: disp_limit_m < 2 s_D m";
  }
  if (!representable<typename F::Force>(largest_force_n(c) / sf)) {
    return "desired_force_limit_n/force_limit_n/force_deadband_n: the largest must fit Force Q19.12 at the "
           "largest force scale, |F| < 524288 × 2^24 N";
  }
  if (!representable<typename F::Gain>(c.stiffness_n_m * c.loss_factor * sd / sf)) {
    return "stiffness_n_m × loss_factor (kη): must fit Gain Q23.8 at the force scale s_F ≤ 2^24, "
           "kη < 8.39e6 s_F/s_D N/m";
  }
  if constexpr (kFixed) {
    if (c.desired_force_limit_n / sf * 4096.0 < kMinDesiredForceCounts) {
      // Which constant raised s_F so far: the forces (load cell) or kη.
      const double sf_forces = pow2(smallest_exp_within(largest_force_n(c), F::Force::max_value()));
      if (sf_forces >= sf) {
        return "force_limit_n against desired_force_limit_n: the force scale s_F that fits the load cell's limit "
               "leaves the desired-force limit fewer than 2^22 counts of Force Q19.12 (2.4e−4 s_F N each): "
               "force_limit_n must stay below about 512 × desired_force_limit_n";
      }
      return "stiffness_n_m × loss_factor (kη) against desired_force_limit_n: the force scale s_F that fits kη in "
             "Gain Q23.8 (kη s_D/s_F < 8.39e6 N/m) leaves the desired-force limit fewer than 2^22 counts of Force "
             "Q19.12 (2.4e−4 s_F N each): kη × s_D must stay below about 8192 /m × desired_force_limit_n "
             "(s_D the stroke scale, 1 for a 0.30 m stroke limit)";
    }
  }
  const double sv = scales.velocity_m();
  if (!representable<typename F::Velocity>(c.velocity_on_m_s * c.period_s / sv)) {
    return "velocity_on_m_s: v_on × period_s must fit Velocity Q3.28 at the velocity scale s_V (±8 s_V m per "
           "tick, s_V the power of two with 8 s_D m/s × period_s ≤ 4 s_V)";
  }
  // A velocity threshold that rounds to zero counts would be no threshold.
  if (kFixed && c.velocity_on_m_s != 0.0 &&
      !(num::to_double(num::from_double<typename F::Velocity>(c.velocity_on_m_s * c.period_s / sv)) > 0.0)) {
    return "velocity_on_m_s: v_on × period_s must be at least one count of Velocity Q3.28 at the velocity "
           "scale s_V (8 s_D m/s × period_s ≤ 4 s_V): 3.7e−9 s_V m per tick, 7.5e−9 to 1.5e−8 s_D m/s";
  }
  // Every current is within the drive's peak (validate_config's order) or the sensor's limit.
  if (!representable<typename F::Current>(c.drive_peak_limit_a / si)) {
    return "drive_peak_limit_a: must fit Current Q7.24 at the current scale s_I (the power of two nearest "
           "rated_current_a / 2.5 A): drive_peak_limit_a < 128 s_I A";
  }
  if (!representable<typename F::Current>(c.coil_current_limit_a / si)) {
    return "coil_current_limit_a: must fit Current Q7.24 at the current scale s_I (the power of two nearest "
           "rated_current_a / 2.5 A): coil_current_limit_a < 128 s_I A";
  }
  // I²t (coil_i2t.hpp): the 16-tick mean of i² of a coil held at the
  // command limit (≥ I_od ≥ I_r) fits Square; the derating slope fits
  // Current; α moves m.
  if (!representable<typename F::Square>(c.command_limit_a * c.command_limit_a / (si * si))) {
    return "command_limit_a: its square must fit Square Q9.22 at the current scale s_I (the power of two "
           "nearest rated_current_a / 2.5 A), so that the I²t mean of i² holds a coil driven at the command "
           "limit: command_limit_a < 22.6 s_I A";
  }
  if (!representable<typename F::Current>(si / ((1.0 - c.coil_derate_fraction) * c.rated_current_a))) {
    return "coil_derate_fraction: the I²t derating slope 1/((1 − f) rated_current_a) must fit Current Q7.24 "
           "at the current scale s_I: (1 − f) rated_current_a > s_I / 128";
  }
  // α = 1 − exp(−x) with x = 16 T/τ; for tiny x, α ≈ x: one count of Coef is 2^−29.
  if (kFixed && !(16.0 * c.period_s / c.coil_thermal_time_constant_s >= 1.0 / 536870912.0)) {
    return "coil_thermal_time_constant_s: the I²t rate 1 − exp(−16 period_s/τ) must be at least one count "
           "of Coef Q2.29 (1.9e−9): τ ≤ 8.6e6 s at a 1 ms period";
  }
  return nullptr;
}

/// Checks a configuration for the numeric policy; kNone when usable.
/// Current levels must satisfy
///   0 < I_nom ≤ I_od ≤ I_cmd ≤ I_cont ≤ I_peak,  0 < I_r ≤ I_od,
///   −I_cmd ≤ I_bd < 0,  0 < I_band < I_r,  0 ≤ I_fallback ≤ I_cmd,
/// so over-drive never exceeds the drive's command range nor its continuous
/// rating. Then every constant must fit its format at the unit scales of
/// core_scales<Policy>(c), or kFixedPointRange (fixed_point_misfit names the
/// first that does not).
template <class Policy>
constexpr ConfigError validate_config(const ControllerConfig& c) noexcept {
  if (!(c.period_s >= 1.0e-5 && c.period_s <= 0.1)) return ConfigError::kPeriod;
  if (c.mode != control::ControlMode::kPassiveOff && c.mode != control::ControlMode::kPassiveOn &&
      c.mode != control::ControlMode::kSemiActive) {
    return ConfigError::kMode;
  }
  if (!detail::finite_positive(c.stiffness_n_m)) return ConfigError::kStiffness;
  if (!(c.loss_factor > 0.0 && c.loss_factor <= 10.0)) return ConfigError::kLossFactor;
  if (!(c.filter_freq_rad_s > 0.0 && c.filter_freq_rad_s * c.period_s < units::kPi)) {
    return ConfigError::kFilterFrequency;
  }
  if (!detail::finite_positive(c.desired_force_limit_n)) return ConfigError::kForceLimit;
  if (!(c.velocity_cutoff_hz > 0.0 && c.velocity_cutoff_hz * 2.0 * c.period_s < 1.0) ||
      !(c.velocity_off_m_s >= 0.0 && c.velocity_off_m_s <= c.velocity_on_m_s && detail::finite(c.velocity_on_m_s))) {
    return ConfigError::kVelocityFilter;
  }
  const bool currents_ok =
      c.nominal_current_a > 0.0 && c.nominal_current_a <= c.overdrive_current_a &&
      c.overdrive_current_a <= c.command_limit_a && c.command_limit_a <= c.drive_continuous_limit_a &&
      c.drive_continuous_limit_a <= c.drive_peak_limit_a && detail::finite(c.drive_peak_limit_a) &&
      c.rated_current_a > 0.0 && c.rated_current_a <= c.overdrive_current_a &&
      c.backdrive_current_a >= -c.command_limit_a && c.backdrive_current_a < 0.0 && c.current_band_a > 0.0 &&
      c.current_band_a < c.rated_current_a && c.fallback_current_a >= 0.0 &&
      c.fallback_current_a <= c.command_limit_a;
  if (!currents_ok) return ConfigError::kCurrentLevels;
  if (!(c.force_deadband_n >= 0.0 && detail::finite(c.force_deadband_n)) ||
      !(c.target_dwell_s >= 0.0 && c.target_dwell_s <= 60.0) || !(c.rest_release_s >= 0.0 && c.rest_release_s <= 60.0)) {
    return ConfigError::kDeadband;
  }
  if (!detail::finite_positive(c.coil_thermal_time_constant_s) ||
      !(c.coil_derate_fraction > 0.0 && c.coil_derate_fraction < 1.0)) {
    return ConfigError::kThermal;
  }
  if (!detail::finite_positive(c.disp_limit_m) || !detail::finite_positive(c.force_limit_n) ||
      !detail::finite_positive(c.accel_limit_m_s2) || !detail::finite_positive(c.coil_current_limit_a) ||
      !detail::finite_positive(c.shaking_threshold_m_s2) || c.stuck_ticks < 2) {
    return ConfigError::kSensorLimits;
  }
  // Fixed point: every constant and every intermediate the blocks document.
  if (fixed_point_misfit<Policy>(c) != nullptr) return ConfigError::kFixedPointRange;
  return ConfigError::kNone;
}

}  // namespace mrd::fw
