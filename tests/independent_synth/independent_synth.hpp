#pragma once
/// Measured-like records of the 200 kN MR damper with hidden physical
/// effects, made independently of the project's discrepancy workflow: its own
/// physics (damper_physics.hpp), continuous-time integration at a multiple of
/// the output rate (plant.hpp), its own forms of each effect and its own
/// sensor models. Standard library only.
///
/// Each effect is sized to an effect-to-noise ratio
/// <pre>
///   ENR = RMS(force with the effect − force without it, all else equal) / RMS(force noise)
/// </pre>
/// drawn log-uniform over [kEnrMin, kEnrMax] (from well below detection to
/// large); a draw is never repeated because an effect came out small.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "plant.hpp"

namespace indep {

enum class Effect {
  // Eight effects of the workflow's catalogue (same names).
  idle_settling,
  backlash,
  gas_spring,
  thermal_fade,
  time_delay,
  coil_lag,
  force_offset,
  direction_asymmetry,
  // Effects the workflow has no model of.
  tanh_transition,
  force_lowpass,
  series_compliance,
  fluid_inertia,
};

inline constexpr std::array kCatalogueEffects{Effect::idle_settling, Effect::backlash,   Effect::gas_spring,
                                              Effect::thermal_fade,  Effect::time_delay, Effect::coil_lag,
                                              Effect::force_offset,  Effect::direction_asymmetry};
inline constexpr std::array kOutOfCatalogueEffects{Effect::tanh_transition, Effect::force_lowpass,
                                                   Effect::series_compliance, Effect::fluid_inertia};

[[nodiscard]] std::string_view effect_name(Effect e) noexcept;
[[nodiscard]] bool in_catalogue(Effect e) noexcept;

/// Full ranges of the sensors an ADC quantizes: the 250 kN load cell (±250 kN)
/// and an LVDT of ±150 mm.
inline constexpr double kLoadCellRange_n = 500.0e3;
inline constexpr double kLvdtRange_m = 0.300;
inline constexpr int kPinkSections = 8;
/// The 1/f noise's slowest correlation time, s: a tenth of the 20 s record.
/// A part slower than that changes little over the record: there it is a
/// load-cell zero offset or drift (an offset the workflow rightly names),
/// not noise, so the clean records keep it out; the linear drift is drawn
/// on its own.
inline constexpr double kPinkSlowest_s = 2.0;

/// Range of the drawn ENR.
inline constexpr double kEnrMin = 0.25;
inline constexpr double kEnrMax = 64.0;

struct Spec {
  std::vector<Effect> effects;
  std::uint64_t seed = 1;
  double duration_s = 20.0;
  double rate_hz = 1000.0;
  int oversample = 10;
  /// ENR every effect is sized to; ≤ 0: drawn per effect, log-uniform in [enr_min, kEnrMax].
  double target_enr = -1.0;
  double enr_min = kEnrMin;
};

/// Force-channel and displacement sensor models of one record.
struct SensorModel {
  double lvdt_noise_m = 0.0;            ///< white, RMS
  double force_white_n = 0.0;           ///< white, RMS
  double force_coloured_n = 0.0;        ///< AR(1), stationary RMS
  double force_correlation_s = 0.0;     ///< AR(1) correlation time
  /// 1/f (pink) noise, RMS: a sum of kPinkSections AR(1) processes of equal
  /// variance with correlation times spaced evenly in log from 2 ms to
  /// kPinkSlowest_s (equal variance per Lorentzian at log-spaced corners gives
  /// a 1/f density between the corners).
  double force_pink_n = 0.0;
  double force_drift_n = 0.0;           ///< linear drift over the record, end minus start
  double disp_quantum_m = 0.0;          ///< 0 = none
  double force_quantum_n = 0.0;         ///< 0 = none
  int adc_bits = 0;                     ///< quanta from an ADC of this many bits over the ranges below; 0 = not an ADC
  double timing_jitter_s = 0.0;         ///< RMS of sampling instant minus time stamp
};

struct Case {
  // The record (SI), time stamps nominal.
  std::vector<double> time_s, displacement_m, current_cmd_a, force_n;
  // The truth.
  std::vector<Effect> effects;
  /// Per effect, its physical form (e.g. "cooling", "impact_spring"), drawn per case.
  std::vector<std::string> forms;
  /// The force noise's colour ("white", "ar1", "pink"), the quantization
  /// ("none", "fine" for 1 µm and 10 N, "adcNN") and the test motion
  /// ("sine", "multisine", "random", "chirp").
  std::string noise_form, quantization_form, motion_form;
  std::vector<double> target_enr;       ///< per effect (NaN where the effect has no size to tune)
  std::vector<double> enr;              ///< per effect, achieved, with the others present
  /// Per effect, for force_lowpass and series_compliance (whose leading term
  /// is a delay of the force): min over d of RMS(force − force without the
  /// effect delayed by d) / RMS(noise), what no pure delay reproduces. NaN
  /// for the other effects.
  std::vector<double> enr_beyond_delay;
  /// Per effect, for a gas spring with its preload (a constant a force_offset
  /// reproduces): RMS(difference less its mean) / RMS(noise), the spring's
  /// part. NaN otherwise.
  std::vector<double> enr_beyond_offset;
  EffectParams params;
  SensorModel sensors;
  double force_noise_rms_n = 0.0;       ///< RMS of the force noise actually added
  std::string description;              ///< input, current, variants, sensors in words
  /// Noise-free force at the samples and the same without any effect, N.
  std::vector<double> clean_force_n, baseline_force_n;
};

/// Deterministic for a spec. Throws std::invalid_argument for an effect
/// listed twice or a combination the plant cannot run (backlash with series
/// compliance).
[[nodiscard]] Case generate(const Spec& spec);

/// `p` with effect `e` removed (its parameters at their null values).
[[nodiscard]] EffectParams without(EffectParams p, Effect e);

/// Noise-free force at the (true) sampling instants `t_s`, delay applied, N.
[[nodiscard]] std::vector<double> noise_free_force(const Scenario& s, const std::vector<double>& t_s);

/// RMS(a − b) / noise_rms.
[[nodiscard]] double effect_to_noise_ratio(const std::vector<double>& a, const std::vector<double>& b, double noise_rms);

}  // namespace indep
