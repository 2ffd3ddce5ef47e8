// The damper file of --damper: the shipped thesis file reads to exactly the
// compiled-in damper (Table 3.1, 4.1, 5.4, 5.6, Eq. 4.5), a baseline maps
// onto Eq. 4.2–4.4's constants one for one (checked against hand
// calculations of the force), what the closed loop leaves out is said, and
// every kind of bad file is refused with "<file>:<line>: <field>: ..." where
// the line is counted in the test's own text.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "file_text_helpers.hpp"
#include "host_sim/damper/damper_file.hpp"
#include "host_sim/discrepancy/baseline_file.hpp"
#include "host_sim/io/usage_error.hpp"
#include "mrd/physics/bingham.hpp"

namespace mrd::damper {
namespace {

using test::edited;
using test::file_text;
using test::line_of;

namespace fs = std::filesystem;

const fs::path kDampersDir = MRD_DAMPERS_DIR;

std::string thesis_text() { return file_text(kDampersDir / "thesis-200kn.toml"); }

/// The error of parsing `text` (empty when it parses).
std::string error_of(const std::string& text) { return test::parse_error_of(&parse_damper_toml, text, "d.toml"); }

/// `text` without the table `[name]` (up to the next table or the end).
std::string without_table(std::string text, const std::string& name) {
  const auto at = text.find("\n[" + name + "]");
  EXPECT_NE(at, std::string::npos) << name;
  const auto end = text.find("\n[", at + 1);
  text.erase(at, end == std::string::npos ? std::string::npos : end - at);
  return text;
}

TEST(DamperFile, TheThesisFileIsTheCompiledInDamper) {
  const DamperFile d = read_damper_file(kDampersDir / "thesis-200kn.toml");
  const physics::MrDamperParams a = d.params;
  const physics::MrDamperParams b{};
  EXPECT_EQ(a.bingham.fc_a_n, b.bingham.fc_a_n);
  EXPECT_EQ(a.bingham.fc_b_n, b.bingham.fc_b_n);
  EXPECT_EQ(a.bingham.fc_c_per_a, b.bingham.fc_c_per_a);
  EXPECT_EQ(a.bingham.c0_a_ns_m, b.bingham.c0_a_ns_m);
  EXPECT_EQ(a.bingham.c0_b_ns_m, b.bingham.c0_b_ns_m);
  EXPECT_EQ(a.bingham.c0_c_per_a, b.bingham.c0_c_per_a);
  EXPECT_EQ(a.bingham.v_tf_m_s, b.bingham.v_tf_m_s);
  EXPECT_EQ(a.coil.tau_slow_s, b.coil.tau_slow_s);
  EXPECT_EQ(a.coil.tau_fast_s, b.coil.tau_fast_s);
  EXPECT_EQ(a.coil.weight_slow, b.coil.weight_slow);
  EXPECT_EQ(a.coil.weight_fast, b.coil.weight_fast);
  EXPECT_EQ(a.pr.a_initial, b.pr.a_initial);
  EXPECT_EQ(a.pr.b_initial, b.pr.b_initial);
  EXPECT_EQ(a.pr.c_initial, b.pr.c_initial);
  EXPECT_EQ(a.pr.a_final, b.pr.a_final);
  EXPECT_EQ(a.pr.b_final, b.pr.b_final);
  EXPECT_EQ(a.pr.c_final, b.pr.c_final);
  EXPECT_EQ(a.pr.a_rise, b.pr.a_rise);
  EXPECT_EQ(a.pr.b_rise, b.pr.b_rise);
  EXPECT_EQ(a.pr.c_rise, b.pr.c_rise);
  EXPECT_EQ(a.pr.flow_area_m2, b.pr.flow_area_m2);
  EXPECT_EQ(a.pr.volume_unit_m3, b.pr.volume_unit_m3);
  EXPECT_EQ(a.law, b.law);
  EXPECT_EQ(a.bouc_wen.yield_disp_m, b.bouc_wen.yield_disp_m);
  EXPECT_EQ(a.bouc_wen.stiffness_n_m, b.bouc_wen.stiffness_n_m);
  EXPECT_EQ(a.rating.current_a, b.rating.current_a);
  EXPECT_EQ(a.rating.force_n, b.rating.force_n);
  EXPECT_EQ(a.rating.stroke_m, b.rating.stroke_m);
  EXPECT_EQ(a.rating.velocity_m_s, b.rating.velocity_m_s);
  // The geometry: SettlingParams' defaults (Table 3.1, 5.4), also through with_geometry.
  const physics::SettlingParams s{};
  EXPECT_EQ(d.geometry.inner_diameter_m, s.inner_diameter_m);
  EXPECT_EQ(d.geometry.shaft_radius_m, s.shaft_radius_m);
  EXPECT_EQ(d.geometry.fluid_length_m, s.fluid_length_m);
  EXPECT_EQ(d.geometry.fluid_volume_m3, s.fluid_volume_m3);
  const physics::SettlingParams g = with_geometry(physics::SettlingParams{}, d.geometry);
  EXPECT_EQ(g.inner_diameter_m, s.inner_diameter_m);
  EXPECT_EQ(g.shaft_radius_m, s.shaft_radius_m);
  EXPECT_EQ(g.fluid_length_m, s.fluid_length_m);
  EXPECT_EQ(g.fluid_volume_m3, s.fluid_volume_m3);
  // The coil's circuit of Table 3.1: 4.8 ohm, 5.0 H at 1 A, 3.0 H at 2 A.
  EXPECT_EQ(d.coil_circuit.resistance_ohm, 4.8);
  EXPECT_EQ(d.coil_circuit.inductance_1a_h, 5.0);
  EXPECT_EQ(d.coil_circuit.inductance_2a_h, 3.0);
  EXPECT_EQ(d.name, "thesis-200kn");
  EXPECT_TRUE(d.rating_given);
  EXPECT_TRUE(d.geometry_given);
  EXPECT_TRUE(d.warnings.empty()) << d.warnings.front();
  // And the thesis damper without a file is the same.
  EXPECT_EQ(thesis_damper().geometry.fluid_volume_m3, s.fluid_volume_m3);
  EXPECT_EQ(thesis_damper().params.rating.force_n, b.rating.force_n);
}

/// A small damper written by hand: Bingham with the tanh transition, the
/// optional tables left out.
const char* kSmallDamper = R"([model]
law = "bingham"
name = "small"

[yield_n]
at_zero = 100.0
limit = 1500.0
rate_per_a = 2.0

[viscous_ns_m]
at_zero = 1000.0
limit = 3000.0
rate_per_a = 0.5

[bingham]
v_tf_m_s = 0.005
transition = "tanh"

[coil]
tau_slow_s = 0.05
tau_fast_s = 0.01
weight_slow = 0.5
weight_fast = 0.5
identified = true
resistance_ohm = 12.0
thermal_resistance_k_w = 3.0
thermal_time_constant_s = 600.0

[participant_ratio]
a_initial = 1.0
b_initial = 0.1
c_initial = 7.0
a_final = 1.0
b_final = 0.605
c_final = 4.5
a_rise = 5.474
b_rise = 0.0
c_rise = 3.65
flow_area_m2 = 0.0005
volume_unit_m3 = 0.001
identified = true

[validity]
current_min_a = 0.0
current_max_a = 1.0
velocity_max_m_s = 0.05
force_peak_n = 1700.0
amplitude_min_m = 0.002
amplitude_max_m = 0.025
frequency_min_hz = 0.25
frequency_max_hz = 5.0
expected_gap = 0.15

[rating]
current_a = 1.0
force_n = 2000.0
stroke_m = 0.025
velocity_m_s = 0.05

[geometry]
inner_diameter_m = 0.04
shaft_radius_m = 0.005
fluid_length_m = 0.1
fluid_volume_m3 = 0.0001
)";

// Eq. 4.2 with the file's law, by hand: f_c(1 A) = 1500 + (100 − 1500)·e^−2
// = 1500 − 1400 · 0.1353352832 = 1310.530603 N; at PR = 0.5 the limit is 750:
// 750 − 650 · 0.1353352832 = 662.032066 N. Eq. 4.3: c_0(1 A) = 3000 +
// (1000 − 3000)·e^−0.5 = 3000 − 2000 · 0.6065306597 = 1786.938681 N s/m.
TEST(DamperFile, CurrentLawsMapOntoEq42To44) {
  const DamperFile d = parse_damper_toml(kSmallDamper, "small.toml");
  const physics::BinghamParams& b = d.params.bingham;
  EXPECT_EQ(b.fc_a_n, 100.0);
  EXPECT_EQ(b.fc_b_n, 1500.0);
  EXPECT_EQ(b.fc_c_per_a, 2.0);
  EXPECT_EQ(b.c0_a_ns_m, 1000.0);
  EXPECT_EQ(b.c0_b_ns_m, 3000.0);
  EXPECT_EQ(b.c0_c_per_a, 0.5);
  EXPECT_EQ(b.v_tf_m_s, 0.005);
  EXPECT_NEAR(physics::coulomb_force_n(b, 1.0), 1310.530603, 1e-6);
  EXPECT_NEAR(physics::coulomb_force_n(b, -1.0, 0.5), 662.032066, 1e-6);
  EXPECT_NEAR(physics::viscous_coeff_ns_m(b, 1.0), 1786.938681, 1e-6);
  EXPECT_EQ(d.params.law, physics::ForceLaw::kBinghamTanh);
  EXPECT_EQ(d.params.coil.tau_slow_s, 0.05);
  EXPECT_EQ(d.params.pr.flow_area_m2, 0.0005);
  EXPECT_EQ(d.params.rating.current_a, 1.0);
  EXPECT_EQ(d.params.rating.force_n, 2000.0);
  EXPECT_EQ(d.params.rating.stroke_m, 0.025);
  EXPECT_EQ(d.params.rating.velocity_m_s, 0.05);
  EXPECT_EQ(d.geometry.inner_diameter_m, 0.04);
  EXPECT_EQ(d.geometry.fluid_volume_m3, 0.0001);
  EXPECT_EQ(d.coil_circuit.resistance_ohm, 12.0);
  EXPECT_TRUE(d.warnings.empty()) << d.warnings.front();
  // Eq. 4.4's linear transition is ForceLaw::kBingham, written or left out.
  const std::string linear = edited(kSmallDamper, "transition = \"tanh\"\n", "transition = \"linear\"\n");
  EXPECT_EQ(parse_damper_toml(linear, "s.toml").params.law, physics::ForceLaw::kBingham);
  const std::string plain = edited(kSmallDamper, "transition = \"tanh\"\n", "");
  EXPECT_EQ(parse_damper_toml(plain, "s.toml").params.law, physics::ForceLaw::kBingham);
}

TEST(DamperFile, BoucWenMapsItsTwoConstants) {
  const std::string text = edited(edited(kSmallDamper, "law = \"bingham\"", "law = \"bouc_wen\""),
                                  "[bingham]\nv_tf_m_s = 0.005\ntransition = \"tanh\"",
                                  "[bouc_wen]\nyield_disp_m = 0.0004\nstiffness_n_m = 2000.0");
  const DamperFile d = parse_damper_toml(text, "bw.toml");
  EXPECT_EQ(d.params.law, physics::ForceLaw::kBoucWen);
  EXPECT_EQ(d.params.bouc_wen.yield_disp_m, 0.0004);
  EXPECT_EQ(d.params.bouc_wen.stiffness_n_m, 2000.0);
  EXPECT_EQ(d.params.bingham.fc_b_n, 1500.0);
}

// A calibration's shape of the law (current exponents, viscous exponent,
// spring, transition time, lost motion) reaches the closed loop's damper as
// the file holds it, and is not warned about; without it the shape bends
// nothing.
TEST(DamperFile, CalibratedShapeReachesTheClosedLoop) {
  std::string text = edited(kSmallDamper, "rate_per_a = 2.0\n", "rate_per_a = 2.0\ncurrent_exponent = 1.8\n");
  text = edited(text, "rate_per_a = 0.5\n", "rate_per_a = 0.5\ncurrent_exponent = 0.7\n");
  text = edited(text, "transition = \"tanh\"\n",
                "transition = \"tanh\"\ntransition_time_s = 0.004\nstiffness_n_m = 12000.0\n"
                "viscous_exponent = 0.6\nviscous_ref_m_s = 0.02\nseries_compliance_m_per_n = 3.5e-07\n");
  text += "\n[lost_motion]\nm_per_n = 2e-07\nshare = 1.0\nband_m_s = 0.015\n";
  const DamperFile d = parse_damper_toml(text, "shaped.toml");
  const physics::LawShape& sh = d.params.shape;
  EXPECT_EQ(sh.yield_current_exponent, 1.8);
  EXPECT_EQ(sh.viscous_current_exponent, 0.7);
  EXPECT_EQ(sh.transition_time_s, 0.004);
  EXPECT_EQ(sh.stiffness_n_m, 12000.0);
  EXPECT_EQ(sh.viscous_exponent, 0.6);
  EXPECT_EQ(sh.viscous_ref_m_s, 0.02);
  EXPECT_EQ(sh.lost_motion_m_per_n, 2e-07);
  EXPECT_EQ(sh.lost_motion_share, 1.0);
  EXPECT_EQ(sh.lost_motion_band_m_s, 0.015);
  EXPECT_EQ(sh.series_compliance_m_per_n, 3.5e-07);
  EXPECT_TRUE(sh.bends());
  EXPECT_TRUE(d.warnings.empty()) << d.warnings.front();
  // f_c(0.5 A) = 1500 + (100 − 1500) e^(−2 · 0.5^1.8) = 1500 − 1400 e^(−0.5743491775)
  //            = 1500 − 1400 · 0.5630712090 = 711.700307 N
  EXPECT_NEAR(physics::coulomb_force_n(d.params.bingham, 0.5, 1.0, sh.yield_current_exponent), 711.700307, 1e-6);
  EXPECT_FALSE(parse_damper_toml(kSmallDamper, "small.toml").params.shape.bends());
}

// law = "spencer": its model and current laws reach the closed loop's damper
// as the file holds them (SI); the commands that model the damper by its
// Bingham laws refuse it naming the file, the law's line and the field.
TEST(DamperFile, SpencerMapsItsModelAndIsRefusedWhereBinghamLawsModelIt) {
  discrepancy::BaselineFile f;
  f.baseline = discrepancy::thesis_baseline();
  f.baseline.law = discrepancy::BaseLaw::spencer;
  f.baseline.spencer = discrepancy::published_lab_spencer();
  f.baseline.range = {0.0, 1.0, 0.1, 1500.0, 0.002, 0.025, 0.25, 5.0};
  f.baseline.expected_gap = 0.2;
  f.rating = physics::DamperRating{1.0, 2000.0, 0.025, 0.1};
  const std::string text = discrepancy::baseline_toml(f);
  const DamperFile d = parse_damper_toml(text, "sp.toml");
  EXPECT_EQ(d.params.law, physics::ForceLaw::kSpencer);
  EXPECT_STREQ(physics::force_law_name(d.params.law), "spencer");
  // The published α(1 A) = −38.152 + 41.508 + 15.221 = 18.577 N/mm, c1(0) = 9.867 N·s/mm.
  EXPECT_NEAR(d.params.spencer.alpha_at(1.0), 18577.0, 1e-6);
  EXPECT_NEAR(d.params.spencer.c1_at(0.0), 9867.0, 1e-9);
  EXPECT_EQ(d.params.rating.current_a, 1.0);
  for (const char* ok : {"sim", "sine", "sweep", "study", "settle", "fragility", "rths"})
    EXPECT_NO_THROW(require_law_for(d, ok)) << ok;
  const int law_line = line_of(text, "law = ");
  ASSERT_GT(law_line, 0);
  for (const char* refused : {"configure", "schedule"}) {
    try {
      require_law_for(d, refused);
      ADD_FAILURE() << refused << " took the spencer law";
    } catch (const io::UsageError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("sp.toml:" + std::to_string(law_line) + ": model.law: \"spencer\" is simulated in the closed loop", 0), 0u)
          << m;
      EXPECT_NE(m.find(refused), std::string::npos) << m;
      EXPECT_NE(m.find("mrd calibrate --law bingham"), std::string::npos) << m;  // what serves instead
    }
  }
  // The other laws go everywhere.
  EXPECT_NO_THROW(require_law_for(thesis_damper(), "configure"));
}

// Without [rating] the rating is what the records covered, said in a warning;
// without [geometry] the thesis damper's cylinder, said too; and each part of
// a calibration the closed loop does not simulate is named.
TEST(DamperFile, DerivesWhatIsMissingAndNamesWhatIsLeftOut) {
  std::string text = without_table(without_table(kSmallDamper, "rating"), "geometry");
  text = edited(text, "transition = \"tanh\"\n", "transition = \"tanh\"\ntransition_time_s = 0.005\n");
  // A calibration's file: a coil not identified, and no circuit or heating.
  text = edited(text,
                "identified = true\nresistance_ohm = 12.0\nthermal_resistance_k_w = 3.0\nthermal_time_constant_s = "
                "600.0\n\n[participant_ratio]",
                "identified = false\n\n[participant_ratio]");
  text = edited(text, "flow_area_m2 = 0.0005\nvolume_unit_m3 = 0.001\nidentified = true",
                "flow_area_m2 = 0.0005\nvolume_unit_m3 = 0.001\nidentified = false");
  text += "\n[lost_motion]\nm_per_n = 3e-07\nshare = 0.45\n\n[channels]\nforce_delay_s = 0.006\n";
  const DamperFile d = parse_damper_toml(text, "lab.toml");
  EXPECT_FALSE(d.rating_given);
  EXPECT_EQ(d.params.rating.current_a, 1.0);        // current_max_a
  EXPECT_EQ(d.params.rating.force_n, 1700.0);       // force_peak_n
  EXPECT_EQ(d.params.rating.stroke_m, 0.025);       // amplitude_max_m
  EXPECT_EQ(d.params.rating.velocity_m_s, 0.05);    // velocity_max_m_s
  EXPECT_FALSE(d.geometry_given);
  EXPECT_EQ(d.geometry.inner_diameter_m, 0.2032);   // Table 3.1
  EXPECT_EQ(d.geometry.fluid_volume_m3, 0.0166);    // Table 5.4
  const auto said = [&](const std::string& what) {
    for (const auto& w : d.warnings)
      if (w.find(what) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(said("no [rating]")) << ::testing::PrintToString(d.warnings);
  EXPECT_TRUE(said("1 A, 1700 N, stroke +-0.025 m, 0.05 m/s"));
  EXPECT_TRUE(said("no [geometry]"));
  EXPECT_TRUE(said("thesis damper's cylinder"));
  EXPECT_FALSE(said("lost_motion"));      // simulated (physics/mr_damper.hpp)
  EXPECT_FALSE(said("transition_time"));  // simulated
  EXPECT_TRUE(said("channels.force_delay_s"));
  EXPECT_TRUE(said("coil: identified = false"));
  EXPECT_TRUE(said("participant_ratio: identified = false"));
  EXPECT_TRUE(said("the coil's heating is assumed"));
  EXPECT_EQ(d.warnings.size(), 6u);
  EXPECT_EQ(d.params.shape.lost_motion_m_per_n, 3e-07);
  EXPECT_EQ(d.params.shape.lost_motion_share, 0.45);
  // A rating above what the records cover: the laws are extrapolated.
  const DamperFile above = parse_damper_toml(edited(kSmallDamper, "current_a = 1.0", "current_a = 2.0"), "a.toml");
  ASSERT_EQ(above.warnings.size(), 1u);
  EXPECT_NE(above.warnings[0].find("rating.current_a: 2 A is above the 1 A the records cover"), std::string::npos);
}

// `mrd calibrate` writes no [rating], [geometry] or coil circuit; a file that
// has them reads back to the same values, and the writer writes them.
TEST(DamperFile, RatingGeometryAndCircuitRoundTrip) {
  discrepancy::BaselineFile f = discrepancy::parse_baseline_toml(kSmallDamper, "small.toml");
  f.coil_circuit = {2.5, 0.8, 0.6, 7.5, 600.0};
  const discrepancy::BaselineFile g = discrepancy::parse_baseline_toml(discrepancy::baseline_toml(f), "w.toml");
  ASSERT_TRUE(g.rating && g.geometry);
  EXPECT_EQ(g.rating->current_a, 1.0);
  EXPECT_EQ(g.rating->force_n, 2000.0);
  EXPECT_EQ(g.rating->stroke_m, 0.025);
  EXPECT_EQ(g.rating->velocity_m_s, 0.05);
  EXPECT_EQ(g.geometry->inner_diameter_m, 0.04);
  EXPECT_EQ(g.geometry->shaft_radius_m, 0.005);
  EXPECT_EQ(g.geometry->fluid_length_m, 0.1);
  EXPECT_EQ(g.geometry->fluid_volume_m3, 0.0001);
  EXPECT_EQ(g.coil_circuit.resistance_ohm, 2.5);
  EXPECT_EQ(g.coil_circuit.inductance_1a_h, 0.8);
  EXPECT_EQ(g.coil_circuit.inductance_2a_h, 0.6);
  EXPECT_EQ(g.coil_circuit.thermal_resistance_k_w, 7.5);
  EXPECT_EQ(g.coil_circuit.thermal_time_constant_s, 600.0);
  // Left out when absent: the text of a calibration has none of them.
  f.rating.reset();
  f.geometry.reset();
  f.coil_circuit = {};
  const std::string t = discrepancy::baseline_toml(f);
  EXPECT_EQ(t.find("[rating]"), std::string::npos);
  EXPECT_EQ(t.find("[geometry]"), std::string::npos);
  EXPECT_EQ(t.find("resistance_ohm"), std::string::npos);
  EXPECT_EQ(t.find("thermal_"), std::string::npos);
}

TEST(DamperFile, AMissingFileIsNamed) {
  try {
    (void)read_damper_file(kDampersDir / "no-such-damper.toml");
    FAIL() << "read a missing file";
  } catch (const io::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-damper.toml"), std::string::npos) << e.what();
  }
}

// Each kind of bad damper file: the message is "d.toml:LINE: field: ..." with
// LINE the line the test's text has the key on (or its table's header for a
// missing key), and names what was expected (the range, for a number).
TEST(DamperFile, RefusesBadFilesNamingFileLineAndField) {
  const std::string t = thesis_text();
  const std::vector<test::Refusal> cases = {
      {"syntax error", edited(t, "force_n = 200000.0", "force_n = = 200000.0"), "force_n = ", "", ""},
      {"unknown table", t + "\n[ratings]\ncurrent_a = 2.5\n", "[ratings]", "ratings",
       "unknown table (expected model,"},
      {"renamed key", edited(t, "velocity_m_s = 0.2491 ", "velocity_max_m_s = 0.2491 "), "[rating]",
       "rating.velocity_m_s", "missing key"},
      {"unknown key beside the known", edited(t, "current_a = 2.5 ", "peak_current_a = 3.0\ncurrent_a = 2.5 "),
       "peak_current_a", "rating.peak_current_a", "unknown key"},
      {"wrong type", edited(t, "force_n = 200000.0", "force_n = \"200 kN\""), "force_n = ", "rating.force_n",
       "expected a number"},
      {"boolean for a number", edited(t, "current_a = 2.5 ", "current_a = true "), "current_a = ",
       "rating.current_a", "expected a number"},
      {"non-finite", edited(t, "stroke_m = 0.2921", "stroke_m = nan"), "stroke_m = ", "rating.stroke_m",
       "expected a finite number"},
      {"negative rating", edited(t, "force_n = 200000.0", "force_n = -200000.0"), "force_n = ", "rating.force_n",
       "expected a force in [1, 1e+08] N, got -2e+05"},
      {"stroke beyond any damper", edited(t, "stroke_m = 0.2921", "stroke_m = 2.921"), "stroke_m = ",
       "rating.stroke_m", "expected a half stroke in [0.0001, 1] m, got 2.921"},
      {"zero rated current", edited(t, "current_a = 2.5 ", "current_a = 0.0 "), "current_a = ", "rating.current_a",
       "expected a current in [0.001, 1000] A, got 0.0"},
      {"coil weights not summing to 1", edited(t, "weight_fast = 0.5", "weight_fast = 0.6"), "weight_fast = ",
       "coil.weight_fast", "expected weight_slow + weight_fast = 1"},
      {"one inductance", edited(t, "inductance_2a_h = 3.0   # L at 2 A\n", ""), "[coil]", "coil.inductance_2a_h",
       "missing key (inductance_1a_h needs it"},
      {"inductance growing with current", edited(t, "inductance_2a_h = 3.0", "inductance_2a_h = 6.0"),
       "inductance_2a_h", "coil.inductance_2a_h", "expected at most inductance_1a_h (5.0 H)"},
      {"zero resistance", edited(t, "resistance_ohm = 4.8", "resistance_ohm = 0"), "resistance_ohm",
       "coil.resistance_ohm", "expected a resistance in [0.001, 10000] ohm, got 0.0"},
      // The coil's heating: R_th is for this coil's R (the rise is i² R R_th), so not without it.
      {"thermal resistance without the resistance", edited(t, "resistance_ohm = 4.8\n", ""), "[coil]",
       "coil.resistance_ohm", "missing key (thermal_resistance_k_w needs it"},
      {"zero thermal resistance", edited(t, "thermal_resistance_k_w = 2.0", "thermal_resistance_k_w = 0.0"),
       "thermal_resistance_k_w", "coil.thermal_resistance_k_w", "expected a thermal resistance in [0.001, 1000] K/W"},
      {"thermal time constant of half a second",
       edited(t, "thermal_time_constant_s = 1200.0", "thermal_time_constant_s = 0.5"), "thermal_time_constant_s",
       "coil.thermal_time_constant_s", "expected a time constant in [1, 100000] s, got 0.5"},
      {"shaft as wide as the bore", edited(t, "shaft_radius_m = 0.04", "shaft_radius_m = 0.1016"), "shaft_radius_m",
       "geometry.shaft_radius_m", "expected less than half inner_diameter_m (0.1016 m)"},
      {"geometry key missing", edited(t, "fluid_volume_m3 = 0.0166  # Table 5.4 (a), method 1\n", ""), "[geometry]",
       "geometry.fluid_volume_m3", "missing key"},
      {"zero bore", edited(t, "inner_diameter_m = 0.2032", "inner_diameter_m = 0.0"), "inner_diameter_m",
       "geometry.inner_diameter_m", "expected a diameter in [0.001, 2] m, got 0.0"},
      {"no rating, no amplitude stated", without_table(t, "rating"), "amplitude_max_m",
       "validity.amplitude_max_m", "the file has no [rating], and 0.0 is no rating: expected a half stroke"},
      {"no rating, no current", edited(without_table(t, "rating"), "current_max_a = 2.5 ", "current_max_a = 0.0 "),
       "current_max_a", "validity.current_max_a", "add a [rating] table"},
      {"unknown law", edited(t, "law = \"bingham\"", "law = \"spring\""), "law = ", "model.law",
       "expected \"bingham\", \"bouc_wen\" or \"spencer\", got \"spring\""},
      {"unknown transition", edited(t, "transition = \"linear\"", "transition = \"cubic\""), "transition = ",
       "bingham.transition", "expected \"linear\" or \"tanh\""},
      {"participant ratio above 1", edited(t, "a_initial = 1.0", "a_initial = 1.5"), "a_initial",
       "participant_ratio.a_initial", "expected a participant ratio in [0, 1], got 1.5"},
      {"rating not a table", "rating = 3\n" + without_table(t, "rating"), "rating = 3", "rating",
       "expected a table [rating]"},
  };
  test::expect_refusals(cases, error_of, "d.toml");
  // A missing table is named at line 1.
  EXPECT_EQ(error_of(without_table(t, "coil")), "d.toml:1: [coil]: missing table");
}

// The coil's heating (mrd/physics/coil_heat.hpp). Hand values:
// - no resistance, no thermal data, rated 1 A: R = 4.8 ohm (the thesis coil's),
//   R_th = 60 K / ((1 A)² · 4.8 ohm) = 12.5 K/W, τ = 1200 s; the steady rise
//   at the rated current is then (1 A)² · 4.8 · 12.5 = 60 K;
// - 12 ohm, no thermal data: R_th = 60 / (1 · 12) = 5 K/W;
// - 12 ohm, 3 K/W, 600 s: as given.
TEST(DamperFile, TheCoilHeatsAsItsFileSaysOrAsTheThesisCoilAtItsRating) {
  const auto heat_warning = [](const DamperFile& d) {
    for (const std::string& w : d.warnings)
      if (w.find("heating is assumed") != std::string::npos) return w;
    return std::string();
  };
  const std::string full_coil = "resistance_ohm = 12.0\nthermal_resistance_k_w = 3.0\nthermal_time_constant_s = 600.0\n";
  const DamperFile given = parse_damper_toml(kSmallDamper, "full.toml");
  EXPECT_EQ(given.params.coil_heat, (physics::CoilHeatParams{12.0, 3.0, 600.0}));
  EXPECT_EQ(heat_warning(given), "");

  const DamperFile bare = parse_damper_toml(edited(kSmallDamper, full_coil, ""), "small.toml");
  EXPECT_EQ(bare.params.coil_heat.resistance_ohm, 4.8);
  EXPECT_DOUBLE_EQ(bare.params.coil_heat.thermal_resistance_k_w, 12.5);
  EXPECT_EQ(bare.params.coil_heat.time_constant_s, 1200.0);
  EXPECT_NE(heat_warning(bare).find("1 A held continuously settling 60 K"), std::string::npos) << heat_warning(bare);
  EXPECT_NE(heat_warning(bare).find("the thesis coil's"), std::string::npos) << heat_warning(bare);

  const DamperFile r = parse_damper_toml(edited(kSmallDamper, full_coil, "resistance_ohm = 12.0\n"), "r.toml");
  EXPECT_EQ(r.params.coil_heat.resistance_ohm, 12.0);
  EXPECT_DOUBLE_EQ(r.params.coil_heat.thermal_resistance_k_w, 5.0);
  EXPECT_EQ(r.params.coil_heat.time_constant_s, 1200.0);
  EXPECT_NE(heat_warning(r).find("R_th 5 K/W at 12 ohm"), std::string::npos) << heat_warning(r);

  // τ alone keeps the rating's R_th.
  const DamperFile tau = parse_damper_toml(
      edited(kSmallDamper, full_coil, "resistance_ohm = 12.0\nthermal_time_constant_s = 60.0\n"), "tau.toml");
  EXPECT_DOUBLE_EQ(tau.params.coil_heat.thermal_resistance_k_w, 5.0);
  EXPECT_EQ(tau.params.coil_heat.time_constant_s, 60.0);
  EXPECT_NE(heat_warning(tau), "");

  // The thesis file: Table 3.1's 4.8 ohm with the assumed 2 K/W and 20 min, the compiled-in coil to the bit.
  const DamperFile thesis = read_damper_file(kDampersDir / "thesis-200kn.toml");
  EXPECT_EQ(thesis.params.coil_heat, physics::CoilHeatParams{});
  EXPECT_EQ(physics::rated_rise_thermal_resistance_k_w(2.5, 4.8), 2.0);
}

}  // namespace
}  // namespace mrd::damper
