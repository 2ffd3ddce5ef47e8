#include "host_sim/discrepancy/effects.hpp"

#include <algorithm>

#include "host_sim/io/usage_error.hpp"

namespace mrd::discrepancy {
namespace {

// Bounds are physical limits, not the ranges the generator draws from.
constexpr std::array kIdleParams{
    // SQ of Eq. 5.5 as a fraction; Eq. 5.6–5.8 give a_PR, b_PR, c_PR from it.
    ParamInfo{"sq", 0.0, 1.0, 0.0, true, {0.05, 0.2, 0.4, 0.7, 1.0}},
};
constexpr std::array kSettlingRecoveryParams{
    ParamInfo{"sq", 0.0, 1.0, 0.0, true, {0.05, 0.2, 0.4, 0.7, 1.0}},
    // Displaced volume over which a settled layer remixes fully, PR = 1 − (1 − a_PR(SQ)) e^(−V/V_r):
    // 0.2 L (a thin layer the first strokes stir) to 50 L (three times the 16.6 L of fluid, Table 5.4).
    ParamInfo{"recovery_volume_m3", 0.0002, 0.05, 0.004, false, {0.0005, 0.0015, 0.004, 0.01, 0.03}},
};
constexpr std::array kBacklashParams{
    // Total free play between actuator and damper rod: up to 10 mm of loose bolts.
    ParamInfo{"free_play_m", 0.0, 0.010, 0.0, false, {0.0002, 0.0006, 0.0015, 0.003, 0.006}},
    // Share of the play over which a compliant stop takes up the motion (damper_model.cpp,
    // soft_contact_step): 0 is a hard stop (metal on metal), up to 1 (a pad as thick as the play).
    ParamInfo{"contact_share", 0.0, 1.0, 0.0, false, {0.0, 0.05, 0.15, 0.35, 0.7}},
};
constexpr std::array kBacklashImpactParams{
    ParamInfo{"free_play_m", 0.0, 0.010, 0.0, false, {0.0002, 0.0006, 0.0015, 0.003, 0.006}},
    // Deflection of the contact spring at the end of the play under the baseline's force scale
    // (200 kN for the thesis damper): 0 is a hard stop, up to 20 mm (a rubber pad, a bolt in bending).
    ParamInfo{"stop_deflection_m", 0.0, 0.020, 0.0, false, {0.0, 0.0005, 0.0015, 0.004, 0.01}},
};
constexpr std::array kBacklashProgressiveParams{
    ParamInfo{"free_play_m", 0.0, 0.010, 0.0, false, {0.0002, 0.0006, 0.0015, 0.003, 0.006}},
    // Length over which a progressive stop engages, as a share of the play (damper_model.cpp,
    // progressive_contact_step): 0 is a hard stop, up to 1 (a bushing as soft as the play is long).
    ParamInfo{"engagement_share", 0.0, 1.0, 0.0, false, {0.0, 0.05, 0.15, 0.35, 0.7}},
};
constexpr std::array kGasParams{
    // k = γ p A_rod² / V_gas: 1.4 · 5.17 MPa (§3.1) · (π 0.04²)² / V ≈ 0.18 MN/m per litre of gas;
    // 5 MN/m allows a gas volume down to ~0.04 L.
    ParamInfo{"stiffness_n_m", 0.0, 5.0e6, 0.0, false, {5.0e4, 2.0e5, 5.0e5, 1.0e6, 3.0e6}, true},
};
constexpr std::array kThermalParams{
    // Fractional loss per kelvin, the temperature rise being E / kThermalCapacity_j_per_k.
    ParamInfo{"yield_coeff_per_k", 0.0, 0.03, 0.0, false, {0.0, 0.002, 0.006, 0.012, 0.02}},
    ParamInfo{"viscous_coeff_per_k", 0.0, 0.06, 0.0, false, {0.0, 0.005, 0.015, 0.03, 0.045}},
};
constexpr std::array kDelayParams{
    ParamInfo{"delay_s", 0.0, 0.1, 0.0, false, {0.002, 0.005, 0.012, 0.03, 0.06}},
};
constexpr std::array kCoilParams{
    // Both time constants of Eq. 4.5 scaled by this factor (1 = Eq. 4.5); below 1
    // too when the baseline's coil was assumed (scaled_param).
    ParamInfo{"tau_scale", 1.0, 10.0, 1.0, false, {1.3, 2.0, 3.0, 5.0, 8.0}, false, true},
};
constexpr std::array kCoilSingleLagParams{
    // One first-order lag (an L/R coil) whose time constant is this factor times Eq. 4.5's
    // mean delay w_s τ_s + w_f τ_f (0.365 s for the thesis coil): 0.1 (37 ms) to 10 (3.7 s);
    // down to kAssumedCoilMinScale when the baseline's coil was assumed (scaled_param).
    ParamInfo{"lag_tau_scale", 0.1, 10.0, 1.0, false, {0.3, 0.7, 1.5, 3.0, 6.0}, false, true},
};
constexpr std::array kOffsetParams{
    // Zero offset of the 250 kN load cell (§3.2), up to 12 % of its range.
    ParamInfo{"offset_n", -30.0e3, 30.0e3, 0.0, false, {-5.0e3, -1.0e3, 0.0, 1.0e3, 5.0e3}, true},
};

constexpr std::array kAsymmetryParams{
    // F·(1 + a) while extending (v > 0), F·(1 − a) while compressing: up to a 3:1 ratio.
    ParamInfo{"asymmetry", -0.5, 0.5, 0.0, false, {-0.2, -0.08, 0.0, 0.08, 0.2}},
};
constexpr std::array kPreyieldParams{
    // Displacement over which the yield force builds after a reversal (Bouc–Wen x_y,
    // baseline.hpp); 0 is the baseline's own law. Up to 10 mm.
    ParamInfo{"yield_disp_m", 0.0, 0.010, 0.0, false, {0.0002, 0.0005, 0.001, 0.002, 0.005}},
};

constexpr std::array kIdleForms{
    EffectForm{"eq5.9", "Eq. 5.9: a lasting deficit 1 - b_PR, recovering at c_PR, all from SQ", kIdleParams},
    EffectForm{"full_recovery",
               "a settled layer remixing fully over its own displaced volume V_r: PR = 1 - (1 - a_PR(SQ)) "
               "exp(-V / V_r)",
               kSettlingRecoveryParams},
};
constexpr std::array kBacklashForms{
    EffectForm{"kinematic", "the rod taken up over a contact length at the end of the play", kBacklashParams},
    EffectForm{"impact_spring",
               "the rod pushed through a contact spring at the end of the play, its deflection following the force",
               kBacklashImpactParams},
    EffectForm{"progressive",
               "the rod taken up by a progressive stop (a bushing stiffening as it closes): its share of the "
               "actuator's motion rising as (1 + tanh(p / l)) / 2 with its penetration p, a tail over many "
               "engagement lengths l",
               kBacklashProgressiveParams},
};
constexpr std::array kGasForms{EffectForm{"linear", "k x", kGasParams}};
constexpr std::array kThermalForms{EffectForm{"linear", "1 - alpha dT, dT = E / C", kThermalParams}};
constexpr std::array kDelayForms{EffectForm{"pure", "F(t - tau)", kDelayParams}};
constexpr std::array kCoilForms{
    EffectForm{"eq4.5_scaled", "both time constants of Eq. 4.5 scaled", kCoilParams},
    EffectForm{"single_lag",
               "one first-order lag (an L/R coil), tau = lag_tau_scale times Eq. 4.5's mean delay",
               kCoilSingleLagParams, false},
};
constexpr std::array kOffsetForms{EffectForm{"constant", "F_0", kOffsetParams}};
constexpr std::array kAsymmetryForms{EffectForm{"scaled", "F (1 + a sgn v)", kAsymmetryParams}};
constexpr std::array kPreyieldForms{EffectForm{"bouc_wen", "Bouc-Wen with fitted x_y", kPreyieldParams}};

const std::array<EffectInfo, kEffectCount>& catalogue() {
  static const std::array<EffectInfo, kEffectCount> c{
      EffectInfo{Effect::idle_settling, "idle_settling",
                 "settled particles: participant ratio PR(SQ, ∫Q dt) below 1, recovering with displaced volume "
                 "(Eq. 5.6-5.12, or fully over a volume of its own)",
                 kIdleParams, kIdleForms},
      EffectInfo{Effect::backlash, "backlash",
                 "free play in the mounting: the damper stands still until the actuator has crossed the gap after "
                 "each reversal, against a hard or a compliant stop (§5.2, Case 3)",
                 kBacklashParams, kBacklashForms},
      EffectInfo{Effect::gas_spring, "gas_spring",
                 "accumulator gas spring: a force proportional to the rod's displacement (§3.1)", kGasParams, kGasForms},
      EffectInfo{Effect::thermal_fade, "thermal_fade",
                 "yield force and viscosity falling linearly with the temperature rise from dissipated energy",
                 kThermalParams, kThermalForms},
      EffectInfo{Effect::time_delay, "time_delay", "pure transport delay between displacement and force channels",
                 kDelayParams, kDelayForms},
      EffectInfo{Effect::coil_lag, "coil_lag",
                 "coil current slower than the baseline's Eq. 4.5 (or faster, when the baseline's coil was assumed): "
                 "both time constants scaled, or one first-order lag of fitted time constant",
                 kCoilParams, kCoilForms},
      EffectInfo{Effect::force_offset, "force_offset", "load-cell zero offset: a constant force", kOffsetParams, kOffsetForms},
      EffectInfo{Effect::direction_asymmetry, "direction_asymmetry",
                 "the damper stronger in one direction: force scaled by 1 + a in extension, 1 - a in compression",
                 kAsymmetryParams, kAsymmetryForms},
      EffectInfo{Effect::preyield_hysteresis, "preyield_hysteresis",
                 "pre-yield hysteresis: after each reversal the yield force builds over a displacement x_y "
                 "(Bouc-Wen) instead of following the velocity (Eq. 4.4)",
                 kPreyieldParams, kPreyieldForms},
  };
  return c;
}

}  // namespace

ParamInfo scaled_param(const ParamInfo& p, const ParamScale& scale) noexcept {
  ParamInfo s = p;
  if (p.force_scaled) {
    s.lower *= scale.force_ratio;
    s.upper *= scale.force_ratio;
    s.null_value *= scale.force_ratio;
    for (double& g : s.init_grid) g *= scale.force_ratio;
  }
  if (p.coil_time && !scale.coil_identified) {
    s.lower = kAssumedCoilMinScale;
    s.init_grid = {0.01, 0.04, 0.15, 0.5, 3.0};
  }
  return s;
}

const EffectInfo& effect_info(Effect e) noexcept { return catalogue()[static_cast<std::size_t>(e)]; }

std::string_view effect_name(Effect e) noexcept { return effect_info(e).name; }

std::span<const ParamInfo> form_params(Effect e, std::size_t form) noexcept {
  const auto& info = effect_info(e);
  return form < info.forms.size() ? info.forms[form].params : info.params;
}

std::string_view form_name(Effect e, std::size_t form) noexcept {
  const auto& info = effect_info(e);
  return form < info.forms.size() ? info.forms[form].name : std::string_view{};
}

bool form_has_null(Effect e, std::size_t form) noexcept {
  const auto& info = effect_info(e);
  return form < info.forms.size() ? info.forms[form].has_null : true;
}

std::optional<Effect> effect_from_name(std::string_view name) noexcept {
  for (const auto& i : catalogue()) {
    if (i.name == name) return i.effect;
  }
  return std::nullopt;
}

bool EffectSet::contains(Effect e) const noexcept {
  return std::find(effects.begin(), effects.end(), e) != effects.end();
}

std::optional<std::size_t> EffectSet::offset(Effect e) const noexcept {
  std::size_t off = 0;
  for (const Effect x : effects) {
    if (x == e) return off;
    off += params_of(x).size();
  }
  return std::nullopt;
}

std::size_t EffectSet::param_count() const noexcept {
  std::size_t n = 0;
  for (const Effect x : effects) n += params_of(x).size();
  return n;
}

std::vector<double> EffectSet::null_params() const {
  std::vector<double> p;
  for (const Effect x : effects) {
    for (const auto& pi : params_of(x)) p.push_back(pi.null_value);
  }
  return p;
}

std::string EffectSet::label() const {
  if (effects.empty()) return "none";
  std::string s;
  for (const Effect x : effects) {
    if (!s.empty()) s += '+';
    s += effect_name(x);
  }
  return s;
}

std::string EffectSet::form_label() const {
  std::string s;
  for (const Effect x : effects) {
    if (form(x) == 0) continue;
    if (!s.empty()) s += "; ";
    s += std::string(effect_name(x)) + " (" + std::string(form_name(x, form(x))) + ")";
  }
  return s;
}

std::vector<Effect> parse_effect_list(std::string_view text, std::string_view option) {
  std::vector<Effect> out;
  if (text.empty() || text == "none") return out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t p = text.find(',', start);
    const std::string_view item = text.substr(start, p == std::string_view::npos ? std::string_view::npos : p - start);
    const auto e = effect_from_name(item);
    if (!e) {
      std::string known;
      for (const Effect x : kAllEffects) known += (known.empty() ? "" : ", ") + std::string(effect_name(x));
      throw io::UsageError(std::string(option) + ": unknown effect '" + std::string(item) + "' (known: " + known +
                               ", or none)");
    }
    if (std::find(out.begin(), out.end(), *e) != out.end()) {
      throw io::UsageError(std::string(option) + ": effect '" + std::string(item) + "' given twice");
    }
    out.push_back(*e);
    if (p == std::string_view::npos) break;
    start = p + 1;
  }
  return out;
}

}  // namespace mrd::discrepancy
