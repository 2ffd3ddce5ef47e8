#include "host_sim/damper/damper_file.hpp"

#include <algorithm>
#include <cmath>

#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/discrepancy/physical_ranges.hpp"
#include "host_sim/discrepancy/toml_fields.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::damper {
namespace {

using discrepancy::BaseLaw;
using discrepancy::Baseline;
using discrepancy::BaselineFile;
using discrepancy::PhysicalRange;

std::string g4(double v) { return io::format_number("%.4g", v); }

// The closed loop averages the lost motion's engagement over the window the calibration does.
static_assert(physics::kLostMotionHalfWindow_s == discrepancy::kContactHalfWindow_s);

physics::ForceLaw force_law(const Baseline& b) {
  if (b.law == BaseLaw::bouc_wen) return physics::ForceLaw::kBoucWen;
  if (b.law == BaseLaw::spencer) return physics::ForceLaw::kSpencer;
  return b.has_tanh_transition() ? physics::ForceLaw::kBinghamTanh : physics::ForceLaw::kBingham;
}

/// Eq. 4.2–4.5 and 5.6–5.9 of the baseline, as physics::MrDamperParams
/// (without the rating).
physics::MrDamperParams damper_params(const Baseline& b) {
  physics::MrDamperParams p;
  p.bingham.fc_a_n = b.yield_n.at_zero;
  p.bingham.fc_b_n = b.yield_n.limit;
  p.bingham.fc_c_per_a = b.yield_n.rate_per_a;
  p.bingham.c0_a_ns_m = b.viscous_ns_m.at_zero;
  p.bingham.c0_b_ns_m = b.viscous_ns_m.limit;
  p.bingham.c0_c_per_a = b.viscous_ns_m.rate_per_a;
  p.bingham.v_tf_m_s = b.v_tf_m_s;
  p.coil = b.coil;
  p.pr = b.pr;
  p.law = force_law(b);
  if (b.law == BaseLaw::bouc_wen) p.bouc_wen = {b.yield_disp_m, b.stiffness_n_m};
  if (b.law == BaseLaw::spencer) p.spencer = b.spencer;
  // The calibration's shape of the law (LawShape), each term where the baseline applies it.
  if (b.has_current_exponent()) {
    p.shape.yield_current_exponent = b.yield_n.current_exponent;
    p.shape.viscous_current_exponent = b.viscous_ns_m.current_exponent;
  }
  if (b.has_viscous_exponent()) {
    p.shape.viscous_exponent = b.viscous_exponent;
    p.shape.viscous_ref_m_s = b.viscous_ref_m_s;
  }
  if (b.has_bingham_stiffness()) p.shape.stiffness_n_m = b.stiffness_n_m;
  if (b.has_transition_time()) p.shape.transition_time_s = b.transition_time_s;
  if (b.has_series_compliance()) p.shape.series_compliance_m_per_n = b.series_compliance_m_per_n;
  if (b.has_lost_motion()) {
    p.shape.lost_motion_m_per_n = b.lost_motion_m_per_n;
    p.shape.lost_motion_share = b.lost_motion_share;
    p.shape.lost_motion_band_m_s = b.lost_motion_band_m_s;
  }
  return p;
}

/// The line of [table] key in `root` (of the table when the key is absent).
toml::source_region where(const toml::table& root, const char* table, const char* key) {
  const toml::node* t = root.get(table);
  if (!t || !t->as_table()) return root.source();
  const toml::node* n = t->as_table()->get(key);
  return n ? n->source() : t->source();
}

/// A rating quantity taken from [validity] `key`: refused naming that key
/// when it lies outside the rating's range.
double derived(double value, const PhysicalRange& r, const toml::table& root, const char* key,
               const std::string& origin) {
  if (!r.contains(value))
    discrepancy::fail_at(origin, where(root, "validity", key), std::string("validity.") + key,
                         "the file has no [rating], and " + discrepancy::toml_number(value) +
                             " is no rating: expected " + discrepancy::range_text(r) +
                             " (add a [rating] table with current_a, force_n, stroke_m, velocity_m_s)");
  return value;
}

/// [rating] from [validity]: what the records covered.
physics::DamperRating rating_of_validity(const discrepancy::ValidityRange& v, const toml::table& root,
                                         const std::string& origin) {
  physics::DamperRating r;
  const bool min_larger = std::fabs(v.current_min_a) > std::fabs(v.current_max_a);
  r.current_a = derived(std::max(std::fabs(v.current_min_a), std::fabs(v.current_max_a)),
                        discrepancy::kRatedCurrentRange, root, min_larger ? "current_min_a" : "current_max_a",
                        origin);
  r.force_n = derived(v.force_peak_n, discrepancy::kRatedForceRange, root, "force_peak_n", origin);
  r.stroke_m = derived(v.amplitude_max_m, discrepancy::kRatedStrokeRange, root, "amplitude_max_m", origin);
  r.velocity_m_s = derived(v.velocity_max_m_s, discrepancy::kRatedVelocityRange, root, "velocity_max_m_s", origin);
  return r;
}

/// The coil's heating: the file's R, R_th and τ; where it has no R_th, the
/// thesis coil's assumption at this coil's rating (the rated current held
/// continuously settles physics::kRatedCoilRise_k above ambient); where it
/// has no τ, the thesis coil's 20 min.
physics::CoilHeatParams coil_heat_of(const discrepancy::CoilCircuit& cc, const physics::DamperRating& rating) {
  physics::CoilHeatParams h;
  if (cc.resistance_ohm) h.resistance_ohm = *cc.resistance_ohm;
  h.thermal_resistance_k_w = cc.thermal_resistance_k_w
                                 ? *cc.thermal_resistance_k_w
                                 : physics::rated_rise_thermal_resistance_k_w(rating.current_a, h.resistance_ohm);
  if (cc.thermal_time_constant_s) h.time_constant_s = *cc.thermal_time_constant_s;
  return h;
}

/// The sentences of DamperFile::warnings.
std::vector<std::string> warnings_of(const BaselineFile& f, const DamperFile& d) {
  const Baseline& b = f.baseline;
  const physics::DamperRating& r = d.params.rating;
  std::vector<std::string> w;
  if (!d.rating_given)
    w.push_back("no [rating]: the closed loop holds the damper to what its records cover ([validity]): " +
                g4(r.current_a) + " A, " + g4(r.force_n) + " N, stroke +-" + g4(r.stroke_m) + " m, " +
                g4(r.velocity_m_s) + " m/s; a [rating] table gives the damper's own limits");
  if (!d.geometry_given) {
    const discrepancy::DamperGeometry g = thesis_geometry();
    w.push_back("no [geometry]: the idle-time physics (settled layer and maximum settling time, Eq. 5.3-5.4) uses "
                "the thesis damper's cylinder (bore " + g4(g.inner_diameter_m) + " m, shaft radius " +
                g4(g.shaft_radius_m) + " m, length " + g4(g.fluid_length_m) + " m, fluid " + g4(g.fluid_volume_m3) +
                " m3)");
  }
  if (b.force_delay_s > 0.0)
    w.push_back("channels.force_delay_s: the force channel's lag of the test (" + g4(b.force_delay_s) +
                " s) is the rig's, not the damper's: the closed loop has none");
  if (!b.coil_identified)
    w.push_back("coil: identified = false: the coil's time constants (" + g4(b.coil.tau_slow_s) + " s, " +
                g4(b.coil.tau_fast_s) + " s, Eq. 4.5) are assumed, not this damper's");
  const discrepancy::CoilCircuit& cc = f.coil_circuit;
  if (!cc.thermal_resistance_k_w || !cc.thermal_time_constant_s) {
    const physics::CoilHeatParams& h = d.params.coil_heat;
    w.push_back("coil: no thermal_resistance_k_w or thermal_time_constant_s: the coil's heating is assumed as the "
                "thesis coil's, " + g4(r.current_a) + " A held continuously settling " +
                g4(physics::kRatedCoilRise_k) + " K above ambient (R_th " + g4(h.thermal_resistance_k_w) +
                " K/W at " + g4(h.resistance_ohm) + " ohm" + (cc.resistance_ohm ? "" : ", the thesis coil's") +
                ") with a time constant of " + g4(h.time_constant_s) + " s");
  }
  if (!f.pr_identified)
    w.push_back("participant_ratio: identified = false: the idle-time coefficients (Table 5.6) are assumed, not "
                "this damper's (--fluid FILE gives a fluid's)");
  const discrepancy::ValidityRange& v = b.range;
  const double covered_a = std::max(std::fabs(v.current_min_a), std::fabs(v.current_max_a));
  if (d.rating_given && r.current_a > covered_a)
    w.push_back("rating.current_a: " + g4(r.current_a) + " A is above the " + g4(covered_a) +
                " A the records cover ([validity]): the current laws are extrapolated above it");
  if (d.rating_given && r.velocity_m_s > v.velocity_max_m_s)
    w.push_back("rating.velocity_m_s: " + g4(r.velocity_m_s) + " m/s is above the " + g4(v.velocity_max_m_s) +
                " m/s the records cover ([validity]): the force is extrapolated above it");
  return w;
}

}  // namespace

discrepancy::DamperGeometry thesis_geometry() {
  const physics::SettlingParams s{};
  return {s.inner_diameter_m, s.shaft_radius_m, s.fluid_length_m, s.fluid_volume_m3};
}

DamperFile thesis_damper() {
  DamperFile d;
  d.geometry = thesis_geometry();
  return d;
}

DamperFile parse_damper_toml(const std::string& text, const std::string& origin) {
  const BaselineFile f = discrepancy::parse_baseline_toml(text, origin);
  DamperFile d;
  if (f.baseline.law == BaseLaw::spencer) {
    const toml::source_region at = where(discrepancy::parse_toml(text, origin), "model", "law");
    d.law_line = static_cast<int>(at.begin.line);
  }
  d.origin = origin;
  d.name = f.baseline.name;
  d.params = damper_params(f.baseline);
  d.rating_given = f.rating.has_value();
  d.params.rating = f.rating ? *f.rating : rating_of_validity(f.baseline.range, discrepancy::parse_toml(text, origin),
                                                              origin);
  d.geometry_given = f.geometry.has_value();
  d.geometry = f.geometry ? *f.geometry : thesis_geometry();
  d.coil_circuit = f.coil_circuit;
  d.params.coil_heat = coil_heat_of(f.coil_circuit, d.params.rating);
  if (f.coil_circuit.inductance_1a_h)
    d.params.coil_inductance =
        physics::coil_inductance(*f.coil_circuit.inductance_1a_h, *f.coil_circuit.inductance_2a_h);
  d.warnings = warnings_of(f, d);
  return d;
}

DamperFile read_damper_file(const std::filesystem::path& path) {
  return parse_damper_toml(io::read_regular_file(path, discrepancy::kMaxBaselineFileBytes), io::file_label(path));
}

void require_law_for(const DamperFile& d, const std::string& command) {
  if (d.params.law != physics::ForceLaw::kSpencer) return;
  for (const char* ok : {"sim", "sine", "sweep", "study", "settle", "fragility", "rths"})
    if (command == ok) return;
  throw io::UsageError(d.origin + ":" + std::to_string(std::max(d.law_line, 1)) + ": model.law: " +
                       "\"spencer\" is simulated in the closed loop (mrd sim, sine, sweep, study, settle, fragility, "
                       "rths); mrd " + command + " models the damper by its Bingham laws (its estimator or board): a Bingham "
                       "calibration of the same records serves it (mrd calibrate --law bingham)");
}

physics::SettlingParams with_geometry(physics::SettlingParams settling, const discrepancy::DamperGeometry& g) {
  settling.inner_diameter_m = g.inner_diameter_m;
  settling.shaft_radius_m = g.shaft_radius_m;
  settling.fluid_length_m = g.fluid_length_m;
  settling.fluid_volume_m3 = g.fluid_volume_m3;
  return settling;
}

}  // namespace mrd::damper
