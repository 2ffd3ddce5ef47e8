#include "host_sim/risk/fragility_plan.hpp"

#include <cmath>
#include <cstring>
#include <variant>

#include "host_sim/batch/batch_run.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/controller.hpp"
#include "mrd/units.hpp"

namespace mrd::risk {
namespace {

class Fnv1a {
 public:
  void bytes(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ b[i]) * 0x100000001b3ULL;
  }
  void number(double v) { bytes(&v, sizeof v); }
  void count(std::uint64_t v) { bytes(&v, sizeof v); }
  void text(const std::string& s) {
    count(s.size());
    bytes(s.data(), s.size());
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

void numbers(Fnv1a& h, const std::vector<double>& v) {
  h.count(v.size());
  for (double x : v) h.number(x);
}

/// Everything of the building that decides a run's result (not its name).
void hash_building(Fnv1a& h, const structure::BuildingParams& b) {
  h.count(static_cast<std::uint64_t>(b.base));
  numbers(h, b.mass_kg);
  numbers(h, b.story_stiffness_n_m);
  numbers(h, b.story_damping_n_s_m);
  h.count(b.rayleigh.has_value());
  if (b.rayleigh) {
    h.number(b.rayleigh->ratio);
    h.count(static_cast<std::uint64_t>(b.rayleigh->mode_a));
    h.count(static_cast<std::uint64_t>(b.rayleigh->mode_b));
  }
  h.count(b.isolators.size());
  for (const auto& iso : b.isolators) {
    h.count(iso.index());
    if (const auto* lr = std::get_if<structure::LeadRubberBearing>(&iso)) {
      h.count(lr->count);
      for (double x : {lr->characteristic_strength_n, lr->post_yield_stiffness_n_m, lr->yield_displacement_m,
                       lr->exponent, lr->displacement_capacity_m}) {
        h.number(x);
      }
    } else if (const auto* fp = std::get_if<structure::FrictionPendulumBearing>(&iso)) {
      h.count(fp->count);
      for (double x : {fp->radius_m, fp->friction_slow, fp->friction_fast, fp->rate_s_per_m, fp->yield_displacement_m,
                       fp->exponent, fp->weight_n, fp->displacement_capacity_m}) {
        h.number(x);
      }
    }
  }
  h.count(b.dampers.size());
  for (const auto& d : b.dampers) {
    h.count(d.element);
    h.count(d.count);
  }
}

/// Everything of the damper (a damper file's) and of the idle-time physics
/// (a fluid file's in the damper's cylinder) that decides a run's result.
void hash_damper_and_fluid(Fnv1a& h, const physics::MrDamperParams& d, const physics::SettlingParams& s) {
  const physics::BinghamParams& b = d.bingham;
  for (double x : {b.fc_a_n, b.fc_b_n, b.fc_c_per_a, b.c0_a_ns_m, b.c0_b_ns_m, b.c0_c_per_a, b.v_tf_m_s}) h.number(x);
  for (double x : {d.coil.tau_slow_s, d.coil.tau_fast_s, d.coil.weight_slow, d.coil.weight_fast}) h.number(x);
  const physics::ParticipantRatioParams& p = d.pr;
  for (double x : {p.a_initial, p.b_initial, p.c_initial, p.a_final, p.b_final, p.c_final, p.a_rise, p.b_rise,
                   p.c_rise, p.flow_area_m2, p.volume_unit_m3}) {
    h.number(x);
  }
  h.count(static_cast<std::uint64_t>(d.law));
  h.number(d.bouc_wen.yield_disp_m);
  h.number(d.bouc_wen.stiffness_n_m);
  // Spencer et al.'s model and current laws (only for that law: a plan of another hashes as before it).
  if (d.law == physics::ForceLaw::kSpencer) {
    const physics::SpencerParams& sp = d.spencer;
    for (double x : {sp.alpha_n_m, sp.alpha_per_a_n_m, sp.alpha_per_a2_n_m, sp.c0_ns_m, sp.c0_per_a_ns_m, sp.c1_ns_m,
                     sp.c1_per_a_ns_m, sp.gamma_per_m_pow_n, sp.gamma_rate_per_a, sp.beta_over_gamma, sp.a, sp.n,
                     sp.k0_n_m, sp.k1_n_m, sp.x0_m}) {
      h.number(x);
    }
  }
  // A calibration's bends of the law (only when there are some: a plan without them hashes as before them).
  const physics::LawShape& sh = d.shape;
  if (sh.bends()) {
    for (double x : {sh.yield_current_exponent, sh.viscous_current_exponent, sh.viscous_exponent, sh.viscous_ref_m_s,
                     sh.stiffness_n_m, sh.transition_time_s, sh.lost_motion_m_per_n, sh.lost_motion_share,
                     sh.lost_motion_band_m_s}) {
      h.number(x);
    }
    // The series compliance only when it acts (a plan with the shapes before it hashes as before it).
    if (sh.series_compliance_m_per_n != 0.0) h.number(sh.series_compliance_m_per_n);
  }
  const physics::DamperRating& r = d.rating;
  for (double x : {r.current_a, r.force_n, r.stroke_m, r.velocity_m_s}) h.number(x);
  // The coil's heating, when it is not the thesis coil's (a plan with the thesis coil hashes as before it).
  const physics::CoilHeatParams& heat = d.coil_heat;
  if (heat != physics::CoilHeatParams{})
    for (double x : {heat.resistance_ohm, heat.thermal_resistance_k_w, heat.time_constant_s}) h.number(x);
  for (double x : {s.gravity_m_s2, s.particle_diameter_m, s.solid_density_kg_m3, s.liquid_density_kg_m3,
                   s.viscosity_pa_s, s.solid_fraction, s.hindered_exponent, s.inner_diameter_m, s.shaft_radius_m,
                   s.fluid_length_m, s.fluid_volume_m3, s.measured_max_settling_time_s}) {
    h.number(x);
  }
}

/// One closed-loop run: run::closed_loop_tick with the peak story drift
/// taken after each advance.
RunMetrics simulate_one(const FragilityPlan& plan, const RunKey& k, run::Controller& controller,
                        std::vector<double>& accel) {
  const auto& rec = plan.records[k.record].accel_1g_m_s2;
  const double pga = plan.pga_g[k.pga];
  accel.resize(rec.size());
  for (std::size_t i = 0; i < rec.size(); ++i) accel[i] = rec[i] * pga;

  plant::PlantSpec spec = plan.base;
  spec.idle_time_s = units::years_to_s(plan.idle_years[k.idle]);
  plant::Plant p;
  p.init(spec);
  controller.reset();
  for (std::size_t n = 0; n < accel.size(); ++n) (void)run::closed_loop_tick(p, controller, accel[n], n);
  const plant::PlantSummary s = p.summary();
  return {s.peak_base_displacement_m, s.peak_damper_force_n, s.peak_superstructure_accel_m_s2, s.peak_base_accel_m_s2,
          s.peak_story_drift_m};
}

}  // namespace

RunKey FragilityPlan::key(std::size_t run) const noexcept {
  RunKey k;
  k.record = run % records.size();
  run /= records.size();
  k.pga = run % pga_g.size();
  run /= pga_g.size();
  k.idle = run % idle_years.size();
  k.mode = run / idle_years.size();
  return k;
}

std::size_t FragilityPlan::index(const RunKey& k) const noexcept {
  return ((k.mode * idle_years.size() + k.idle) * pga_g.size() + k.pga) * records.size() + k.record;
}

std::uint64_t FragilityPlan::fingerprint() const {
  Fnv1a h;
  h.text("mrd-fragility-1");
  h.count(records.size());
  for (const auto& r : records) {
    h.text(r.name);
    h.count(r.accel_1g_m_s2.size());
    h.bytes(r.accel_1g_m_s2.data(), r.accel_1g_m_s2.size() * sizeof(double));
  }
  h.count(pga_g.size());
  for (double v : pga_g) h.number(v);
  h.count(idle_years.size());
  for (double v : idle_years) h.number(v);
  h.count(modes.size());
  for (auto m : modes) h.count(static_cast<std::uint64_t>(m));
  h.number(base.step_s);
  h.count(static_cast<std::uint64_t>(base.kind));
  hash_building(h, base.building);
  hash_damper_and_fluid(h, base.damper, base.settling);
  h.count(seed);
  return h.value();
}

void simulate_runs_one_by_one(const FragilityPlan& plan, std::span<const std::size_t> runs, std::span<RunMetrics> out) {
  std::vector<double> accel;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunKey k = plan.key(runs[i]);
    auto controller = run::make_controller(plan.modes[k.mode], plan.base.step_s);
    out[i] = simulate_one(plan, k, *controller, accel);
  }
}

bool lanes_take(const FragilityPlan& plan) noexcept {
  return plan.base.kind == plant::PlantKind::kThesis;
}

void simulate_runs(const FragilityPlan& plan, std::span<const std::size_t> runs, std::span<RunMetrics> out) {
  if (!lanes_take(plan)) {
    simulate_runs_one_by_one(plan, runs, out);
    return;
  }
  // The chunk's runs side by side in SIMD lanes: each lane's a_g[n] is
  // pga · record[n], the product simulate_one forms, and its peaks are the
  // scalar loop's bit for bit (batch_run.hpp).
  std::vector<batch::BatchRun> lanes(runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunKey k = plan.key(runs[i]);
    lanes[i].ground_accel_m_s2 = plan.records[k.record].accel_1g_m_s2;
    lanes[i].ground_scale = plan.pga_g[k.pga];
    lanes[i].idle_time_s = units::years_to_s(plan.idle_years[k.idle]);
    lanes[i].mode = plan.modes[k.mode];
  }
  const std::vector<plant::PlantSummary> s = batch::run_closed_loop_batch(plan.base, lanes);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    out[i] = {s[i].peak_base_displacement_m, s[i].peak_damper_force_n, s[i].peak_superstructure_accel_m_s2,
              s[i].peak_base_accel_m_s2, s[i].peak_story_drift_m};
  }
}

}  // namespace mrd::risk
