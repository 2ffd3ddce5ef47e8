// The fluid file of --fluid: the shipped model-fluid file reads to exactly
// the compiled-in fluid (Table 5.3, 5.6); a measured maximum settling time
// replaces Eq. 5.4, checked by hand on a fluid of 20 years (Eq. 5.5–5.8);
// and every kind of bad file is refused with "<file>:<line>: <field>: ..."
// where the line is counted in the test's own text.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "file_text_helpers.hpp"
#include "host_sim/damper/damper_file.hpp"
#include "host_sim/fluid/fluid_file.hpp"
#include "host_sim/io/usage_error.hpp"
#include "mrd/physics/participant_ratio.hpp"
#include "mrd/physics/settling.hpp"
#include "mrd/units.hpp"

namespace mrd::fluid {
namespace {

using test::edited;
using test::file_text;
using test::line_of;

namespace fs = std::filesystem;

const fs::path kFluidsDir = MRD_FLUIDS_DIR;

/// The error of parsing `text` (empty when it parses).
std::string error_of(const std::string& text) { return test::parse_error_of(&parse_fluid_toml, text, "f.toml"); }

TEST(FluidFile, TheModelFluidFileIsTheCompiledInFluid) {
  const FluidFile f = read_fluid_file(kFluidsDir / "thesis-model-fluid.toml");
  const physics::SettlingParams s{};
  EXPECT_EQ(f.settling.particle_diameter_m, s.particle_diameter_m);
  EXPECT_EQ(f.settling.solid_density_kg_m3, s.solid_density_kg_m3);
  EXPECT_EQ(f.settling.liquid_density_kg_m3, s.liquid_density_kg_m3);
  EXPECT_EQ(f.settling.viscosity_pa_s, s.viscosity_pa_s);
  EXPECT_EQ(f.settling.solid_fraction, s.solid_fraction);
  EXPECT_EQ(f.settling.hindered_exponent, s.hindered_exponent);
  EXPECT_EQ(f.settling.measured_max_settling_time_s, s.measured_max_settling_time_s);
  const physics::ParticipantRatioParams p{};
  const physics::ParticipantRatioParams& q = f.participant_ratio;
  EXPECT_EQ(q.a_initial, p.a_initial);
  EXPECT_EQ(q.b_initial, p.b_initial);
  EXPECT_EQ(q.c_initial, p.c_initial);
  EXPECT_EQ(q.a_final, p.a_final);
  EXPECT_EQ(q.b_final, p.b_final);
  EXPECT_EQ(q.c_final, p.c_final);
  EXPECT_EQ(q.a_rise, p.a_rise);
  EXPECT_EQ(q.b_rise, p.b_rise);
  EXPECT_EQ(q.c_rise, p.c_rise);
  EXPECT_EQ(f.name, "thesis-model-fluid");
  EXPECT_TRUE(f.warnings.empty());
  // In the thesis damper's cylinder it is SettlingParams{} field for field.
  const physics::SettlingParams in = with_fluid(damper::with_geometry({}, damper::thesis_geometry()), f);
  EXPECT_EQ(in.gravity_m_s2, s.gravity_m_s2);
  EXPECT_EQ(in.particle_diameter_m, s.particle_diameter_m);
  EXPECT_EQ(in.solid_density_kg_m3, s.solid_density_kg_m3);
  EXPECT_EQ(in.liquid_density_kg_m3, s.liquid_density_kg_m3);
  EXPECT_EQ(in.viscosity_pa_s, s.viscosity_pa_s);
  EXPECT_EQ(in.solid_fraction, s.solid_fraction);
  EXPECT_EQ(in.hindered_exponent, s.hindered_exponent);
  EXPECT_EQ(in.inner_diameter_m, s.inner_diameter_m);
  EXPECT_EQ(in.shaft_radius_m, s.shaft_radius_m);
  EXPECT_EQ(in.fluid_length_m, s.fluid_length_m);
  EXPECT_EQ(in.fluid_volume_m3, s.fluid_volume_m3);
  EXPECT_EQ(in.measured_max_settling_time_s, s.measured_max_settling_time_s);
  EXPECT_EQ(physics::max_settling_time_s(in), physics::max_settling_time_s(s));
}

// A fluid whose maximum settling time is 20 years (the shipped illustrative
// file), by hand:
//   T_max = 20 · 365.25 · 86400 s = 631 152 000 s (replaces Eq. 5.4)
//   SQ after 1 year = 1/20 = 0.05 (Eq. 5.5: idle time over T_max)
//   a_PR = 0.1 + 0.9·e^(−7·0.05)    = 0.1 + 0.9 · 0.7046880897 = 0.7342192807   (Eq. 5.6)
//   b_PR = 0.605 + 0.395·e^(−4.5·0.05) = 0.605 + 0.395 · 0.7985162188 = 0.9204139064   (Eq. 5.7)
//   c_PR = 0 + 5.474·e^(−3.65·0.05) = 5.474 · 0.8331846439 = 4.5608527409   (Eq. 5.8)
// The cylinder does not enter: the same in the thesis damper's and another's.
TEST(FluidFile, TwentyYearFluidGivesEq55To58ByHand) {
  const FluidFile f = read_fluid_file(kFluidsDir / "illustrative-20-year.toml");
  EXPECT_EQ(f.settling.measured_max_settling_time_s, 631152000.0);
  EXPECT_NE(f.source.find("illustrative"), std::string::npos);
  discrepancy::DamperGeometry small{0.04, 0.005, 0.1, 0.0001};
  for (const auto& g : {damper::thesis_geometry(), small}) {
    const physics::SettlingParams s = with_fluid(damper::with_geometry({}, g), f);
    EXPECT_EQ(physics::max_settling_time_s(s), 631152000.0);
    const double sq = physics::settling_quotient_after_idle(units::years_to_s(1.0), s);
    EXPECT_NEAR(sq, 0.05, 1e-15);
    const physics::PrCoefficients c = physics::pr_coefficients(with_fluid_coefficients({}, f), sq);
    EXPECT_NEAR(c.a_pr, 0.7342192807, 1e-10);
    EXPECT_NEAR(c.b_pr, 0.9204139064, 1e-10);
    EXPECT_NEAR(c.c_pr, 4.5608527409, 1e-10);
    // Saturates at 20 years and beyond (Eq. 5.5).
    EXPECT_EQ(physics::settling_quotient_after_idle(units::years_to_s(25.0), s), 1.0);
  }
}

// with_fluid_coefficients takes Table 5.6's nine and keeps the damper's flow
// area and volume unit of ∫Q dt.
TEST(FluidFile, CoefficientsLeaveTheDampersFlowArea) {
  FluidFile f;
  f.participant_ratio.b_final = 0.8;
  f.participant_ratio.flow_area_m2 = 0.5;  // not the fluid's to give
  physics::ParticipantRatioParams damper_pr;
  damper_pr.flow_area_m2 = 0.0005;
  const physics::ParticipantRatioParams p = with_fluid_coefficients(damper_pr, f);
  EXPECT_EQ(p.b_final, 0.8);
  EXPECT_EQ(p.flow_area_m2, 0.0005);
  EXPECT_EQ(p.volume_unit_m3, 1e-3);
}

// Eq. 5.1 holds for Re_p < 0.3. A 1 mm particle in a water-like carrier:
// V_t = 9.81 · (1e−3)² · (7870 − 820) / (18 · 1e−3) = 3.842 m/s, Re_p =
// 820 · 3.842 · 1e−3 / 1e−3 = 3150: read, with a warning.
TEST(FluidFile, WarnsBeyondStokesLaw) {
  std::string t = file_text(kFluidsDir / "thesis-model-fluid.toml");
  t = edited(edited(t, "particle_diameter_m = 5e-06", "particle_diameter_m = 1e-3"), "viscosity_pa_s = 2.0",
             "viscosity_pa_s = 1e-3");
  const FluidFile f = parse_fluid_toml(t, "fast.toml");
  ASSERT_EQ(f.warnings.size(), 1u);
  EXPECT_NE(f.warnings[0].find("particle Reynolds number 3.15e+03"), std::string::npos) << f.warnings[0];
}

TEST(FluidFile, AMissingFileIsNamed) {
  try {
    (void)read_fluid_file(kFluidsDir / "no-such-fluid.toml");
    FAIL() << "read a missing file";
  } catch (const io::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-fluid.toml"), std::string::npos) << e.what();
  }
}

TEST(FluidFile, RefusesBadFilesNamingFileLineAndField) {
  const std::string t = file_text(kFluidsDir / "illustrative-20-year.toml");
  const std::vector<test::Refusal> cases = {
      {"syntax error", edited(t, "solid_fraction = 0.4", "solid_fraction = 0.4.0"), "solid_fraction", "", ""},
      {"unknown table", t + "\n[fluids]\nname = \"x\"\n", "[fluids]", "fluids",
       "unknown table (expected fluid or participant_ratio)"},
      {"unknown key", edited(t, "solid_fraction = 0.4", "solid_fraction = 0.4\ndensity_kg_m3 = 3000.0"),
       "density_kg_m3", "fluid.density_kg_m3", "unknown key"},
      {"missing key", edited(t, "hindered_exponent = 4.65\n", ""), "[fluid]", "fluid.hindered_exponent",
       "missing key"},
      {"wrong type", edited(t, "viscosity_pa_s = 2.0", "viscosity_pa_s = \"2 Pa s\""), "viscosity_pa_s",
       "fluid.viscosity_pa_s", "expected a number"},
      {"name not a string", edited(t, "name = \"illustrative-20-year\"", "name = 20"), "name = ", "fluid.name",
       "expected a string"},
      {"non-finite", edited(t, "particle_diameter_m = 5e-06", "particle_diameter_m = inf"), "particle_diameter_m",
       "fluid.particle_diameter_m", "expected a finite number"},
      {"solid lighter than the liquid", edited(t, "solid_density_kg_m3 = 7870.0", "solid_density_kg_m3 = 800.0"),
       "solid_density_kg_m3", "fluid.solid_density_kg_m3", "expected a density in [1000, 23000] kg/m3, got 800.0"},
      {"solid density below the liquid's",
       edited(edited(t, "solid_density_kg_m3 = 7870.0", "solid_density_kg_m3 = 1000.0"),
              "liquid_density_kg_m3 = 820.0", "liquid_density_kg_m3 = 1200.0"),
       "solid_density_kg_m3", "fluid.solid_density_kg_m3",
       "expected more than liquid_density_kg_m3 (1200.0 kg/m3): particles that do not sink do not settle"},
      {"solid fraction of 1", edited(t, "solid_fraction = 0.4", "solid_fraction = 1.0"), "solid_fraction",
       "fluid.solid_fraction", "expected a volume fraction in [0.001, 0.74], got 1.0"},
      {"max settling time 0", edited(t, "max_settling_time_s = 631152000.0", "max_settling_time_s = 0"),
       "max_settling_time_s", "fluid.max_settling_time_s", "expected a time in [1, 1e+11] s, got 0.0"},
      {"negative max settling time", edited(t, "max_settling_time_s = 631152000.0", "max_settling_time_s = -1.0"),
       "max_settling_time_s", "fluid.max_settling_time_s", "expected a time in [1, 1e+11] s, got -1.0"},
      {"viscosity zero", edited(t, "viscosity_pa_s = 2.0", "viscosity_pa_s = 0.0"), "viscosity_pa_s",
       "fluid.viscosity_pa_s", "expected a viscosity in [0.0001, 1e+06] Pa s, got 0.0"},
      {"participant ratio above 1", edited(t, "b_final = 0.605", "b_final = 1.2"), "b_final",
       "participant_ratio.b_final", "expected a participant ratio in [0, 1], got 1.2"},
      {"participant ratio key unknown", edited(t, "c_rise = 3.65", "c_rise = 3.65\nflow_area_m2 = 0.01"),
       "flow_area_m2", "participant_ratio.flow_area_m2", "unknown key"},
  };
  test::expect_refusals(cases, error_of, "f.toml");
  // A missing table is named at line 1.
  const std::string no_pr = t.substr(0, t.find("\n[participant_ratio]"));
  EXPECT_EQ(error_of(no_pr), "f.toml:1: [participant_ratio]: missing table");
  EXPECT_EQ(error_of(""), "f.toml:1: [fluid]: missing table");
}

}  // namespace
}  // namespace mrd::fluid
