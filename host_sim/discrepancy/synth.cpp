#include "host_sim/discrepancy/synth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "host_sim/discrepancy/damper_model.hpp"
#include "mrd/units.hpp"

namespace mrd::discrepancy {
namespace {

/// SplitMix64 (Steele, Lea, Flood 2014): small, fast, identical everywhere.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : s_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  /// Standard normal (Box–Muller).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = uniform();
    while (u1 <= 0.0) u1 = uniform();
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * units::kPi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * units::kPi * u2);
  }

 private:
  std::uint64_t s_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

/// Damper velocity limit, Table 3.1 (0.2491 m/s), with a margin.
constexpr double kMaxVelocity_m_s = 0.22;
/// 16-bit channels: load cell ±250 kN (§3.2), LVDT over the 0.5842 m stroke (Table 3.1).
constexpr double kForceLsb_n = 500.0e3 / 65536.0;
constexpr double kDispLsb_m = 0.5842 / 65536.0;
constexpr double kRamp_s = 1.0;
constexpr double kNoiseCorrelation_s = 0.020;
constexpr int kMaxDraws = 50;

/// What the draws are put on: the thesis damper's ranges, or a baseline's
/// (SynthSpec::baseline).
struct SynthScale {
  double amp_lo_m = 0.005, amp_hi_m = 0.040;  ///< sine half range; broadband peak
  double sine_lo_hz = 0.25, sine_hi_hz = 2.0;
  double band_lo_hz = 0.1, band_hi_hz = 2.5;  ///< broadband components
  double v_max_m_s = kMaxVelocity_m_s;
  double i_max_a = 2.5;  ///< constant currents in [0.2, 1] of it, steps in [0.1, 1]
  double force = 1.0;    ///< forces (noise, channel range, offsets) over the thesis damper's
  double length = 1.0;   ///< lengths (LVDT noise and range, free play) over the thesis's
  [[nodiscard]] double force_lsb_n() const { return kForceLsb_n * force; }
  [[nodiscard]] double disp_lsb_m() const { return kDispLsb_m * length; }
};

SynthScale scale_of(const std::optional<Baseline>& b) {
  SynthScale s;
  if (!b) return s;
  const ValidityRange& r = b->range;
  if (r.amplitude_max_m > 0.0) {
    s.amp_hi_m = r.amplitude_max_m;
    s.amp_lo_m = r.amplitude_min_m > 0.0 ? std::min(r.amplitude_min_m, r.amplitude_max_m) : 0.125 * r.amplitude_max_m;
    s.length = r.amplitude_max_m / 0.040;
  }
  if (r.frequency_max_hz > 0.0) {
    s.sine_hi_hz = r.frequency_max_hz;
    s.sine_lo_hz = r.frequency_min_hz > 0.0 ? std::min(r.frequency_min_hz, r.frequency_max_hz) : 0.125 * s.sine_hi_hz;
    s.band_lo_hz = 0.4 * s.sine_lo_hz;
    s.band_hi_hz = s.sine_hi_hz;
  }
  if (r.velocity_max_m_s > 0.0) s.v_max_m_s = 0.9 * r.velocity_max_m_s;
  const double i_max = std::max(std::fabs(r.current_min_a), std::fabs(r.current_max_a));
  if (i_max > 0.0) s.i_max_a = i_max;
  const double f = b->force_scale_n();
  if (f > 0.0 && std::isfinite(f)) s.force = f / thesis_force_scale_n();
  return s;
}

struct Motion {
  std::vector<double> x, v;
  std::string description;
};

/// Half-cosine ramp at both ends so the actuator starts and ends at rest.
void taper(const std::vector<double>& t, std::vector<double>& x, std::vector<double>& v) {
  const double t0 = t.front();
  const double t1 = t.back();
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double a = t[k] - t0;
    const double b = t1 - t[k];
    double w = 1.0, dw = 0.0;
    if (a < kRamp_s) {
      w = 0.5 * (1.0 - std::cos(units::kPi * a / kRamp_s));
      dw = 0.5 * units::kPi / kRamp_s * std::sin(units::kPi * a / kRamp_s);
    } else if (b < kRamp_s) {
      w = 0.5 * (1.0 - std::cos(units::kPi * b / kRamp_s));
      dw = -0.5 * units::kPi / kRamp_s * std::sin(units::kPi * b / kRamp_s);
    }
    v[k] = dw * x[k] + w * v[k];
    x[k] *= w;
  }
}

Motion make_motion(SynthInput kind, const std::vector<double>& t, Rng& rng, const SynthScale& sc) {
  Motion m;
  const std::size_t n = t.size();
  m.x.assign(n, 0.0);
  m.v.assign(n, 0.0);
  char buf[160];
  if (kind == SynthInput::sine) {
    const double amp = rng.uniform(sc.amp_lo_m, sc.amp_hi_m);
    double f = rng.uniform(sc.sine_lo_hz, sc.sine_hi_hz);
    f = std::min(f, sc.v_max_m_s / (2.0 * units::kPi * amp));
    const double ph = rng.uniform(0.0, 2.0 * units::kPi);
    const double w = 2.0 * units::kPi * f;
    for (std::size_t k = 0; k < n; ++k) {
      m.x[k] = amp * std::sin(w * t[k] + ph);
      m.v[k] = amp * w * std::cos(w * t[k] + ph);
    }
    std::snprintf(buf, sizeof buf, "sine %.*f mm, %.3f Hz", amp < 0.005 ? 2 : 1, amp * 1e3, f);
  } else {
    constexpr int kComponents = 12;
    for (int c = 0; c < kComponents; ++c) {
      const double f = rng.uniform(sc.band_lo_hz, sc.band_hi_hz);
      const double a = rng.uniform(0.5, 1.0) / f;
      const double ph = rng.uniform(0.0, 2.0 * units::kPi);
      const double w = 2.0 * units::kPi * f;
      for (std::size_t k = 0; k < n; ++k) {
        m.x[k] += a * std::sin(w * t[k] + ph);
        m.v[k] += a * w * std::cos(w * t[k] + ph);
      }
    }
    double xmax = 0.0;
    for (const double x : m.x) xmax = std::max(xmax, std::fabs(x));
    const double target = rng.uniform(0.25 * sc.amp_hi_m, sc.amp_hi_m);
    double scale = target / xmax;
    double vmax = 0.0;
    for (const double v : m.v) vmax = std::max(vmax, std::fabs(v * scale));
    if (vmax > sc.v_max_m_s) scale *= sc.v_max_m_s / vmax;
    for (std::size_t k = 0; k < n; ++k) {
      m.x[k] *= scale;
      m.v[k] *= scale;
    }
    std::snprintf(buf, sizeof buf, "broadband %.3g-%.3g Hz, peak %.*f mm", sc.band_lo_hz, sc.band_hi_hz,
                  target < 0.005 ? 2 : 1, target * 1e3 * std::min(1.0, scale * xmax / target));
  }
  taper(t, m.x, m.v);
  m.description = buf;
  return m;
}

std::vector<double> make_current(SynthCurrent kind, const std::vector<double>& t, Rng& rng, std::string& description,
                                 const SynthScale& sc) {
  std::vector<double> i(t.size());
  char buf[120];
  if (kind == SynthCurrent::constant) {
    const double level = rng.uniform(0.2 * sc.i_max_a, sc.i_max_a);
    std::fill(i.begin(), i.end(), level);
    std::snprintf(buf, sizeof buf, "constant %.2f A", level);
  } else {
    double next_change = t.front();
    double level = 0.0;
    int steps = 0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      if (t[k] >= next_change) {
        level = rng.uniform(0.1 * sc.i_max_a, sc.i_max_a);
        next_change = t[k] + rng.uniform(2.0, 6.0);
        ++steps;
      }
      i[k] = level;
    }
    std::snprintf(buf, sizeof buf, "%d steps of 2-6 s, %.3g-%.3g A", steps, 0.1 * sc.i_max_a, sc.i_max_a);
  }
  description = buf;
  return i;
}

double quantize(double v, double lsb) { return lsb * std::round(v / lsb); }

/// Sample times k / rate, each after the first moved by up to ±jitter/2 of a step.
std::vector<double> sample_times(const SynthSpec& spec, Rng& rng) {
  const double dt = 1.0 / spec.rate_hz;
  const auto n = static_cast<std::size_t>(std::floor(spec.duration_s * spec.rate_hz)) + 1;
  std::vector<double> t(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double j = spec.jitter > 0.0 ? (rng.uniform() - 0.5) * spec.jitter : 0.0;
    t[k] = (static_cast<double>(k) + (k == 0 ? 0.0 : j)) * dt;
  }
  return t;
}

/// Parameters of every effect of `set` drawn from synth_range (and the sign
/// of a force offset), packed in its order.
std::vector<double> draw_params(const EffectSet& set, Rng& rng, const SynthScale& sc) {
  std::vector<double> params;
  for (const Effect e : set.effects) {
    for (std::size_t p = 0; p < effect_info(e).params.size(); ++p) {
      const auto [lo, hi] = synth_range(e, p);
      if (lo == hi) {  // held, and no draw: the other parameters' draws stay as they were
        params.push_back(lo);
        continue;
      }
      double v = rng.uniform(lo, hi);
      if ((e == Effect::force_offset || e == Effect::direction_asymmetry) && rng.uniform() < 0.5) v = -v;
      // The thesis damper's ranges put on the baseline's damper: forces,
      // stiffnesses (force over length) and lengths scale with it.
      if (e == Effect::force_offset) v *= sc.force;
      if (e == Effect::gas_spring) v *= sc.force / sc.length;
      if ((e == Effect::backlash && p == 0) || e == Effect::preyield_hysteresis) v *= sc.length;
      params.push_back(v);
    }
  }
  return params;
}

/// RMS change of the force each effect of `set` causes: `f_true` against the
/// same model without the effect, the other effects' parameters kept, N.
std::vector<double> effect_rms_n(const DamperModel& truth, const EffectSet& set, const std::vector<double>& params,
                                 const std::vector<double>& f_true, ModelWorkspace& ws) {
  const std::size_t n = f_true.size();
  std::vector<double> f_without;
  std::vector<double> effect_rms;
  for (const Effect e : set.effects) {
    EffectSet without;
    std::vector<double> p_without;
    for (const Effect x : set.effects) {
      if (x == e) continue;
      without.effects.push_back(x);
      const auto off = *set.offset(x);
      for (std::size_t p = 0; p < effect_info(x).params.size(); ++p) p_without.push_back(params[off + p]);
    }
    truth.simulate(without, p_without, ws, f_without);
    double ss = 0.0;
    for (std::size_t k = 0; k < n; ++k) ss += (f_true[k] - f_without[k]) * (f_true[k] - f_without[k]);
    effect_rms.push_back(std::sqrt(ss / static_cast<double>(n)));
  }
  return effect_rms;
}

/// Sensor noise of one draw.
struct Noise {
  double white_n = 0.0;    ///< white load-cell noise, RMS, N
  double colored_n = 0.0;  ///< correlated (kNoiseCorrelation_s) load-cell noise, RMS, N
  double disp_m = 0.0;     ///< LVDT noise, RMS, m
};

/// The record as the sensors give it: the true force and motion with
/// `noise`, quantized to 16 bits, and a velocity column when asked for.
MeasuredData measure(const SynthSpec& spec, const std::vector<double>& t, const Motion& m,
                     const std::vector<double>& i_cmd, const std::vector<double>& f_true, const Noise& noise,
                     Rng& rng, const SynthScale& sc) {
  const std::size_t n = t.size();
  MeasuredData d;
  char label[64];
  std::snprintf(label, sizeof label, "synth-seed-%llu", static_cast<unsigned long long>(spec.seed));
  d.source = label;
  d.time_s = t;
  d.current_cmd_a = i_cmd;
  d.displacement_m.resize(n);
  d.force_n.resize(n);
  const double a_c = std::exp(-(1.0 / spec.rate_hz) / kNoiseCorrelation_s);
  const double innov = noise.colored_n * std::sqrt(1.0 - a_c * a_c);
  double colored = noise.colored_n * rng.normal();
  for (std::size_t k = 0; k < n; ++k) {
    colored = a_c * colored + innov * rng.normal();
    d.force_n[k] = quantize(f_true[k] + noise.white_n * rng.normal() + colored, sc.force_lsb_n());
    d.displacement_m[k] = quantize(m.x[k] + noise.disp_m * rng.normal(), sc.disp_lsb_m());
  }
  if (spec.velocity_column) {
    d.velocity_m_s.resize(n);
    const double v_noise_m_s = 0.5e-3 * (sc.v_max_m_s / kMaxVelocity_m_s);
    for (std::size_t k = 0; k < n; ++k) d.velocity_m_s[k] = m.v[k] + v_noise_m_s * rng.normal();
  }
  return d;
}

}  // namespace

std::pair<double, double> synth_range(Effect e, std::size_t i) {
  switch (e) {
    case Effect::idle_settling: return {0.1, 1.0};        // SQ: ~0.04 years idle to fully settled
    // Total free play, m; hard stops (a contact share of 0: the independent
    // study's generator draws compliant ones).
    case Effect::backlash: return i == 0 ? std::pair{0.0006, 0.004} : std::pair{0.0, 0.0};
    case Effect::gas_spring: return {0.15e6, 1.5e6};      // N/m
    case Effect::thermal_fade: return i == 0 ? std::pair{0.008, 0.02} : std::pair{0.02, 0.05};  // 1/K
    case Effect::time_delay: return {0.004, 0.030};       // s
    case Effect::coil_lag: return {1.8, 5.0};             // × Eq. 4.5 time constants
    case Effect::force_offset: return {2.0e3, 8.0e3};     // |offset|, N (sign drawn)
    case Effect::direction_asymmetry: return {0.08, 0.3};  // |a| (sign drawn)
    case Effect::preyield_hysteresis: return {0.0005, 0.004};  // x_y, m
  }
  return {0.0, 0.0};
}

std::vector<Effect> random_effects(std::uint64_t seed) {
  std::uint64_t h = seed * 0x9E3779B97F4A7C15ull + 7u;
  const auto draw = [&h](std::size_t n) {
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    return static_cast<std::size_t>(h % n);
  };
  const std::size_t count = draw(3);
  std::vector<Effect> effects;
  while (effects.size() < count) {
    const Effect e = kAllEffects[draw(kEffectCount)];
    if (std::find(effects.begin(), effects.end(), e) == effects.end()) effects.push_back(e);
  }
  return effects;
}

SynthCase synthesize(const SynthSpec& spec) {
  if (!(spec.duration_s >= 2.0)) throw std::invalid_argument("synthesize: duration below 2 s");
  if (!(spec.rate_hz >= 50.0)) throw std::invalid_argument("synthesize: rate below 50 Hz");
  if (!(spec.jitter >= 0.0 && spec.jitter < 1.0)) throw std::invalid_argument("synthesize: jitter outside [0, 1)");
  const EffectSet set{spec.effects};
  if (!spec.params.empty() && spec.params.size() != set.param_count()) {
    throw std::invalid_argument("synthesize: params do not match the effects");
  }
  Rng rng(spec.seed * 0x2545F4914F6CDD1Dull + 12345u);
  const std::vector<double> t = sample_times(spec, rng);

  const SynthScale sc = scale_of(spec.baseline);
  SynthCase out;
  for (int draw = 1; draw <= kMaxDraws; ++draw) {
    const SynthInput input =
        spec.input != SynthInput::random ? spec.input : (rng.uniform() < 0.5 ? SynthInput::sine : SynthInput::broadband);
    SynthCurrent cur = spec.current;
    if (cur == SynthCurrent::random) {
      // A current that never changes hides coil_lag: the generator then steps it.
      cur = set.contains(Effect::coil_lag) || rng.uniform() < 0.65 ? SynthCurrent::steps : SynthCurrent::constant;
    }
    Motion m = make_motion(input, t, rng, sc);
    std::string cur_desc;
    std::vector<double> i_cmd = make_current(cur, t, rng, cur_desc, sc);
    const std::vector<double> params = spec.params.empty() ? draw_params(set, rng, sc) : spec.params;
    Noise noise;
    noise.white_n = spec.force_noise_n >= 0.0 ? spec.force_noise_n : sc.force * rng.uniform(200.0, 1000.0);
    noise.colored_n = spec.force_noise_n >= 0.0 ? 0.0 : sc.force * rng.uniform(100.0, 500.0);
    noise.disp_m = spec.disp_noise_m >= 0.0 ? spec.disp_noise_m : sc.length * rng.uniform(5e-6, 20e-6);
    const double noise_rms = std::hypot(noise.white_n, noise.colored_n);

    // |ā| is filled by the model when the baseline's transition time needs it.
    const ModelInput input_of_truth{t, m.x, m.v, i_cmd, false, {}, {}};
    const DamperModel truth = spec.baseline ? DamperModel(input_of_truth, *spec.baseline) : DamperModel(input_of_truth);
    ModelWorkspace ws;
    std::vector<double> f_true, f_base;
    truth.simulate(set, params, ws, f_true);
    truth.simulate(EffectSet{}, {}, ws, f_base);
    const std::vector<double> effect_rms = effect_rms_n(truth, set, params, f_true, ws);
    const bool visible = std::all_of(effect_rms.begin(), effect_rms.end(),
                                     [&](double rms) { return !(rms < spec.min_effect_to_noise * noise_rms); });
    const bool last = draw == kMaxDraws;
    if (!visible && spec.params.empty() && !last) continue;

    out.effects = spec.effects;
    out.params = params;
    out.input_description = m.description;
    out.current_description = cur_desc;
    out.force_noise_rms_n = noise_rms;
    out.disp_noise_m = noise.disp_m;
    out.effect_rms_n = effect_rms;
    out.true_gap = normalized_rms_gap(f_true, f_base);
    out.draws = draw;
    out.data = measure(spec, t, m, i_cmd, f_true, noise, rng, sc);
    break;
  }
  return out;
}

}  // namespace mrd::discrepancy
