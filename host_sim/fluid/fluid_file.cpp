#include "host_sim/fluid/fluid_file.hpp"

#include "host_sim/discrepancy/toml_fields.hpp"
#include "host_sim/fluid/fluid_ranges.hpp"
#include "host_sim/io/text.hpp"

namespace mrd::fluid {
namespace {

using discrepancy::TomlTable;

/// Table 5.3's quantities and the optional measured maximum settling time.
void read_fluid_table(const toml::table& root, const std::string& origin, FluidFile& f) {
  TomlTable t(discrepancy::required_table(root, "fluid", origin), "fluid", origin);
  f.name = t.string("name");
  f.source = t.string("source");
  physics::SettlingParams& s = f.settling;
  s.particle_diameter_m = t.in("particle_diameter_m", kParticleDiameterRange);
  s.solid_density_kg_m3 = t.in("solid_density_kg_m3", kSolidDensityRange);
  s.liquid_density_kg_m3 = t.in("liquid_density_kg_m3", kLiquidDensityRange);
  s.viscosity_pa_s = t.in("viscosity_pa_s", kViscosityRange);
  s.solid_fraction = t.in("solid_fraction", kSolidFractionRange);
  s.hindered_exponent = t.in("hindered_exponent", kHinderedExponentRange);
  s.measured_max_settling_time_s = t.optional_in("max_settling_time_s", kMaxSettlingTimeRange).value_or(0.0);
  if (!(s.solid_density_kg_m3 > s.liquid_density_kg_m3))
    t.refuse("solid_density_kg_m3", "expected more than liquid_density_kg_m3 (" +
                                         discrepancy::toml_number(s.liquid_density_kg_m3) +
                                         " kg/m3): particles that do not sink do not settle (Eq. 5.1)");
  t.no_unknown_keys();
}

/// Table 5.6's nine coefficients.
void read_coefficients(const toml::table& root, const std::string& origin, physics::ParticipantRatioParams& q) {
  TomlTable p(discrepancy::required_table(root, "participant_ratio", origin), "participant_ratio", origin);
  q.a_initial = p.in("a_initial", discrepancy::kParticipantRatioRange);
  q.b_initial = p.in("b_initial", discrepancy::kParticipantRatioRange);
  q.c_initial = p.in("c_initial", discrepancy::kSettlingRateRange);
  q.a_final = p.in("a_final", discrepancy::kParticipantRatioRange);
  q.b_final = p.in("b_final", discrepancy::kParticipantRatioRange);
  q.c_final = p.in("c_final", discrepancy::kSettlingRateRange);
  q.a_rise = p.in("a_rise", discrepancy::kMixingRateRange);
  q.b_rise = p.in("b_rise", discrepancy::kMixingRateRange);
  q.c_rise = p.in("c_rise", discrepancy::kSettlingRateRange);
  p.no_unknown_keys();
}

/// Stokes' law (Eq. 5.1) needs Re_p = ρ_l V_t d_p / η < 0.3 (§5.1.1).
std::vector<std::string> warnings_of(const FluidFile& f) {
  const physics::SettlingParams& s = f.settling;
  const double re = s.liquid_density_kg_m3 * physics::stokes_velocity_m_s(s) * s.particle_diameter_m / s.viscosity_pa_s;
  if (re < kMaxStokesReynolds) return {};
  return {"fluid: the particle Reynolds number " + io::format_number("%.3g", re) +
          " is not below 0.3: Stokes' law (Eq. 5.1) and the exponent of Eq. 5.2 are extrapolated"};
}

}  // namespace

FluidFile thesis_fluid() { return FluidFile{}; }

FluidFile parse_fluid_toml(const std::string& text, const std::string& origin) {
  const toml::table root = discrepancy::parse_toml(text, origin);
  discrepancy::no_unknown_tables(root, {"fluid", "participant_ratio"}, origin);
  FluidFile f;
  read_fluid_table(root, origin, f);
  read_coefficients(root, origin, f.participant_ratio);
  f.warnings = warnings_of(f);
  return f;
}

FluidFile read_fluid_file(const std::filesystem::path& path) {
  return parse_fluid_toml(io::read_regular_file(path, kMaxFluidFileBytes), io::file_label(path));
}

physics::SettlingParams with_fluid(physics::SettlingParams settling, const FluidFile& f) {
  const physics::SettlingParams& s = f.settling;
  settling.particle_diameter_m = s.particle_diameter_m;
  settling.solid_density_kg_m3 = s.solid_density_kg_m3;
  settling.liquid_density_kg_m3 = s.liquid_density_kg_m3;
  settling.viscosity_pa_s = s.viscosity_pa_s;
  settling.solid_fraction = s.solid_fraction;
  settling.hindered_exponent = s.hindered_exponent;
  settling.measured_max_settling_time_s = s.measured_max_settling_time_s;
  return settling;
}

physics::ParticipantRatioParams with_fluid_coefficients(physics::ParticipantRatioParams pr, const FluidFile& f) {
  const physics::ParticipantRatioParams& q = f.participant_ratio;
  pr.a_initial = q.a_initial;
  pr.b_initial = q.b_initial;
  pr.c_initial = q.c_initial;
  pr.a_final = q.a_final;
  pr.b_final = q.b_final;
  pr.c_final = q.c_final;
  pr.a_rise = q.a_rise;
  pr.b_rise = q.b_rise;
  pr.c_rise = q.c_rise;
  return pr;
}

}  // namespace mrd::fluid
