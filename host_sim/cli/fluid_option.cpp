#include "host_sim/cli/fluid_option.hpp"

#include <cstdio>

#include "host_sim/cli/damper_option.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "mrd/units.hpp"

namespace mrd::cli {
namespace {

fluid::FluidFile load_fluid(const char* command, const std::string& fluid_file) {
  if (fluid_file.empty()) return fluid::thesis_fluid();
  fluid::FluidFile f = fluid::read_fluid_file(fluid_file);
  const std::string label = io::file_label(fluid_file);
  for (const std::string& w : f.warnings)
    std::fprintf(stderr, "mrd %s: warning: %s: %s\n", command, label.c_str(), w.c_str());
  return f;
}

/// Eq. 5.3's settled layer must fit below the bore: the solids' volume χ·V
/// below the annulus' L·π(R² − r_s²).
void check_solids_fit(const physics::SettlingParams& s, const std::string& damper_file, const std::string& fluid_file) {
  const double r = 0.5 * s.inner_diameter_m;
  const double annulus_m3 = s.fluid_length_m * units::kPi * (r * r - s.shaft_radius_m * s.shaft_radius_m);
  const double solids_m3 = s.solid_fraction * s.fluid_volume_m3;
  if (solids_m3 < annulus_m3) return;
  const std::string damper = damper_file.empty() ? "the thesis damper" : io::file_label(damper_file);
  const std::string fluid = fluid_file.empty() ? "the thesis fluid" : io::file_label(fluid_file);
  throw io::UsageError("--damper, --fluid: the solids of " + fluid + " (solid_fraction " +
                       io::format_number("%.4g", s.solid_fraction) + " of " +
                       io::format_number("%.4g", s.fluid_volume_m3) + " m3) do not fit in the cylinder of " +
                       damper + " (" + io::format_number("%.4g", annulus_m3) +
                       " m3 between bore and shaft over fluid_length_m): no settled layer (Eq. 5.3)");
}

bool same(const physics::MrDamperParams& a, const physics::MrDamperParams& b) {
  const physics::BinghamParams &x = a.bingham, &y = b.bingham;
  const physics::ParticipantRatioParams &p = a.pr, &q = b.pr;
  const physics::DamperRating &r = a.rating, &t = b.rating;
  return x.fc_a_n == y.fc_a_n && x.fc_b_n == y.fc_b_n && x.fc_c_per_a == y.fc_c_per_a && x.c0_a_ns_m == y.c0_a_ns_m &&
         x.c0_b_ns_m == y.c0_b_ns_m && x.c0_c_per_a == y.c0_c_per_a && x.v_tf_m_s == y.v_tf_m_s &&
         a.coil.tau_slow_s == b.coil.tau_slow_s && a.coil.tau_fast_s == b.coil.tau_fast_s &&
         a.coil.weight_slow == b.coil.weight_slow && a.coil.weight_fast == b.coil.weight_fast &&
         p.a_initial == q.a_initial && p.b_initial == q.b_initial && p.c_initial == q.c_initial &&
         p.a_final == q.a_final && p.b_final == q.b_final && p.c_final == q.c_final && p.a_rise == q.a_rise &&
         p.b_rise == q.b_rise && p.c_rise == q.c_rise && p.flow_area_m2 == q.flow_area_m2 &&
         p.volume_unit_m3 == q.volume_unit_m3 && a.law == b.law &&
         a.bouc_wen.yield_disp_m == b.bouc_wen.yield_disp_m && a.bouc_wen.stiffness_n_m == b.bouc_wen.stiffness_n_m &&
         a.shape == b.shape && r.current_a == t.current_a && r.force_n == t.force_n && r.stroke_m == t.stroke_m &&
         r.velocity_m_s == t.velocity_m_s && a.coil_heat == b.coil_heat &&
         a.coil_inductance == b.coil_inductance;
}

bool same(const physics::SettlingParams& a, const physics::SettlingParams& b) {
  return a.gravity_m_s2 == b.gravity_m_s2 && a.particle_diameter_m == b.particle_diameter_m &&
         a.solid_density_kg_m3 == b.solid_density_kg_m3 && a.liquid_density_kg_m3 == b.liquid_density_kg_m3 &&
         a.viscosity_pa_s == b.viscosity_pa_s && a.solid_fraction == b.solid_fraction &&
         a.hindered_exponent == b.hindered_exponent && a.inner_diameter_m == b.inner_diameter_m &&
         a.shaft_radius_m == b.shaft_radius_m && a.fluid_length_m == b.fluid_length_m &&
         a.fluid_volume_m3 == b.fluid_volume_m3 && a.measured_max_settling_time_s == b.measured_max_settling_time_s;
}

}  // namespace

bool is_thesis_damper(const DamperAndFluid& d) { return same(d.params, physics::MrDamperParams{}); }

bool is_thesis_settling(const DamperAndFluid& d) { return same(d.settling, physics::SettlingParams{}); }

void add_fluid_option(CLI::App& app, std::string& fluid_file) {
  app.add_option("--fluid", fluid_file,
                 "Fluid file (TOML: Table 5.3's quantities or a measured max_settling_time_s, Table 5.6's "
                 "coefficients; README \"Your damper and fluid\"); default: the thesis's model fluid "
                 "(fluids/thesis-model-fluid.toml)");
}

DamperAndFluid load_damper_and_fluid(const char* command, const std::string& damper_file,
                                     const std::string& fluid_file) {
  DamperAndFluid out;
  out.damper = load_damper(command, damper_file);
  out.fluid = load_fluid(command, fluid_file);
  out.params = out.damper.params;
  if (!fluid_file.empty()) out.params.pr = fluid::with_fluid_coefficients(out.params.pr, out.fluid);
  out.settling = fluid::with_fluid(damper::with_geometry(physics::SettlingParams{}, out.damper.geometry), out.fluid);
  check_solids_fit(out.settling, damper_file, fluid_file);
  return out;
}

}  // namespace mrd::cli
