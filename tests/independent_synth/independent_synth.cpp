#include "independent_synth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "damper_physics.hpp"

namespace indep {
namespace {

/// The range of one effect's size (the parameter the ENR is tuned with), searched on a log scale.
struct SizeRange {
  double lo, hi;
};

/// Sizes stay inside physical limits, below the workflow's parameter bounds
/// (a size that cannot reach the drawn ENR stops at the top of its range).
SizeRange size_range(Effect e) {
  switch (e) {
    case Effect::idle_settling: return {1e-5, 1.0};          // SQ
    case Effect::backlash: return {1e-7, 0.006};             // total free play, m
    case Effect::gas_spring: return {1.0, 3.0e6};            // N/m (0.06 L of gas at 5.17 MPa)
    // Yield coefficient, 1/K (viscous ≤ 1.6× that): with C ≥ 50 kJ/K, at most 0.024 and 0.038 per kelvin
    // of the workflow's 60 kJ/K, inside its bounds (0.03, 0.06).
    case Effect::thermal_fade: return {1e-8, 0.02};
    case Effect::time_delay: return {1e-7, 0.06};            // s
    case Effect::coil_lag: return {1e-5, 5.0};               // tau scale − 1
    case Effect::force_offset: return {0.1, 15.0e3};         // |F_0|, N: 6 % of a 250 kN load cell
    case Effect::tanh_transition: return {0.0, 0.0};         // drawn, not tuned
    case Effect::direction_asymmetry: return {1e-6, 0.4};    // |a|: up to a 7:3 ratio
    case Effect::force_lowpass: return {1e-7, 0.05};         // s
    case Effect::series_compliance: return {1e-13, 1e-7};    // 1 / k, m/N
    // Effective fluid mass ρ L A_p²/A_gap, kg: 3.6 t/m³ over a 0.3 m gap with A_p²/A_gap of 2 m²
    // (a 0.2 m piston, a 1 mm annulus) gives about 2 t; the range goes 5× beyond to span detection.
    case Effect::fluid_inertia: return {1e-2, 1.0e4};
  }
  return {0.0, 0.0};
}

/// Per-effect variations of form, fixed before the size is tuned.
struct Variation {
  double sign = 1.0;
  // thermal: viscous / yield coefficient; compliance: damping time, s; gas spring: preload over
  // stiffness, m (0 = no preload); backlash with impact stiffness: the contact spring's
  // deflection under 100 kN as a fraction of the play.
  double ratio = 1.0;
  double filter_s = 0.0;  // time_delay: the anti-alias filter behind it
};

/// Gas pressure of §3.1 on the rod: 5.17 MPa × π (0.04 m)² ≈ 26 kN, the largest preload drawn.
constexpr double kMaxGasPreload_n = 26.0e3;
/// Force at which the impact spring's deflection is drawn, N.
constexpr double kImpactReferenceForce_n = 100.0e3;

void set_size(EffectParams& p, Effect e, double size, const Variation& v) {
  switch (e) {
    case Effect::idle_settling: p.settling_quotient = size; break;
    case Effect::backlash:
      p.free_play_m = size;
      if (p.contact_stiffness_n_m > 0.0) p.contact_stiffness_n_m = kImpactReferenceForce_n / (v.ratio * size);
      break;
    case Effect::gas_spring:
      p.gas_stiffness_n_m = size;
      p.gas_preload_n = std::min(size * v.ratio, kMaxGasPreload_n);
      break;
    case Effect::thermal_fade:
      p.fade_yield_per_k = size;
      p.fade_viscous_per_k = size * v.ratio;
      break;
    case Effect::time_delay:
      p.force_delay_s = size;
      p.delay_filter_s = v.filter_s;
      break;
    case Effect::coil_lag: p.coil_tau_scale = 1.0 + size; break;
    case Effect::force_offset: p.force_offset_n = v.sign * size; break;
    case Effect::tanh_transition: break;
    case Effect::direction_asymmetry: p.asymmetry = v.sign * size; break;
    case Effect::force_lowpass: p.force_filter_s = size; break;
    case Effect::fluid_inertia: p.fluid_mass_kg = size; break;
    case Effect::series_compliance:
      p.series_stiffness_n_m = 1.0 / size;
      p.series_damping_n_s_m = v.ratio / size;
      break;
  }
}

std::string fmt(const char* f, double a, double b = 0.0, double c = 0.0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

/// Actuator motion: one sine (35 %), a multi-sine of 2–5 tones (20 %), band-limited random
/// (0.1–3 Hz, 25 %) or a linear chirp (20 %); peak velocity within the damper's range.
Motion draw_motion(Rng& rng, double duration_s, std::string& text, std::string& form) {
  Motion m;
  constexpr double kVelocityLimit_m_s = 0.245;  // below Table 3.1's 0.2491 m/s
  const double kind = rng.uniform();
  if (kind < 0.35) {
    const double f = rng.log_uniform(0.2, 2.0);
    const double a_max = std::min(0.100, kVelocityLimit_m_s / (2.0 * std::numbers::pi * f));
    const double a = rng.log_uniform(0.005, a_max);
    m.sines.push_back({a, f, rng.uniform(0.0, 2.0 * std::numbers::pi)});
    text = fmt("sine %.1f mm %.2f Hz", a * 1e3, f);
    form = "sine";
    return m;
  }
  if (kind >= 0.80) {
    // Sweep between f_lo in 0.1–0.5 Hz and f_hi in 1–3 Hz, up or down; the velocity's peak is at f_hi.
    const double f_lo = rng.log_uniform(0.1, 0.5), f_hi = rng.log_uniform(1.0, 3.0);
    const bool up = rng.chance(0.5);
    const double a_max = std::min(0.100, kVelocityLimit_m_s / (2.0 * std::numbers::pi * f_hi));
    m.chirp.amplitude_m = rng.log_uniform(0.005, a_max);
    m.chirp.start_hz = up ? f_lo : f_hi;
    m.chirp.rate_hz_per_s = (up ? f_hi - f_lo : f_lo - f_hi) / duration_s;
    text = fmt("chirp %.1f mm, %.2f to ", m.chirp.amplitude_m * 1e3, m.chirp.start_hz) +
           fmt("%.2f Hz", up ? f_hi : f_lo);
    form = "chirp";
    return m;
  }
  const bool multisine = kind < 0.55;
  // Multi-sine: 2–5 tones log-uniform in 0.2–2 Hz, amplitudes 0.3–1. Random: 12–30 tones in
  // 0.1–3 Hz with amplitudes ∝ f^(−slope), from flat (velocity-rich) to 1/f (displacement-rich).
  const int count = multisine ? 2 + static_cast<int>(rng.uniform() * 4.0) : 12 + static_cast<int>(rng.uniform() * 19.0);
  const double slope = multisine ? 0.0 : rng.uniform(0.0, 1.0);
  for (int i = 0; i < count; ++i) {
    const double f = multisine ? rng.log_uniform(0.2, 2.0) : rng.uniform(0.1, 3.0);
    const double a = multisine ? rng.uniform(0.3, 1.0) : rng.uniform(0.5, 1.5) * std::pow(f, -slope);
    m.sines.push_back({a, f, rng.uniform(0.0, 2.0 * std::numbers::pi)});
  }
  form = multisine ? "multisine" : "random";
  double ss = 0.0, vpeak = 0.0;
  const int n = static_cast<int>(duration_s * 1000.0);
  for (int k = 0; k < n; ++k) {
    const double t = k * 1e-3;
    ss += m.displacement_m(t) * m.displacement_m(t);
    vpeak = std::max(vpeak, std::abs(m.velocity_m_s(t)));
  }
  const double rms_target = rng.uniform(0.010, 0.050);
  double scale = rms_target / std::sqrt(ss / n);
  scale = std::min(scale, kVelocityLimit_m_s / (vpeak));
  for (auto& s : m.sines) s.amplitude_m *= scale;
  text = fmt(multisine ? "multisine %.0f tones 0.2-2 Hz, %.1f mm rms" : "random %.0f sines 0.1-3 Hz, %.1f mm rms",
             count, std::sqrt(ss / n) * scale * 1e3) +
         fmt(", %.0f mm/s peak, slope %.2f", vpeak * scale * 1e3, slope);
  return m;
}

/// Commanded current: constant, a few steps, or random steps every 0.5–3 s, levels in 0–2.5 A.
CurrentProgram draw_current(Rng& rng, double duration_s, bool must_vary, std::string& text) {
  CurrentProgram c;
  c.levels_a = {rng.uniform(0.0, 2.5)};
  const double kind = must_vary ? rng.uniform(1.0 / 3.0, 1.0) : rng.uniform();
  if (kind < 1.0 / 3.0) {
    text = fmt("constant %.2f A", c.levels_a[0]);
    return c;
  }
  if (kind < 2.0 / 3.0) {
    const int steps = 2 + static_cast<int>(rng.uniform() * 3.0);
    std::vector<double> at;
    for (int i = 0; i < steps; ++i) at.push_back(rng.uniform(0.5, duration_s - 0.5));
    std::sort(at.begin(), at.end());
    for (const double t : at) {
      c.start_s.push_back(t);
      c.levels_a.push_back(rng.uniform(0.0, 2.5));
    }
    text = fmt("%.0f steps in 0-2.5 A", steps);
    return c;
  }
  for (double t = rng.uniform(0.5, 3.0); t < duration_s; t += rng.uniform(0.5, 3.0)) {
    c.start_s.push_back(t);
    c.levels_a.push_back(rng.uniform(0.0, 2.5));
  }
  text = fmt("random steps every 0.5-3 s (%.0f)", static_cast<double>(c.start_s.size() - 1));
  return c;
}

/// Force noise white only, white plus AR(1), or white plus 1/f (a third each); quantization none,
/// fine (1 µm, 10 N, each on half of those), or a 12–16-bit ADC over both sensors' ranges.
SensorModel draw_sensors(Rng& rng, std::string& noise_form, std::string& quantization_form) {
  SensorModel s;
  s.lvdt_noise_m = rng.uniform(5e-6, 20e-6);
  s.force_white_n = rng.uniform(200.0, 1000.0);
  const double colour = rng.uniform();
  if (colour < 1.0 / 3.0) {
    noise_form = "white";
  } else if (colour < 2.0 / 3.0) {
    s.force_coloured_n = rng.uniform(100.0, 500.0);
    s.force_correlation_s = rng.uniform(0.010, 0.050);
    noise_form = "ar1";
  } else {
    s.force_pink_n = rng.uniform(100.0, 500.0);
    noise_form = "pink";
  }
  if (rng.chance(0.3)) s.force_drift_n = rng.uniform(-300.0, 300.0);
  const double q = rng.uniform();
  if (q < 1.0 / 3.0) {
    quantization_form = "none";
  } else if (q < 2.0 / 3.0) {
    if (rng.chance(0.5)) s.disp_quantum_m = 1e-6;
    if (rng.chance(0.5)) s.force_quantum_n = 10.0;
    quantization_form = "fine";
  } else {
    s.adc_bits = 12 + static_cast<int>(rng.uniform() * 5.0);
    const double levels = std::ldexp(1.0, s.adc_bits);
    s.force_quantum_n = kLoadCellRange_n / levels;
    s.disp_quantum_m = kLvdtRange_m / levels;
    quantization_form = std::string("adc").append(std::to_string(s.adc_bits));
  }
  if (rng.chance(0.3)) s.timing_jitter_s = rng.uniform(5e-6, 20e-6);
  return s;
}

double quantize(double x, double q) { return q > 0.0 ? q * std::round(x / q) : x; }

}  // namespace

std::string_view effect_name(Effect e) noexcept {
  switch (e) {
    case Effect::idle_settling: return "idle_settling";
    case Effect::backlash: return "backlash";
    case Effect::gas_spring: return "gas_spring";
    case Effect::thermal_fade: return "thermal_fade";
    case Effect::time_delay: return "time_delay";
    case Effect::coil_lag: return "coil_lag";
    case Effect::force_offset: return "force_offset";
    case Effect::tanh_transition: return "tanh_transition";
    case Effect::direction_asymmetry: return "direction_asymmetry";
    case Effect::force_lowpass: return "force_lowpass";
    case Effect::series_compliance: return "series_compliance";
    case Effect::fluid_inertia: return "fluid_inertia";
  }
  return "?";
}

bool in_catalogue(Effect e) noexcept {
  return std::find(kCatalogueEffects.begin(), kCatalogueEffects.end(), e) != kCatalogueEffects.end();
}

EffectParams without(EffectParams p, Effect e) {
  const EffectParams null{};
  switch (e) {
    case Effect::idle_settling:
      p.settling_quotient = null.settling_quotient;
      p.settling_recovery_l = null.settling_recovery_l;
      break;
    case Effect::backlash:
      p.free_play_m = null.free_play_m;
      p.contact_fraction = null.contact_fraction;
      p.contact_stiffness_n_m = null.contact_stiffness_n_m;
      break;
    case Effect::gas_spring:
      p.gas_stiffness_n_m = null.gas_stiffness_n_m;
      p.gas_nonlinearity_per_m2 = null.gas_nonlinearity_per_m2;
      p.gas_preload_n = null.gas_preload_n;
      break;
    case Effect::thermal_fade:
      p.fade_yield_per_k = null.fade_yield_per_k;
      p.fade_viscous_per_k = null.fade_viscous_per_k;
      break;
    case Effect::time_delay:
      p.force_delay_s = null.force_delay_s;
      p.delay_filter_s = null.delay_filter_s;
      break;
    case Effect::coil_lag:
      p.coil_tau_scale = null.coil_tau_scale;
      p.coil_single_lag = null.coil_single_lag;
      break;
    case Effect::force_offset: p.force_offset_n = null.force_offset_n; break;
    case Effect::tanh_transition: p.tanh_velocity_m_s = null.tanh_velocity_m_s; break;
    case Effect::direction_asymmetry: p.asymmetry = null.asymmetry; break;
    case Effect::fluid_inertia: p.fluid_mass_kg = null.fluid_mass_kg; break;
    case Effect::force_lowpass: p.force_filter_s = null.force_filter_s; break;
    case Effect::series_compliance:
      p.series_stiffness_n_m = null.series_stiffness_n_m;
      p.series_damping_n_s_m = null.series_damping_n_s_m;
      break;
  }
  return p;
}

std::vector<double> noise_free_force(const Scenario& s, const std::vector<double>& t_s) {
  return sample_force(simulate(s, Channels::force_only), t_s, s.effects.force_delay_s);
}

double effect_to_noise_ratio(const std::vector<double>& a, const std::vector<double>& b, double noise_rms) {
  double ss = 0.0;
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k) ss += (a[k] - b[k]) * (a[k] - b[k]);
  return a.empty() ? 0.0 : std::sqrt(ss / static_cast<double>(a.size())) / noise_rms;
}

Case generate(const Spec& spec) {
  for (std::size_t i = 0; i < spec.effects.size(); ++i) {
    for (std::size_t j = i + 1; j < spec.effects.size(); ++j) {
      if (spec.effects[i] == spec.effects[j]) throw std::invalid_argument("indep::generate: an effect listed twice");
    }
  }
  Rng rng(spec.seed);
  Case c;
  c.effects = spec.effects;

  Scenario sc;
  sc.duration_s = spec.duration_s;
  sc.rate_hz = spec.rate_hz;
  sc.oversample = spec.oversample;
  std::string motion_text, current_text;
  sc.motion = draw_motion(rng, spec.duration_s, motion_text, c.motion_form);
  const bool must_vary =
      std::find(spec.effects.begin(), spec.effects.end(), Effect::coil_lag) != spec.effects.end();
  sc.current = draw_current(rng, spec.duration_s, must_vary, current_text);
  c.sensors = draw_sensors(rng, c.noise_form, c.quantization_form);
  const SensorModel& sm = c.sensors;

  // Sampling instants and the force noise.
  const auto n = static_cast<std::size_t>(std::llround(spec.duration_s * spec.rate_hz));
  c.time_s.resize(n);
  std::vector<double> t_true(n), force_noise(n);
  const double phi = sm.force_correlation_s > 0.0 ? std::exp(-1.0 / (spec.rate_hz * sm.force_correlation_s)) : 0.0;
  double ar = sm.force_coloured_n * rng.normal();
  // 1/f: kPinkSections AR(1) sections of equal variance, correlation times 2 ms … 2 s.
  std::array<double, kPinkSections> pink_phi{}, pink{};
  const double pink_sigma = sm.force_pink_n / std::sqrt(static_cast<double>(kPinkSections));
  for (int q = 0; q < kPinkSections; ++q) {
    const double tau = 2e-3 * std::pow(kPinkSlowest_s / 2e-3, static_cast<double>(q) / (kPinkSections - 1));
    pink_phi[q] = std::exp(-1.0 / (spec.rate_hz * tau));
    pink[q] = pink_sigma * rng.normal();
  }
  double ss_noise = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    c.time_s[k] = static_cast<double>(k) / spec.rate_hz;
    const double jitter = std::clamp(rng.normal(), -3.0, 3.0) * sm.timing_jitter_s;
    t_true[k] = std::max(0.0, c.time_s[k] + jitter);
    if (k > 0) ar = phi * ar + std::sqrt(1.0 - phi * phi) * sm.force_coloured_n * rng.normal();
    double pink_sum = 0.0;
    for (int q = 0; q < kPinkSections; ++q) {
      if (k > 0 && sm.force_pink_n > 0.0) {
        pink[q] = pink_phi[q] * pink[q] + std::sqrt(1.0 - pink_phi[q] * pink_phi[q]) * pink_sigma * rng.normal();
      }
      pink_sum += pink[q];
    }
    force_noise[k] = sm.force_white_n * rng.normal() + ar + pink_sum +
                     sm.force_drift_n * (c.time_s[k] / spec.duration_s - 0.5);
    ss_noise += force_noise[k] * force_noise[k];
  }
  c.force_noise_rms_n = std::sqrt(ss_noise / static_cast<double>(n));

  // Forms of the effects, then their sizes.
  std::string effects_text;
  std::vector<Variation> variation(spec.effects.size());
  c.forms.assign(spec.effects.size(), "-");
  for (std::size_t i = 0; i < spec.effects.size(); ++i) {
    Variation& v = variation[i];
    EffectParams& p = sc.effects;
    std::string& form = c.forms[i];
    switch (spec.effects[i]) {
      case Effect::idle_settling:
        // Eq. 5.9 (a lasting deficit 1 − b_PR, recovery rate c_PR(SQ)), or a settled layer
        // remixing fully over its own volume V_r, 0.3–10 L (the records displace 1–30 L).
        if (rng.chance(0.5)) {
          form = "eq5.9";
          effects_text += " idle_settling Eq. 5.9";
        } else {
          form = "full_recovery";
          p.settling_recovery_l = rng.log_uniform(0.3, 10.0);
          effects_text += fmt(" idle_settling full recovery over %.2f L", p.settling_recovery_l);
        }
        break;
      case Effect::backlash: {
        const double kind = rng.uniform();
        if (kind < 1.0 / 3.0) {
          form = "hard";
          effects_text += " backlash hard";
        } else if (kind < 2.0 / 3.0) {
          form = "smooth";
          p.contact_fraction = rng.log_uniform(0.02, 0.2);
          effects_text += fmt(" backlash smooth (contact %.3f of the play)", p.contact_fraction);
        } else {
          // A contact spring deflecting 10–100 % of the play under 100 kN (set_size).
          form = "impact_spring";
          v.ratio = rng.log_uniform(0.1, 1.0);
          p.contact_stiffness_n_m = 1.0;  // marks the form; sized with the play
          effects_text += fmt(" backlash with impact spring (%.2f of the play at 100 kN)", v.ratio);
        }
        break;
      }
      case Effect::gas_spring:
        if (rng.chance(0.5)) p.gas_nonlinearity_per_m2 = rng.uniform(0.0, 80.0);
        // Preload over stiffness V_gas / (γ A_rod): 0.02–0.3 m for 0.14–2 L of gas on an 80 mm rod.
        v.ratio = rng.chance(0.5) ? rng.uniform(0.02, 0.3) : 0.0;
        form = v.ratio > 0.0 ? "preload" : "no_preload";
        effects_text += fmt(" gas_spring eps %.0f/m2, preload/k %.3f m", p.gas_nonlinearity_per_m2, v.ratio);
        break;
      case Effect::time_delay:
        // A pure delay, or the delay behind a first-order anti-alias filter of the acquisition
        // (corner 250–500 Hz at a 1 kHz record: τ 0.3–0.6 ms).
        if (rng.chance(0.5)) {
          form = "pure";
        } else {
          form = "antialias";
          v.filter_s = rng.log_uniform(0.3e-3, 0.6e-3);
          effects_text += fmt(" time_delay behind a %.2f ms anti-alias filter", v.filter_s * 1e3);
        }
        break;
      case Effect::coil_lag:
        p.coil_single_lag = rng.chance(0.5);
        form = p.coil_single_lag ? "one_tau" : "two_tau";
        effects_text += p.coil_single_lag ? " coil_lag one time constant (0.365 s x scale)"
                                          : " coil_lag Eq. 4.5 both time constants x scale";
        break;
      case Effect::thermal_fade:
        p.fade_exponential = rng.chance(0.5);
        v.ratio = rng.log_uniform(0.3, 1.6);
        p.heat_capacity_j_per_k = rng.uniform(50.0e3, 80.0e3);
        if (rng.chance(0.5)) p.cooling_time_s = rng.uniform(60.0, 600.0);
        effects_text += fmt(p.fade_exponential ? " thermal exp (visc/yield %.2f, C %.0f kJ/K, cooling %.0f s)"
                                               : " thermal linear (visc/yield %.2f, C %.0f kJ/K, cooling %.0f s)",
                            v.ratio, p.heat_capacity_j_per_k * 1e-3, p.cooling_time_s);
        form = p.cooling_time_s > 0.0 ? "cooling" : "adiabatic";
        break;
      case Effect::force_offset:
        v.sign = rng.chance(0.5) ? 1.0 : -1.0;
        form = v.sign > 0.0 ? "positive" : "negative";
        break;
      case Effect::direction_asymmetry:
        v.sign = rng.chance(0.5) ? 1.0 : -1.0;
        form = v.sign > 0.0 ? "extension_stronger" : "compression_stronger";
        break;
      case Effect::series_compliance: v.ratio = rng.uniform(0.2e-3, 2.0e-3); break;
      case Effect::tanh_transition:
        p.tanh_velocity_m_s = rng.log_uniform(1e-3, 20e-3);
        effects_text += fmt(" tanh v0 %.1f mm/s", p.tanh_velocity_m_s * 1e3);
        break;
      default: break;
    }
  }
  c.target_enr.assign(spec.effects.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < spec.effects.size(); ++i) {
    const Effect e = spec.effects[i];
    const double target = spec.target_enr > 0.0 ? spec.target_enr : rng.log_uniform(spec.enr_min, kEnrMax);
    const SizeRange r = size_range(e);
    if (r.hi <= 0.0) continue;
    c.target_enr[i] = target;
    Scenario off = sc;
    off.effects = without(sc.effects, e);
    const std::vector<double> f_off = noise_free_force(off, t_true);
    // A gas spring with its preload is sized by its part beyond a constant (the spring's), which
    // a force_offset cannot reproduce; the preload rides along.
    const bool beyond_constant = e == Effect::gas_spring && variation[i].ratio > 0.0;
    auto enr_at = [&](double size) {
      Scenario on = sc;
      set_size(on.effects, e, size, variation[i]);
      std::vector<double> f_on = noise_free_force(on, t_true);
      if (beyond_constant) {
        double mean = 0.0;
        for (std::size_t k = 0; k < n; ++k) mean += (f_on[k] - f_off[k]) / static_cast<double>(n);
        for (double& f : f_on) f -= mean;
      }
      return effect_to_noise_ratio(f_on, f_off, c.force_noise_rms_n);
    };
    // Root of g(u) = ln ENR(e^u) − ln target by regula falsi (Illinois); the ENR grows with the size.
    auto g = [&](double u) { return std::log(std::max(enr_at(std::exp(u)), 1e-300)) - std::log(target); };
    double lo = std::log(r.lo), hi = std::log(r.hi);
    double g_lo = g(lo), g_hi = g(hi);
    double size_log = hi;
    if (g_hi <= 0.0) {
      size_log = hi;
    } else if (g_lo >= 0.0) {
      size_log = lo;
    } else {
      int side = 0;
      for (int it = 0; it < 40; ++it) {
        size_log = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
        const double gm = g(size_log);
        if (std::abs(gm) < 1e-3) break;
        if (gm > 0.0) {
          hi = size_log;
          g_hi = gm;
          if (side == 1) g_lo *= 0.5;
          side = 1;
        } else {
          lo = size_log;
          g_lo = gm;
          if (side == -1) g_hi *= 0.5;
          side = -1;
        }
      }
    }
    set_size(sc.effects, e, std::exp(size_log), variation[i]);
    // The size in the effect's own unit (size_range): SQ, m, N/m, 1/K, s, tau scale - 1, N, a.
    effects_text += std::string("; ").append(effect_name(e)).append(fmt(" size %.4g", std::exp(size_log)));
  }
  c.params = sc.effects;

  // Noise-free truth, its ENR per effect, and the baseline.
  c.clean_force_n = noise_free_force(sc, t_true);
  Scenario base = sc;
  base.effects = EffectParams{};
  c.baseline_force_n = noise_free_force(base, t_true);
  for (const Effect e : spec.effects) {
    Scenario off = sc;
    off.effects = without(sc.effects, e);
    const std::vector<double> f_off = noise_free_force(off, t_true);
    c.enr.push_back(effect_to_noise_ratio(c.clean_force_n, f_off, c.force_noise_rms_n));
    // A gas spring's part beyond a constant: the effect's difference less its mean.
    double beyond = std::numeric_limits<double>::quiet_NaN();
    if (e == Effect::gas_spring && sc.effects.gas_preload_n != 0.0) {
      double mean = 0.0;
      for (std::size_t k = 0; k < n; ++k) mean += (c.clean_force_n[k] - f_off[k]) / static_cast<double>(n);
      std::vector<double> shifted = f_off;
      for (double& f : shifted) f += mean;
      beyond = effect_to_noise_ratio(c.clean_force_n, shifted, c.force_noise_rms_n);
    }
    c.enr_beyond_offset.push_back(beyond);
  }

  // What of a filter-like effect the best pure delay leaves: a grid of delays, then golden section.
  for (const Effect e : spec.effects) {
    double beyond = std::numeric_limits<double>::quiet_NaN();
    if (e == Effect::force_lowpass || e == Effect::series_compliance) {
      Scenario off = sc;
      off.effects = without(sc.effects, e);
      const FineRun raw = simulate(off, Channels::force_only);
      const auto enr_at = [&](double d_s) {
        return effect_to_noise_ratio(c.clean_force_n, sample_force(raw, t_true, off.effects.force_delay_s + d_s),
                                     c.force_noise_rms_n);
      };
      constexpr double kStep_s = 5e-4;
      int best = 0;
      double best_enr = enr_at(0.0);
      for (int g = 1; g <= 200; ++g) {
        const double r = enr_at(g * kStep_s);
        if (r < best_enr) {
          best = g;
          best_enr = r;
        }
      }
      double a = std::max(best - 1, 0) * kStep_s, b = (best + 1) * kStep_s;
      for (int it = 0; it < 30; ++it) {
        const double m1 = a + (b - a) / 3.0, m2 = b - (b - a) / 3.0;
        if (enr_at(m1) < enr_at(m2)) {
          b = m2;
        } else {
          a = m1;
        }
      }
      beyond = std::min(best_enr, enr_at(0.5 * (a + b)));
    }
    c.enr_beyond_delay.push_back(beyond);
  }

  // The record.
  c.displacement_m.resize(n);
  c.current_cmd_a.resize(n);
  c.force_n.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    c.displacement_m[k] = quantize(sc.motion.displacement_m(t_true[k]) + sm.lvdt_noise_m * rng.normal(), sm.disp_quantum_m);
    c.current_cmd_a[k] = sc.current.at(c.time_s[k]);
    c.force_n[k] = quantize(c.clean_force_n[k] + force_noise[k], sm.force_quantum_n);
  }
  c.description = motion_text + "; " + current_text + ";" + effects_text +
                  fmt("; noise %.0f N rms (white %.0f, AR %.0f N", c.force_noise_rms_n, sm.force_white_n,
                      sm.force_coloured_n) +
                  fmt(" %.0f ms, 1/f %.0f N", sm.force_correlation_s * 1e3, sm.force_pink_n) +
                  fmt(", drift %.0f N)", sm.force_drift_n) +
                  fmt(", LVDT %.0f um, jitter %.0f us", sm.lvdt_noise_m * 1e6, sm.timing_jitter_s * 1e6) +
                  (sm.disp_quantum_m > 0.0 ? fmt(", x quantized %.1f um", sm.disp_quantum_m * 1e6) : "") +
                  (sm.force_quantum_n > 0.0 ? fmt(", F quantized %.0f N", sm.force_quantum_n) : "");
  return c;
}

}  // namespace indep
