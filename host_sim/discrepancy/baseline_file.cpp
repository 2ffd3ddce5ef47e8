#include "host_sim/discrepancy/baseline_file.hpp"

#include <algorithm>
#include <cmath>

#include "host_sim/discrepancy/physical_ranges.hpp"
#include "host_sim/discrepancy/toml_fields.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/report/output_dir.hpp"

namespace mrd::discrepancy {
namespace {

// ---- writing ---------------------------------------------------------------

std::string num(double v) { return toml_number(v); }

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string fitted_list(const CurrentLawFitted& f) {
  std::string s = "[";
  const auto add = [&](bool on, const char* name) {
    if (!on) return;
    if (s.size() > 1) s += ", ";
    s += quoted(name);
  };
  add(f.at_zero, "at_zero");
  add(f.limit, "limit");
  add(f.rate_per_a, "rate_per_a");
  return s + "]";
}

/// "key = sigma": a standard error within the range of its quantity's
/// standard errors (sigma_range); a larger one (a parameter the records do
/// not identify, or an infinite one) is written as that range's top with a
/// comment that says so, so that the file reads back.
std::string sigma_line(const std::string& key, double sigma, const PhysicalRange& quantity) {
  const double top = sigma_range(quantity).max;
  if (sigma <= top) return key + " = " + num(sigma) + "\n";
  return key + " = " + num(top) + "  # the fit's standard error, " + num(sigma) +
         ", exceeds the quantity's range: not identified\n";
}

void law_table(std::string& t, const char* name, const char* comment, const CurrentLaw& v, const CurrentLaw& s,
               const CurrentLawFitted& f, const PhysicalRange& value_range) {
  t += std::string("\n[") + name + "]  # " + comment + "\n";
  t += "at_zero = " + num(v.at_zero) + "\n";
  t += sigma_line("at_zero_sigma", s.at_zero, value_range);
  t += "limit = " + num(v.limit) + "\n";
  t += sigma_line("limit_sigma", s.limit, value_range);
  t += "rate_per_a = " + num(v.rate_per_a) + "\n";
  t += sigma_line("rate_per_a_sigma", s.rate_per_a, kCurrentRateRange);
  if (v.current_exponent != 1.0) {
    t += "current_exponent = " + num(v.current_exponent) + "  # q: exp(-rate_per_a |I|^q)\n";
    t += sigma_line("current_exponent_sigma", s.current_exponent, kCurrentExponentRange);
  }
  t += "fitted = " + fitted_list(f) + "  # the others are held (sigma 0)\n";
}

/// [spencer]: Spencer et al. (1997)'s model and its current laws (physics/spencer_law.hpp).
void spencer_table(std::string& t, const physics::SpencerParams& p) {
  t += "\n[spencer]  # Spencer et al. (1997): F = c1 y' + k1 (x - x0), Eq. (8)-(10); |I| in A\n";
  t += "alpha_n_m = " + num(p.alpha_n_m) + "  # alpha(I) = alpha_n_m + alpha_per_a_n_m |I| + alpha_per_a2_n_m I^2\n";
  t += "alpha_per_a_n_m = " + num(p.alpha_per_a_n_m) + "\n";
  t += "alpha_per_a2_n_m = " + num(p.alpha_per_a2_n_m) + "\n";
  t += "c0_ns_m = " + num(p.c0_ns_m) + "  # c0(I) = c0_ns_m + c0_per_a_ns_m |I|\n";
  t += "c0_per_a_ns_m = " + num(p.c0_per_a_ns_m) + "\n";
  t += "c1_ns_m = " + num(p.c1_ns_m) + "  # c1(I) = c1_ns_m + c1_per_a_ns_m |I|\n";
  t += "c1_per_a_ns_m = " + num(p.c1_per_a_ns_m) + "\n";
  t += "gamma_per_m_pow_n = " + num(p.gamma_per_m_pow_n) + "  # gamma(I) = gamma_per_m_pow_n exp(-gamma_rate_per_a |I|)\n";
  t += "gamma_rate_per_a = " + num(p.gamma_rate_per_a) + "\n";
  t += "beta_over_gamma = " + num(p.beta_over_gamma) + "\n";
  t += "a = " + num(p.a) + "  # A, dimensionless (z is a length)\n";
  t += "n = " + num(p.n) + "\n";
  t += "k0_n_m = " + num(p.k0_n_m) + "\n";
  t += "k1_n_m = " + num(p.k1_n_m) + "\n";
  t += "x0_m = " + num(p.x0_m) + "\n";
}

// ---- reading ---------------------------------------------------------------

using Table = TomlTable;

[[noreturn]] void fail(const std::string& origin, const toml::source_region& where, const std::string& field,
                       const std::string& problem) {
  fail_at(origin, where, field, problem);
}

const toml::table& table_of(const toml::table& root, const char* name, const std::string& origin) {
  return required_table(root, name, origin);
}

BaseLaw law_named(const std::string& s, const std::string& origin, const toml::source_region& where,
                  const std::string& field) {
  if (s == "bingham") return BaseLaw::bingham;
  if (s == "bouc_wen") return BaseLaw::bouc_wen;
  if (s == "spencer") return BaseLaw::spencer;
  fail(origin, where, field, "expected \"bingham\", \"bouc_wen\" or \"spencer\", got \"" + s + "\"");
}

/// The `transition` key of table `t`: true for "tanh", false for "linear".
bool transition_named(Table& t, const std::string& origin, const std::string& field) {
  const std::string s = t.string("transition");
  if (s == "tanh") return true;
  if (s == "linear") return false;
  fail(origin, t.where("transition"), field, "expected \"linear\" or \"tanh\", got \"" + s + "\"");
}

/// The `expected_gap_basis` key of table `t` (absent in files written before
/// it: the calibration records).
GapBasis gap_basis_named(Table& t, const std::string& origin) {
  const std::string s = t.string("expected_gap_basis");
  for (const GapBasis b : {GapBasis::calibration_records, GapBasis::check_records, GapBasis::left_out_motions})
    if (s == gap_basis_name(b)) return b;
  fail(origin, t.where("expected_gap_basis"), t.field("expected_gap_basis"),
       "expected \"calibration_records\", \"check_records\" or \"left_out_motions\", got \"" + s + "\"");
}

/// The standard error `key` of a quantity of range `r`: 0 when absent (a
/// value written by hand, not fitted).
double sigma_of(Table& t, const char* key, const PhysicalRange& r) {
  return t.optional_in(key, sigma_range(r)).value_or(0.0);
}

void read_law(const toml::table& root, const char* name, const std::string& origin, CurrentLaw& v, CurrentLaw& s,
              CurrentLawFitted& f, const PhysicalRange& value_range) {
  Table t(table_of(root, name, origin), name, origin);
  v.at_zero = t.in("at_zero", value_range);
  s.at_zero = sigma_of(t, "at_zero_sigma", value_range);
  v.limit = t.in("limit", value_range);
  s.limit = sigma_of(t, "limit_sigma", value_range);
  v.rate_per_a = t.in("rate_per_a", kCurrentRateRange);
  s.rate_per_a = sigma_of(t, "rate_per_a_sigma", kCurrentRateRange);
  if (t.has("current_exponent")) {
    v.current_exponent = t.in("current_exponent", kCurrentExponentRange);
    s.current_exponent = sigma_of(t, "current_exponent_sigma", kCurrentExponentRange);
  }
  f = {false, false, false};
  const std::vector<std::string> fitted = t.has("fitted") ? t.strings("fitted") : std::vector<std::string>{};
  for (const std::string& p : fitted) {
    if (p == "at_zero") {
      f.at_zero = true;
    } else if (p == "limit") {
      f.limit = true;
    } else if (p == "rate_per_a") {
      f.rate_per_a = true;
    } else {
      fail(origin, t.where("fitted"), t.field("fitted"), "expected at_zero, limit or rate_per_a, got \"" + p + "\"");
    }
  }
  t.no_unknown_keys();
}

/// [coil]'s optional circuit: R, and L at 1 A and 2 A together (the
/// inductance falls as the iron saturates: L(2 A) <= L(1 A)); its heating:
/// R_th only with R (the rise is i² R R_th: without R the thesis coil's
/// 4.8 ohm would be taken for this coil's), τ alone.
void read_coil_circuit(Table& c, CoilCircuit& circuit) {
  circuit.resistance_ohm = c.optional_in("resistance_ohm", kCoilResistanceRange);
  circuit.inductance_1a_h = c.optional_in("inductance_1a_h", kCoilInductanceRange);
  circuit.inductance_2a_h = c.optional_in("inductance_2a_h", kCoilInductanceRange);
  circuit.thermal_resistance_k_w = c.optional_in("thermal_resistance_k_w", kCoilThermalResistanceRange);
  circuit.thermal_time_constant_s = c.optional_in("thermal_time_constant_s", kCoilThermalTimeConstantRange);
  if (circuit.thermal_resistance_k_w && !circuit.resistance_ohm)
    c.refuse("resistance_ohm", "missing key (thermal_resistance_k_w needs it: the coil heats by i^2 R, and R_th "
                               "is for this coil's R)");
  if (circuit.inductance_1a_h && !circuit.inductance_2a_h)
    c.refuse("inductance_2a_h", "missing key (inductance_1a_h needs it: L(i) is set by the two)");
  if (circuit.inductance_2a_h && !circuit.inductance_1a_h)
    c.refuse("inductance_1a_h", "missing key (inductance_2a_h needs it: L(i) is set by the two)");
  if (circuit.inductance_1a_h && *circuit.inductance_2a_h > *circuit.inductance_1a_h)
    c.refuse("inductance_2a_h", "expected at most inductance_1a_h (" + num(*circuit.inductance_1a_h) +
                                    " H): the iron saturates, the inductance does not grow with the current");
}

/// [spencer]; its laws' signs are checked against the current range once
/// [validity] is read (check_spencer_laws).
physics::SpencerParams read_spencer(const toml::table& root, const std::string& origin) {
  Table t(table_of(root, "spencer", origin), "spencer", origin);
  physics::SpencerParams p;
  p.alpha_n_m = t.in("alpha_n_m", kStiffnessRange);
  p.alpha_per_a_n_m = t.in("alpha_per_a_n_m", kSpencerAlphaSlopeRange);
  p.alpha_per_a2_n_m = t.in("alpha_per_a2_n_m", kSpencerAlphaSlopeRange);
  p.c0_ns_m = t.in("c0_ns_m", kViscousRange);
  p.c0_per_a_ns_m = t.in("c0_per_a_ns_m", kSpencerViscousSlopeRange);
  p.c1_ns_m = t.in("c1_ns_m", kViscousRange);
  p.c1_per_a_ns_m = t.in("c1_per_a_ns_m", kSpencerViscousSlopeRange);
  p.gamma_per_m_pow_n = t.in("gamma_per_m_pow_n", kSpencerGammaRange);
  p.gamma_rate_per_a = t.in("gamma_rate_per_a", kCurrentRateRange);
  p.beta_over_gamma = t.in("beta_over_gamma", kSpencerBetaRatioRange);
  p.a = t.in("a", kSpencerARange);
  p.n = t.in("n", kSpencerExponentRange);
  p.k0_n_m = t.in("k0_n_m", kStiffnessRange);
  p.k1_n_m = t.in("k1_n_m", kStiffnessRange);
  p.x0_m = t.in("x0_m", kSpencerRestStrokeRange);
  t.no_unknown_keys();
  return p;
}

/// α, c_0 and c_1 of [spencer] at 0 A and at the largest current of
/// [validity] (a quadratic α also at its vertex when inside): α and c_0 not
/// negative, c_1 positive (ẏ divides by c_0 + c_1).
void check_spencer_laws(const toml::table& root, const physics::SpencerParams& p, const ValidityRange& v,
                        const std::string& origin) {
  Table t(table_of(root, "spencer", origin), "spencer", origin);
  const double top = std::max(std::fabs(v.current_min_a), std::fabs(v.current_max_a));
  std::vector<double> at{0.0, top};
  if (p.alpha_per_a2_n_m != 0.0) {
    const double vertex = -p.alpha_per_a_n_m / (2.0 * p.alpha_per_a2_n_m);
    if (vertex > 0.0 && vertex < top) at.push_back(vertex);
  }
  for (const double i : at) {
    const std::string where = " at " + num(i) + " A (the [validity] current range reaches " + num(top) + " A)";
    if (p.alpha_at(i) < 0.0)
      t.refuse(i == 0.0 ? "alpha_n_m" : "alpha_per_a_n_m", "alpha(I) = " + num(p.alpha_at(i)) + " N/m" + where +
                                                                ": expected a stiffness of at least 0");
    if (p.c0_at(i) < 0.0)
      t.refuse("c0_per_a_ns_m", "c0(I) = " + num(p.c0_at(i)) + " N s/m" + where + ": expected at least 0");
    if (!(p.c1_at(i) > 0.0))
      t.refuse("c1_per_a_ns_m", "c1(I) = " + num(p.c1_at(i)) + " N s/m" + where + ": expected more than 0");
  }
}

physics::DamperRating read_rating(const toml::table& table, const std::string& origin) {
  Table t(table, "rating", origin);
  physics::DamperRating r;
  r.current_a = t.in("current_a", kRatedCurrentRange);
  r.force_n = t.in("force_n", kRatedForceRange);
  r.stroke_m = t.in("stroke_m", kRatedStrokeRange);
  r.velocity_m_s = t.in("velocity_m_s", kRatedVelocityRange);
  t.no_unknown_keys();
  return r;
}

DamperGeometry read_geometry(const toml::table& table, const std::string& origin) {
  Table t(table, "geometry", origin);
  DamperGeometry g;
  g.inner_diameter_m = t.in("inner_diameter_m", kBoreDiameterRange);
  g.shaft_radius_m = t.in("shaft_radius_m", kShaftRadiusRange);
  g.fluid_length_m = t.in("fluid_length_m", kFluidLengthRange);
  g.fluid_volume_m3 = t.in("fluid_volume_m3", kFluidVolumeRange);
  if (!(g.shaft_radius_m < 0.5 * g.inner_diameter_m))
    t.refuse("shaft_radius_m", "expected less than half inner_diameter_m (" + num(0.5 * g.inner_diameter_m) +
                                   " m): the shaft runs inside the bore");
  t.no_unknown_keys();
  return g;
}

}  // namespace

BaselineFile baseline_file_of(const CalibrationResult& r) {
  BaselineFile f;
  const LawFit& best = r.best();
  f.baseline = best.baseline;
  f.sigma = best.sigma;
  f.yield_fitted = best.yield_fitted;
  f.viscous_fitted = best.viscous_fitted;
  f.source_records = r.sources;
  for (const LawFit& fit : r.fits) {
    for (std::size_t i = 0; i < r.sources.size(); ++i)
      f.fits.push_back({r.sources[i], fit.baseline.law, fit.record_gaps.at(i), r.record_samples.at(i),
                        fit.baseline.has_lost_motion(), fit.baseline.has_transition_time(),
                        fit.baseline.has_tanh_transition(), fit.baseline.has_viscous_lost_motion()});
  }
  return f;
}

std::string baseline_toml(const BaselineFile& f) {
  const Baseline& b = f.baseline;
  const ValidityRange& v = b.range;
  std::string t;
  t += "# Damper baseline for `mrd discrepancy --baseline` (written by `mrd calibrate`). SI units.\n";
  t += "\n[model]\n";
  t += "law = " + quoted(base_law_name(b.law)) + "  # bingham: Eq. 4.1-4.4; bouc_wen: Spencer et al. (1997), normalized\n";
  t += "name = " + quoted(b.name) + "\n";
  t += "source_records = [";
  for (std::size_t i = 0; i < f.source_records.size(); ++i) t += (i ? ", " : "") + quoted(f.source_records[i]);
  t += "]\n";
  if (b.law != BaseLaw::spencer) {
    law_table(t, "yield_n", "Y(I) = limit + (at_zero - limit) exp(-rate_per_a |I|), N (Eq. 4.2)", b.yield_n,
              f.sigma.yield_n, f.yield_fitted, kYieldForceRange);
    law_table(t, "viscous_ns_m", "C(I), the same law, N s/m (Eq. 4.3)", b.viscous_ns_m, f.sigma.viscous_ns_m,
              f.viscous_fitted, kViscousRange);
  }
  if (b.law == BaseLaw::spencer) {
    spencer_table(t, b.spencer);
  } else if (b.law == BaseLaw::bingham) {
    t += std::string("\n[bingham]  # transition function, ") + (b.has_tanh_transition() ? "tanh" : "Eq. 4.4") + "\n";
    t += "v_tf_m_s = " + num(b.v_tf_m_s) + "\n";
    t += sigma_line("v_tf_m_s_sigma", f.sigma.v_tf_m_s, kVelocityBandRange);
    if (b.has_tanh_transition()) t += "transition = \"tanh\"  # F = Y tanh(v / v_tf_m_s) + C v\n";
    if (b.has_transition_time()) {
      t += "transition_time_s = " + num(b.transition_time_s) + "  # the band is v_tf_m_s + transition_time_s |a|\n";
      t += sigma_line("transition_time_s_sigma", f.sigma.transition_time_s, kTransitionTimeRange);
    }
    if (b.has_bingham_stiffness()) {
      t += "stiffness_n_m = " + num(b.stiffness_n_m) + "  # a spring k x beside the law (the accumulator)\n";
      t += sigma_line("stiffness_n_m_sigma", f.sigma.stiffness_n_m, kStiffnessRange);
    }
    if (b.has_viscous_exponent()) {
      t += "viscous_exponent = " + num(b.viscous_exponent) +
           "  # the viscous force C v_r (|v| / v_r)^m sgn v, m this exponent\n";
      t += sigma_line("viscous_exponent_sigma", f.sigma.viscous_exponent, kViscousExponentRange);
      t += "viscous_ref_m_s = " + num(b.viscous_ref_m_s) + "  # v_r: C is the force per velocity there\n";
    }
    if (b.has_series_compliance()) {
      t += "series_compliance_m_per_n = " + num(b.series_compliance_m_per_n) +
           "  # 1/k_s: the law acts on the fluid's velocity v - dF/dt / k_s\n";
      t += sigma_line("series_compliance_m_per_n_sigma", f.sigma.series_compliance_m_per_n, kSeriesComplianceRange);
    }
  } else {
    t += "\n[bouc_wen]  # F = Y z + C v + k0 x, z' = (v/x_y)(1 - |z|^2 (1/2 + 1/2 sgn(v z)))\n";
    t += "yield_disp_m = " + num(b.yield_disp_m) + "\n";
    t += sigma_line("yield_disp_m_sigma", f.sigma.yield_disp_m, kYieldDispRange);
    t += "stiffness_n_m = " + num(b.stiffness_n_m) + "\n";
    t += sigma_line("stiffness_n_m_sigma", f.sigma.stiffness_n_m, kStiffnessRange);
  }
  if (b.has_lost_motion()) {
    t += "\n[lost_motion]  # F = F_law ((1 - share) + share e) + (1 - e) Y(I) tanh(v / band_m_s), e: play of width "
         "m_per_n Y(I) at reversals\n";
    t += "m_per_n = " + num(b.lost_motion_m_per_n) + "\n";
    t += sigma_line("m_per_n_sigma", f.sigma.lost_motion_m_per_n, kPlayRange);
    t += "share = " + num(b.lost_motion_share) + "\n";
    t += sigma_line("share_sigma", f.sigma.lost_motion_share, kShareRange);
    if (b.has_viscous_lost_motion()) {
      t += "band_m_s = " + num(b.lost_motion_band_m_s) + "  # the force inside the play\n";
      t += sigma_line("band_m_s_sigma", f.sigma.lost_motion_band_m_s, kVelocityBandRange);
    }
  }
  t += "\n[channels]  # the force channel's lag behind the motion channels\n";
  t += "force_delay_s = " + num(b.force_delay_s) + "\n";
  t += sigma_line("force_delay_s_sigma", f.sigma.force_delay_s, kForceDelayRange);
  t += "\n[coil]  # Eq. 4.5";
  t += b.coil_identified ? ", fitted to the records whose current changes\n"
                         : ": assumed (thesis values), not identified from the records\n";
  t += "tau_slow_s = " + num(b.coil.tau_slow_s) + "\n";
  if (b.coil_identified) t += sigma_line("tau_slow_s_sigma", f.sigma.coil_tau_slow_s, kCoilTimeConstantRange);
  t += "tau_fast_s = " + num(b.coil.tau_fast_s) + "\n";
  if (b.coil_identified) t += sigma_line("tau_fast_s_sigma", f.sigma.coil_tau_fast_s, kCoilTimeConstantRange);
  t += "weight_slow = " + num(b.coil.weight_slow) + "\n";
  t += "weight_fast = " + num(b.coil.weight_fast) + "\n";
  t += std::string("identified = ") + (b.coil_identified ? "true" : "false") + "\n";
  const CoilCircuit& cc = f.coil_circuit;
  if (cc.resistance_ohm) t += "resistance_ohm = " + num(*cc.resistance_ohm) + "\n";
  if (cc.inductance_1a_h) t += "inductance_1a_h = " + num(*cc.inductance_1a_h) + "  # L at 1 A, H\n";
  if (cc.inductance_2a_h) t += "inductance_2a_h = " + num(*cc.inductance_2a_h) + "  # L at 2 A, H\n";
  if (cc.thermal_resistance_k_w)
    t += "thermal_resistance_k_w = " + num(*cc.thermal_resistance_k_w) + "  # coil to ambient, K/W\n";
  if (cc.thermal_time_constant_s)
    t += "thermal_time_constant_s = " + num(*cc.thermal_time_constant_s) + "  # R_th C, s\n";
  const auto& p = b.pr;
  t += "\n[participant_ratio]  # Eq. 5.6-5.11, Table 5.6";
  t += f.pr_identified ? "\n" : ": assumed (thesis values), not identified from the records\n";
  t += "a_initial = " + num(p.a_initial) + "\n";
  t += "b_initial = " + num(p.b_initial) + "\n";
  t += "c_initial = " + num(p.c_initial) + "\n";
  t += "a_final = " + num(p.a_final) + "\n";
  t += "b_final = " + num(p.b_final) + "\n";
  t += "c_final = " + num(p.c_final) + "\n";
  t += "a_rise = " + num(p.a_rise) + "\n";
  t += "b_rise = " + num(p.b_rise) + "\n";
  t += "c_rise = " + num(p.c_rise) + "\n";
  t += "flow_area_m2 = " + num(p.flow_area_m2) + "\n";
  t += "volume_unit_m3 = " + num(p.volume_unit_m3) + "\n";
  t += std::string("identified = ") + (f.pr_identified ? "true" : "false") + "\n";
  t += "\n[validity]  # the conditions the records cover\n";
  t += "current_min_a = " + num(v.current_min_a) + "\n";
  t += "current_max_a = " + num(v.current_max_a) + "\n";
  t += "velocity_max_m_s = " + num(v.velocity_max_m_s) + "\n";
  t += "force_peak_n = " + num(v.force_peak_n) + "\n";
  t += "amplitude_min_m = " + num(v.amplitude_min_m) + "\n";
  t += "amplitude_max_m = " + num(v.amplitude_max_m) + "\n";
  t += "frequency_min_hz = " + num(v.frequency_min_hz) + "\n";
  t += "frequency_max_hz = " + num(v.frequency_max_hz) + "\n";
  t += "expected_gap = " + num(b.expected_gap) + "  # largest normalized RMS gap on the records below\n";
  t += std::string("expected_gap_basis = \"") + gap_basis_name(b.expected_gap_basis) + "\"  # " +
       gap_basis_phrase(b.expected_gap_basis) + "\n";
  if (f.rating) {
    t += "\n[rating]  # what the damper is rated for (a closed loop's limits)\n";
    t += "current_a = " + num(f.rating->current_a) + "\n";
    t += "force_n = " + num(f.rating->force_n) + "\n";
    t += "stroke_m = " + num(f.rating->stroke_m) + "  # +- from the centre\n";
    t += "velocity_m_s = " + num(f.rating->velocity_m_s) + "\n";
  }
  if (f.geometry) {
    t += "\n[geometry]  # the cylinder the fluid settles in (Eq. 5.3)\n";
    t += "inner_diameter_m = " + num(f.geometry->inner_diameter_m) + "\n";
    t += "shaft_radius_m = " + num(f.geometry->shaft_radius_m) + "\n";
    t += "fluid_length_m = " + num(f.geometry->fluid_length_m) + "\n";
    t += "fluid_volume_m3 = " + num(f.geometry->fluid_volume_m3) + "\n";
  }
  for (const RecordFit& r : f.fits) {
    t += "\n[[fit]]\n";
    t += "file = " + quoted(r.file) + "\n";
    t += "law = " + quoted(base_law_name(r.law)) + "\n";
    if (r.tanh_transition) t += "transition = \"tanh\"\n";
    if (r.transition_time) t += "transition_time = true\n";
    if (r.lost_motion) t += "lost_motion = true\n";
    if (r.viscous_lost_motion) t += "viscous_lost_motion = true\n";
    t += "gap = " + num(r.gap) + "\n";
    t += "samples = " + std::to_string(r.samples) + "\n";
  }
  return t;
}

BaselineFile parse_baseline_toml(const std::string& text, const std::string& origin) {
  const toml::table root = parse_toml(text, origin);
  BaselineFile f;
  Baseline& b = f.baseline;
  b = thesis_baseline();
  no_unknown_tables(root,
                    {"model", "yield_n", "viscous_ns_m", "bingham", "bouc_wen", "spencer", "lost_motion", "channels",
                     "coil", "participant_ratio", "validity", "rating", "geometry", "fit"},
                    origin);
  {
    Table m(table_of(root, "model", origin), "model", origin);
    b.law = law_named(m.string("law"), origin, m.where("law"), "model.law");
    b.name = m.string("name");
    if (m.has("source_records")) f.source_records = m.strings("source_records");
    m.no_unknown_keys();
  }
  const char* own = base_law_name(b.law);
  for (const char* other : {"bingham", "bouc_wen", "spencer"}) {
    if (std::string(other) == own) continue;
    if (const toml::node* n = root.get(other))
      fail(origin, n->source(), other, std::string("not allowed with model.law = \"") + own + "\"");
  }
  if (b.law == BaseLaw::spencer) {
    // The spencer law has its own current laws: Eq. 4.2-4.3's do not act.
    for (const char* unused : {"yield_n", "viscous_ns_m", "lost_motion"})
      if (const toml::node* n = root.get(unused))
        fail(origin, n->source(), unused, "not allowed with model.law = \"spencer\" (its current laws are in [spencer])");
    b.spencer = read_spencer(root, origin);
  } else {
    read_law(root, "yield_n", origin, b.yield_n, f.sigma.yield_n, f.yield_fitted, kYieldForceRange);
    read_law(root, "viscous_ns_m", origin, b.viscous_ns_m, f.sigma.viscous_ns_m, f.viscous_fitted, kViscousRange);
  }
  if (b.law != BaseLaw::spencer) {
    Table t(table_of(root, own, origin), own, origin);
    if (b.law == BaseLaw::bingham) {
      b.v_tf_m_s = t.in("v_tf_m_s", kVelocityBandRange);
      f.sigma.v_tf_m_s = sigma_of(t, "v_tf_m_s_sigma", kVelocityBandRange);
      if (t.has("transition")) b.tanh_transition = transition_named(t, origin, "bingham.transition");
      if (t.has("transition_time_s")) {
        b.transition_time_s = t.in("transition_time_s", kTransitionTimeRange);
        f.sigma.transition_time_s = sigma_of(t, "transition_time_s_sigma", kTransitionTimeRange);
      }
      if (t.has("stiffness_n_m")) {
        b.stiffness_n_m = t.in("stiffness_n_m", kStiffnessRange);
        f.sigma.stiffness_n_m = sigma_of(t, "stiffness_n_m_sigma", kStiffnessRange);
      }
      if (t.has("viscous_exponent") != t.has("viscous_ref_m_s"))
        fail(origin, t.has("viscous_exponent") ? t.where("viscous_exponent") : t.where("viscous_ref_m_s"),
             "bingham.viscous_exponent", "needs viscous_ref_m_s beside it (and the other way round)");
      if (t.has("viscous_exponent")) {
        b.viscous_exponent = t.in("viscous_exponent", kViscousExponentRange);
        f.sigma.viscous_exponent = sigma_of(t, "viscous_exponent_sigma", kViscousExponentRange);
        b.viscous_ref_m_s = t.in("viscous_ref_m_s", kVelocityBandRange);
      }
      if (t.has("series_compliance_m_per_n")) {
        b.series_compliance_m_per_n = t.in("series_compliance_m_per_n", kSeriesComplianceRange);
        f.sigma.series_compliance_m_per_n =
            sigma_of(t, "series_compliance_m_per_n_sigma", kSeriesComplianceRange);
      }
    } else {
      b.yield_disp_m = t.in("yield_disp_m", kYieldDispRange);
      f.sigma.yield_disp_m = sigma_of(t, "yield_disp_m_sigma", kYieldDispRange);
      b.stiffness_n_m = t.in("stiffness_n_m", kStiffnessRange);
      f.sigma.stiffness_n_m = sigma_of(t, "stiffness_n_m_sigma", kStiffnessRange);
    }
    t.no_unknown_keys();
  }
  if (root.get("lost_motion") != nullptr) {
    Table t(table_of(root, "lost_motion", origin), "lost_motion", origin);
    b.lost_motion_m_per_n = t.in("m_per_n", kPlayRange);
    f.sigma.lost_motion_m_per_n = sigma_of(t, "m_per_n_sigma", kPlayRange);
    b.lost_motion_share = t.in("share", kShareRange);
    f.sigma.lost_motion_share = sigma_of(t, "share_sigma", kShareRange);
    if (t.has("band_m_s")) {
      b.lost_motion_band_m_s = t.in("band_m_s", kVelocityBandRange);
      f.sigma.lost_motion_band_m_s = sigma_of(t, "band_m_s_sigma", kVelocityBandRange);
    }
    t.no_unknown_keys();
  }
  if (const toml::table* channels = optional_table(root, "channels", origin)) {
    Table ch(*channels, "channels", origin);
    b.force_delay_s = ch.in("force_delay_s", kForceDelayRange);
    f.sigma.force_delay_s = sigma_of(ch, "force_delay_s_sigma", kForceDelayRange);
    ch.no_unknown_keys();
  }
  {
    Table c(table_of(root, "coil", origin), "coil", origin);
    b.coil.tau_slow_s = c.in("tau_slow_s", kCoilTimeConstantRange);
    b.coil.tau_fast_s = c.in("tau_fast_s", kCoilTimeConstantRange);
    b.coil.weight_slow = c.in("weight_slow", kCoilWeightRange);
    b.coil.weight_fast = c.in("weight_fast", kCoilWeightRange);
    b.coil_identified = c.boolean("identified");
    const PhysicalRange tau_sigma = sigma_range(kCoilTimeConstantRange);
    if (c.has("tau_slow_s_sigma")) f.sigma.coil_tau_slow_s = c.in("tau_slow_s_sigma", tau_sigma);
    if (c.has("tau_fast_s_sigma")) f.sigma.coil_tau_fast_s = c.in("tau_fast_s_sigma", tau_sigma);
    if (std::fabs(b.coil.weight_slow + b.coil.weight_fast - 1.0) > 1e-9)
      fail(origin, c.where("weight_fast"), "coil.weight_fast", "expected weight_slow + weight_fast = 1 (unity DC gain)");
    read_coil_circuit(c, f.coil_circuit);
    c.no_unknown_keys();
  }
  {
    Table p(table_of(root, "participant_ratio", origin), "participant_ratio", origin);
    auto& q = b.pr;
    q.a_initial = p.in("a_initial", kParticipantRatioRange);
    q.b_initial = p.in("b_initial", kParticipantRatioRange);
    q.c_initial = p.in("c_initial", kSettlingRateRange);
    q.a_final = p.in("a_final", kParticipantRatioRange);
    q.b_final = p.in("b_final", kParticipantRatioRange);
    q.c_final = p.in("c_final", kSettlingRateRange);
    q.a_rise = p.in("a_rise", kMixingRateRange);
    q.b_rise = p.in("b_rise", kMixingRateRange);
    q.c_rise = p.in("c_rise", kSettlingRateRange);
    q.flow_area_m2 = p.in("flow_area_m2", kFlowAreaRange);
    q.volume_unit_m3 = p.in("volume_unit_m3", kVolumeUnitRange);
    f.pr_identified = p.boolean("identified");
    p.no_unknown_keys();
  }
  {
    Table v(table_of(root, "validity", origin), "validity", origin);
    auto& r = b.range;
    r.current_min_a = v.in("current_min_a", kRecordCurrentRange);
    r.current_max_a = v.in("current_max_a", kRecordCurrentRange);
    r.velocity_max_m_s = v.in("velocity_max_m_s", kRecordVelocityRange);
    r.force_peak_n = v.in("force_peak_n", kRecordForceRange);
    r.amplitude_min_m = v.in("amplitude_min_m", kRecordAmplitudeRange);
    r.amplitude_max_m = v.in("amplitude_max_m", kRecordAmplitudeRange);
    r.frequency_min_hz = v.in("frequency_min_hz", kRecordFrequencyRange);
    r.frequency_max_hz = v.in("frequency_max_hz", kRecordFrequencyRange);
    b.expected_gap = v.in("expected_gap", kGapRange);
    if (v.has("expected_gap_basis")) b.expected_gap_basis = gap_basis_named(v, origin);
    const auto order = [&](double lo, double hi, const char* key, const char* what) {
      if (lo > hi) fail(origin, v.where(key), v.field(key), std::string("expected at least ") + what + " (" + num(lo) + ")");
    };
    order(r.current_min_a, r.current_max_a, "current_max_a", "current_min_a");
    order(r.amplitude_min_m, r.amplitude_max_m, "amplitude_max_m", "amplitude_min_m");
    order(r.frequency_min_hz, r.frequency_max_hz, "frequency_max_hz", "frequency_min_hz");
    v.no_unknown_keys();
  }
  if (b.law == BaseLaw::spencer) check_spencer_laws(root, b.spencer, b.range, origin);
  if (const toml::table* t = optional_table(root, "rating", origin)) f.rating = read_rating(*t, origin);
  if (const toml::table* t = optional_table(root, "geometry", origin)) f.geometry = read_geometry(*t, origin);
  if (const toml::node* n = root.get("fit")) {
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables()) fail(origin, n->source(), "fit", "expected [[fit]] tables");
    std::size_t i = 0;
    for (const toml::node& e : *a) {
      Table t(*e.as_table(), "fit[" + std::to_string(i++) + "]", origin);
      RecordFit r;
      r.file = t.string("file");
      r.law = law_named(t.string("law"), origin, t.where("law"), t.field("law"));
      if (t.has("transition")) r.tanh_transition = transition_named(t, origin, t.field("transition"));
      if (t.has("transition_time")) r.transition_time = t.boolean("transition_time");
      if (t.has("lost_motion")) r.lost_motion = t.boolean("lost_motion");
      if (t.has("viscous_lost_motion")) r.viscous_lost_motion = t.boolean("viscous_lost_motion");
      r.gap = t.in("gap", kGapRange);
      r.samples = t.count("samples", kMaxRecordSamples);
      t.no_unknown_keys();
      f.fits.push_back(std::move(r));
    }
  }
  return f;
}

BaselineFile read_baseline_file(const std::filesystem::path& path) {
  return parse_baseline_toml(io::read_regular_file(path, kMaxBaselineFileBytes), io::file_label(path));
}

void write_baseline_file(const BaselineFile& f, const std::filesystem::path& path) {
  report::write_file_atomically(path, baseline_toml(f));
}

}  // namespace mrd::discrepancy
