#pragma once
/// The catalogue of named physical effects the discrepancy workflow can add
/// to the chapter-4 damper model, each with its parameters, physical bounds
/// and the value at which it vanishes.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mrd::discrepancy {

enum class Effect {
  idle_settling,  ///< chapter 5: PR(∫Q dt) from a settling quotient SQ (Eq. 5.6–5.9)
  backlash,       ///< free play in the mounting (§5.2, Case 3)
  gas_spring,     ///< accumulator stiffness (§3.1)
  thermal_fade,   ///< yield and viscosity falling as dissipated energy heats the fluid
  time_delay,     ///< pure transport delay of the measured force
  coil_lag,       ///< coil current slower than Eq. 4.5
  force_offset,   ///< load-cell zero offset
  direction_asymmetry,  ///< force in extension and compression scaled differently
  preyield_hysteresis,  ///< yield force building over a pre-yield displacement after each reversal
};

inline constexpr std::size_t kEffectCount = 9;
inline constexpr std::array<Effect, kEffectCount> kAllEffects{
    Effect::idle_settling, Effect::backlash,  Effect::gas_spring,          Effect::thermal_fade,
    Effect::time_delay,    Effect::coil_lag,  Effect::force_offset,        Effect::direction_asymmetry,
    Effect::preyield_hysteresis};

/// One fitted parameter, in SI (or dimensionless) units.
struct ParamInfo {
  std::string_view name;        ///< JSON key, with its unit (`gap_m`, `delay_s`)
  double lower;                 ///< physical lower bound
  double upper;                 ///< physical upper bound
  double null_value;            ///< the effect vanishes here
  /// A fit that ends at the upper bound is still plausible (SQ = 1 is a fully
  /// settled fluid). Otherwise a fit pinned at a bound other than the null
  /// value means the effect is being stretched to mimic something else.
  bool upper_bound_physical;
  std::array<double, 5> init_grid;  ///< starting values tried before the local fit
  /// The value is a force (or force per metre): bounds and grid are for the
  /// thesis's 200 kN damper and scale with the baseline's force scale.
  bool force_scaled = false;
  /// The value scales the coil's time constants: above 1 only (slower) on a
  /// coil that was measured, either way on one that was assumed.
  bool coil_time = false;
};

/// What an effect's bounds depend on besides the effect: the baseline's
/// force scale over the thesis damper's (DamperModel::force_ratio()) and
/// whether its coil was identified (Baseline::coil_identified).
struct ParamScale {
  double force_ratio = 1.0;
  bool coil_identified = true;
};

/// Smallest scale of the coil's time constants fitted on a baseline whose coil
/// was assumed: Eq. 4.5's 0.7 s and 30 ms become 3.5 ms and 0.15 ms, a small
/// damper's coil behind a current drive (Spencer et al. 1997: 5 ms) and faster.
inline constexpr double kAssumedCoilMinScale = 0.005;

/// `p` with bounds, null value and grid multiplied by `scale.force_ratio` when
/// it is force-scaled; a coil_time parameter of a baseline whose coil was not
/// identified with its lower bound at kAssumedCoilMinScale and a grid on both
/// sides of 1; `p` itself otherwise.
[[nodiscard]] ParamInfo scaled_param(const ParamInfo& p, const ParamScale& scale) noexcept;

/// One physical form of an effect: what it describes and its parameters
/// (a form may have more or fewer than another).
struct EffectForm {
  std::string_view name;
  std::string_view description;
  std::span<const ParamInfo> params;
  /// Whether the form is the baseline at its parameters' null values. A
  /// single-lag coil is not Eq. 4.5 at any time constant: a fit that ends at
  /// its null value (one lag of Eq. 4.5's mean delay) is still a finding.
  bool has_null = true;
};

struct EffectInfo {
  Effect effect;
  std::string_view name;
  std::string_view description;
  std::span<const ParamInfo> params;  ///< the first form's
  /// Every form, the first the catalogue's original (params above); at least one.
  std::span<const EffectForm> forms;
};

/// Per effect (indexed by the enum), the index of its form in
/// EffectInfo::forms; 0 is the first form.
using EffectForms = std::array<std::uint8_t, kEffectCount>;

/// Forms of the effects with more than one (EffectInfo::forms), by index:
/// coil_lag's, idle_settling's and backlash's second forms, backlash's third.
inline constexpr std::uint8_t kCoilSingleLag = 1;      ///< coil_lag: one first-order lag of fitted tau
inline constexpr std::uint8_t kSettlingFullRecovery = 1;  ///< idle_settling: full recovery over its own volume
inline constexpr std::uint8_t kBacklashImpactSpring = 1;  ///< backlash: a contact spring at the end of the play
inline constexpr std::uint8_t kBacklashProgressive = 2;   ///< backlash: a progressive stop (tanh engagement)

[[nodiscard]] const EffectInfo& effect_info(Effect e) noexcept;
/// Parameters of effect `e` in its form `form` (the first form's when out of range).
[[nodiscard]] std::span<const ParamInfo> form_params(Effect e, std::size_t form) noexcept;
/// Name of effect `e`'s form `form` ("" when out of range).
[[nodiscard]] std::string_view form_name(Effect e, std::size_t form) noexcept;
/// Whether effect `e`'s form `form` is the baseline at its null values (EffectForm::has_null).
[[nodiscard]] bool form_has_null(Effect e, std::size_t form) noexcept;
[[nodiscard]] std::string_view effect_name(Effect e) noexcept;
[[nodiscard]] std::optional<Effect> effect_from_name(std::string_view name) noexcept;

/// Heat capacity that turns dissipated energy into a temperature rise in the
/// `thermal_fade` effect, J/K: about 60 kg of MR fluid (0.0166 m³, Table 5.4,
/// at ~3.6 t/m³) at ~1 kJ/(kg·K). Only α/C is identified from force data, so
/// the fitted coefficients are "per kelvin of this assumed capacity".
inline constexpr double kThermalCapacity_j_per_k = 60.0e3;

/// An ordered set of effects with their parameters packed one after the other.
struct EffectSet {
  std::vector<Effect> effects;
  /// The form of each effect (EffectInfo::forms); parameters are packed by it.
  EffectForms forms{};

  [[nodiscard]] bool contains(Effect e) const noexcept;
  /// Form index of `e` (0 for an effect with one form).
  [[nodiscard]] std::size_t form(Effect e) const noexcept { return forms[static_cast<std::size_t>(e)]; }
  /// Parameters of `e` in its form here.
  [[nodiscard]] std::span<const ParamInfo> params_of(Effect e) const noexcept { return form_params(e, form(e)); }
  /// Index of the first parameter of `e` in the packed vector; nullopt if absent.
  [[nodiscard]] std::optional<std::size_t> offset(Effect e) const noexcept;
  [[nodiscard]] std::size_t param_count() const noexcept;
  /// Null values of every parameter (the baseline model).
  [[nodiscard]] std::vector<double> null_params() const;
  /// "a+b" or "none".
  [[nodiscard]] std::string label() const;
  /// "backlash (impact_spring)" for the effects not in their first form, joined by "; "; "" when none is.
  [[nodiscard]] std::string form_label() const;
};

/// Parses "none", "" or a comma-separated list of effect names. Throws
/// io::UsageError naming the unknown entry.
[[nodiscard]] std::vector<Effect> parse_effect_list(std::string_view text, std::string_view option);

}  // namespace mrd::discrepancy
