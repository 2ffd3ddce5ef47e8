// The building file: the shipped files read to the values written in them
// (the thesis file to exactly the compiled-in defaults, Table 6.1 and
// Fig. 6.2), the writer's text reads back to the same values, and every kind
// of bad file is refused with "<file>:<line>: <field>: ..." where the line is
// counted in the test's own text.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "host_sim/io/usage_error.hpp"
#include "host_sim/structure/building_file.hpp"

namespace mrd::structure {
namespace {

namespace fs = std::filesystem;

const fs::path kBuildingsDir = MRD_BUILDINGS_DIR;

// ---- comparing two buildings, exactly ------------------------------------------

void expect_same_isolator(const Isolator& a, const Isolator& b, std::size_t i) {
  ASSERT_EQ(a.index(), b.index()) << "isolator " << i;
  if (const auto* l = std::get_if<LeadRubberBearing>(&a)) {
    const auto& m = std::get<LeadRubberBearing>(b);
    EXPECT_EQ(l->count, m.count) << i;
    EXPECT_EQ(l->characteristic_strength_n, m.characteristic_strength_n) << i;
    EXPECT_EQ(l->post_yield_stiffness_n_m, m.post_yield_stiffness_n_m) << i;
    EXPECT_EQ(l->yield_displacement_m, m.yield_displacement_m) << i;
    EXPECT_EQ(l->exponent, m.exponent) << i;
    EXPECT_EQ(l->displacement_capacity_m, m.displacement_capacity_m) << i;
  } else {
    const auto& f = std::get<FrictionPendulumBearing>(a);
    const auto& g = std::get<FrictionPendulumBearing>(b);
    EXPECT_EQ(f.count, g.count) << i;
    EXPECT_EQ(f.radius_m, g.radius_m) << i;
    EXPECT_EQ(f.friction_slow, g.friction_slow) << i;
    EXPECT_EQ(f.friction_fast, g.friction_fast) << i;
    EXPECT_EQ(f.rate_s_per_m, g.rate_s_per_m) << i;
    EXPECT_EQ(f.yield_displacement_m, g.yield_displacement_m) << i;
    EXPECT_EQ(f.exponent, g.exponent) << i;
    EXPECT_EQ(f.weight_n, g.weight_n) << i;
    EXPECT_EQ(f.displacement_capacity_m, g.displacement_capacity_m) << i;
  }
}

void expect_same_building(const BuildingParams& a, const BuildingParams& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.base, b.base);
  EXPECT_EQ(a.mass_kg, b.mass_kg);
  EXPECT_EQ(a.story_stiffness_n_m, b.story_stiffness_n_m);
  EXPECT_EQ(a.story_damping_n_s_m, b.story_damping_n_s_m);
  ASSERT_EQ(a.rayleigh.has_value(), b.rayleigh.has_value());
  if (a.rayleigh) {
    EXPECT_EQ(a.rayleigh->ratio, b.rayleigh->ratio);
    EXPECT_EQ(a.rayleigh->mode_a, b.rayleigh->mode_a);
    EXPECT_EQ(a.rayleigh->mode_b, b.rayleigh->mode_b);
  }
  ASSERT_EQ(a.isolators.size(), b.isolators.size());
  for (std::size_t i = 0; i < a.isolators.size(); ++i) expect_same_isolator(a.isolators[i], b.isolators[i], i);
  ASSERT_EQ(a.dampers.size(), b.dampers.size());
  for (std::size_t i = 0; i < a.dampers.size(); ++i) {
    EXPECT_EQ(a.dampers[i].element, b.dampers[i].element) << i;
    EXPECT_EQ(a.dampers[i].count, b.dampers[i].count) << i;
  }
}

// ---- the shipped files -----------------------------------------------------------

TEST(BuildingFileShipped, ThesisFileIsExactlyTheDefaultBuilding) {
  // BuildingParams{} holds Table 6.1 / Fig. 6.2; the file writes the same
  // decimal numbers, so every double must be bit-identical.
  expect_same_building(read_building_file(kBuildingsDir / "thesis-6dof.toml"), BuildingParams{});
}

TEST(BuildingFileShipped, LeadRubberExampleReadsItsBearings) {
  const BuildingParams b = read_building_file(kBuildingsDir / "lead-rubber-7dof.toml");
  EXPECT_EQ(b.name, "lead-rubber-7dof");
  EXPECT_EQ(b.base, BaseKind::kIsolated);
  EXPECT_EQ(b.dofs(), 7);
  EXPECT_EQ(b.mass_kg.front(), 600.0e3);
  EXPECT_EQ(b.story_stiffness_n_m.front(), 0.0);
  EXPECT_FALSE(b.rayleigh.has_value());
  ASSERT_EQ(b.isolators.size(), 1u);
  const auto& l = std::get<LeadRubberBearing>(b.isolators[0]);
  EXPECT_EQ(l.count, 24u);
  EXPECT_EQ(l.characteristic_strength_n, 72.0e3);
  EXPECT_EQ(l.post_yield_stiffness_n_m, 0.74e6);
  EXPECT_EQ(l.yield_displacement_m, 0.011);
  EXPECT_EQ(l.exponent, 2.0);
  EXPECT_EQ(l.displacement_capacity_m, 0.45);
  // The file's claim: a post-yield period of 2.80 s for the rigid building,
  // 2 pi sqrt(sum m / (24 k_p)) with sum m = 600 + 5 x 500 + 430 t = 3530 t.
  double m = 0.0;
  for (const double x : b.mass_kg) m += x;
  EXPECT_EQ(m, 3530.0e3);
  EXPECT_NEAR(2.0 * std::numbers::pi * std::sqrt(m / (24 * l.post_yield_stiffness_n_m)), 2.80, 0.005);
  ASSERT_EQ(b.dampers.size(), 1u);
  EXPECT_EQ(b.dampers[0].element, 0u);
  EXPECT_EQ(b.dampers[0].count, 1u);
}

TEST(BuildingFileShipped, FrictionPendulumExampleReadsItsBearingsAndTwoDampers) {
  const BuildingParams b = read_building_file(kBuildingsDir / "friction-pendulum-5dof.toml");
  EXPECT_EQ(b.name, "friction-pendulum-5dof");
  EXPECT_EQ(b.dofs(), 5);
  ASSERT_EQ(b.isolators.size(), 1u);
  const auto& f = std::get<FrictionPendulumBearing>(b.isolators[0]);
  EXPECT_EQ(f.count, 12u);
  EXPECT_EQ(f.radius_m, 2.24);
  EXPECT_EQ(f.friction_slow, 0.03);
  EXPECT_EQ(f.friction_fast, 0.07);
  EXPECT_EQ(f.rate_s_per_m, 30.0);
  EXPECT_EQ(f.yield_displacement_m, 0.0005);
  EXPECT_EQ(f.weight_n, 0.0);  // not given: the building's weight / count
  EXPECT_EQ(f.displacement_capacity_m, 0.5);
  // The file's claim: the pendulum period 2 pi sqrt(R / g) is 3.00 s.
  EXPECT_NEAR(2.0 * std::numbers::pi * std::sqrt(f.radius_m / 9.80665), 3.00, 0.005);
  ASSERT_EQ(b.dampers.size(), 1u);
  EXPECT_EQ(b.dampers[0].element, 0u);
  EXPECT_EQ(b.dampers[0].count, 2u);
}

TEST(BuildingFileShipped, FixedBaseExampleReadsRayleighAndDampersOnTwoStories) {
  const BuildingParams b = read_building_file(kBuildingsDir / "fixed-base-8dof.toml");
  EXPECT_EQ(b.base, BaseKind::kFixed);
  EXPECT_EQ(b.dofs(), 8);
  EXPECT_TRUE(b.isolators.empty());
  ASSERT_TRUE(b.rayleigh.has_value());
  EXPECT_EQ(b.rayleigh->ratio, 0.05);
  EXPECT_EQ(b.rayleigh->mode_a, 1);
  EXPECT_EQ(b.rayleigh->mode_b, 3);
  EXPECT_EQ(b.story_damping_n_s_m, std::vector<double>(8, 0.0));  // unused with Rayleigh damping
  ASSERT_EQ(b.dampers.size(), 2u);
  EXPECT_EQ(b.dampers[0].element, 0u);
  EXPECT_EQ(b.dampers[0].count, 2u);
  EXPECT_EQ(b.dampers[1].element, 1u);
  EXPECT_EQ(b.dampers[1].count, 2u);
}

TEST(BuildingFileShipped, EveryShippedFileReadsBackFromItsWrittenText) {
  for (const char* name :
       {"thesis-6dof.toml", "lead-rubber-7dof.toml", "friction-pendulum-5dof.toml", "fixed-base-8dof.toml"}) {
    SCOPED_TRACE(name);
    const BuildingParams b = read_building_file(kBuildingsDir / name);
    expect_same_building(parse_building_toml(building_toml(b), "written.toml"), b);
  }
}

// ---- defaults and the writer --------------------------------------------------------

const char* const kMinimal = R"(
[building]
name = "one mass"
mass_kg = [1000]
stiffness_n_m = [40000]
damping_n_s_m = [0]
)";

TEST(BuildingFileDefaults, IsolatedBaseAndOneDamperAtElementZeroWhenNotGiven) {
  const BuildingParams b = parse_building_toml(kMinimal, "minimal.toml");
  EXPECT_EQ(b.name, "one mass");
  EXPECT_EQ(b.base, BaseKind::kIsolated);
  EXPECT_EQ(b.mass_kg, std::vector<double>{1000.0});  // integers read as numbers
  EXPECT_EQ(b.story_stiffness_n_m, std::vector<double>{40000.0});
  EXPECT_TRUE(b.isolators.empty());
  ASSERT_EQ(b.dampers.size(), 1u);
  EXPECT_EQ(b.dampers[0].element, 0u);
  EXPECT_EQ(b.dampers[0].count, 1u);
}

TEST(BuildingFileDefaults, IsolatorExponentIsTwoAndDamperCountOne) {
  const BuildingParams b = parse_building_toml(std::string(kMinimal) + R"(
[[isolator]]
kind = "friction_pendulum"
count = 4
radius_m = 1.5
friction_slow = 0.05
friction_fast = 0.05
rate_s_per_m = 0
yield_displacement_m = 0.0005

[[damper]]
element = 0
)",
                                               "minimal.toml");
  ASSERT_EQ(b.isolators.size(), 1u);
  EXPECT_EQ(std::get<FrictionPendulumBearing>(b.isolators[0]).exponent, 2.0);
  ASSERT_EQ(b.dampers.size(), 1u);
  EXPECT_EQ(b.dampers[0].count, 1u);
}

TEST(BuildingFileDefaults, ByteOrderMarkAndInlineRayleighTableAreAccepted) {
  const BuildingParams b = parse_building_toml("\xEF\xBB\xBF" R"([building]
name = "two"
base = "fixed"
mass_kg = [1.0e5, 1.0e5]
stiffness_n_m = [1.0e8, 1.0e8]
rayleigh = { ratio = 0.03, modes = [2, 1] }
)",
                                               "bom.toml");
  ASSERT_TRUE(b.rayleigh.has_value());
  EXPECT_EQ(b.rayleigh->ratio, 0.03);
  EXPECT_EQ(b.rayleigh->mode_a, 2);
  EXPECT_EQ(b.rayleigh->mode_b, 1);
}

TEST(BuildingFileWriter, EveryFeatureReadsBackExactly) {
  BuildingParams b;
  b.name = "a \"quoted\" \\ name";
  b.base = BaseKind::kIsolated;
  // 40 DOFs: the arrays are written over several lines.
  b.mass_kg.assign(40, 1.0e5 / 3.0);
  b.story_stiffness_n_m.assign(40, 2.0e8 / 7.0);
  b.story_stiffness_n_m[0] = 0.0;
  b.story_damping_n_s_m.assign(40, 0.1);
  b.rayleigh.reset();
  LeadRubberBearing l;
  l.count = 20;
  l.characteristic_strength_n = 1.0e4 / 3.0;
  l.post_yield_stiffness_n_m = 1.23456789e5;
  l.yield_displacement_m = 0.0123;
  l.exponent = 1.5;
  l.displacement_capacity_m = 0.4;
  FrictionPendulumBearing f;
  f.count = 8;
  f.radius_m = 2.2;
  f.friction_slow = 0.03;
  f.friction_fast = 0.06;
  f.rate_s_per_m = 25.0;
  f.yield_displacement_m = 5.0e-4;
  f.exponent = 3.0;
  f.weight_n = 1.0e5;
  FrictionPendulumBearing g = f;
  g.count = 2;
  g.weight_n = 2.5e5;
  g.displacement_capacity_m = 0.6;
  b.isolators = {l, f, g};
  b.dampers = {DamperPlacement{0, 2}, DamperPlacement{39, 1}, DamperPlacement{7, 3}};
  expect_same_building(parse_building_toml(building_toml(b), "written.toml"), b);

  // Rayleigh damping, a fixed base: the dashpots read back as zeros.
  BuildingParams r;
  r.base = BaseKind::kFixed;
  r.rayleigh = RayleighDamping{0.05, 1, 3};
  r.story_damping_n_s_m.assign(6, 0.0);
  expect_same_building(parse_building_toml(building_toml(r), "written.toml"), r);
}

TEST(BuildingFileWriter, RefusesABuildingWithoutDampers) {
  BuildingParams b;
  b.dampers.clear();
  EXPECT_THROW((void)building_toml(b), std::invalid_argument);
}

// ---- bad files -----------------------------------------------------------------------

// A valid building: 3 masses, W = 7e5 kg x 9.80665 = 6.865e6 N. The
// lead-rubber bearings' strength 10 x 40 kN = 0.058 W; the restoring stiffness
// 1e6 + 10 x 1e6 + 6.865e6 / 2.0 = 1.443e7 N/m, a period of
// 2 pi sqrt(7e5 / 1.443e7) = 1.38 s.
const std::string kBuilding = R"(# a three-mass test building
[building]
name = "test-3dof"
mass_kg = [3.0e5, 2.0e5, 2.0e5]
stiffness_n_m = [1.0e6, 4.0e8, 3.0e8]
damping_n_s_m = [1.0e5, 1.0e6, 1.0e6]
)";
const std::string kLead = R"(
[[isolator]]
kind = "lead_rubber"
count = 10
characteristic_strength_n = 4.0e4
post_yield_stiffness_n_m = 1.0e6
yield_displacement_m = 0.01
)";
const std::string kPendulum = R"(
[[isolator]]
kind = "friction_pendulum"
count = 4
radius_m = 2.0
friction_slow = 0.03
friction_fast = 0.06
rate_s_per_m = 25.0
yield_displacement_m = 0.0005
)";
const std::string kDamper = R"(
[[damper]]
element = 0
count = 1
)";
const std::string kGood = kBuilding + kLead + kPendulum + kDamper;

/// `text` with the first `from` replaced by `to` (`from` must be there).
std::string with(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("test text lacks: " + from);
  return text.replace(at, from.size(), to);
}

/// The 1-based line of the first `needle` in `text`.
std::size_t line_of_text(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  if (at == std::string::npos) throw std::logic_error("test text lacks: " + needle);
  std::size_t line = 1;
  for (std::size_t i = 0; i < at; ++i) line += text[i] == '\n';
  return line;
}

std::string many_masses(std::size_t n) {
  std::string s = "[";
  for (std::size_t i = 0; i < n; ++i) s += i ? ", 1.0e5" : "1.0e5";
  return s + "]";
}

struct BadFile {
  const char* name;    ///< the test's name
  std::string text;    ///< the file
  std::string needle;  ///< the error's line is the first line holding it
  std::string field;   ///< the field the message names ("" for a TOML syntax error)
  std::string what;    ///< a part of the explanation
};

void PrintTo(const BadFile& c, std::ostream* os) { *os << c.name; }

std::vector<BadFile> bad_files() {
  const std::string g = kGood;
  const std::string pend2 = with(kPendulum, "count = 4", "count = 2\nweight_n = 1.0e6");
  return {
      // Not TOML.
      {"SyntaxError", with(g, "count = 10", "count = = 10"), "count = = 10", "", "not valid TOML"},
      {"DuplicateKey", with(g, "count = 10", "count = 10\ncount = 11"), "count = 11", "", "not valid TOML"},
      // Unknown tables and keys.
      {"UnknownTable", g + "\n[options]\nfast = true\n", "[options]", "options", "unknown table"},
      {"UnknownBuildingKey", with(g, "name = \"test-3dof\"", "name = \"test-3dof\"\nheight_m = 12.0"), "height_m",
       "building.height_m", "unknown key"},
      {"UnknownIsolatorKey", with(g, "kind = \"lead_rubber\"", "kind = \"lead_rubber\"\ncolour = \"red\""), "colour",
       "isolator[0].colour", "unknown key"},
      {"UnknownDamperKey", with(g, "element = 0", "element = 0\nstroke_m = 0.1"), "stroke_m", "damper[0].stroke_m",
       "unknown key"},
      {"UnknownRayleighKey",
       with(g, "damping_n_s_m = [1.0e5, 1.0e6, 1.0e6]", "rayleigh = { ratio = 0.02, modes = [1, 2], mode = 3 }"),
       "rayleigh =", "building.rayleigh.mode", "unknown key"},
      {"IsolatorNotAnArrayOfTables", kBuilding + "\n[isolator]\nkind = \"lead_rubber\"\n", "[isolator]", "isolator",
       "expected [[isolator]] tables"},
      {"EmptyDamperArray", "damper = []\n" + kBuilding, "damper = []", "damper", "expected [[damper]] tables"},
      // Missing tables and keys.
      {"MissingBuilding", kDamper, "\n", "building", "missing table [building]"},
      {"MissingName", with(g, "name = \"test-3dof\"\n", ""), "[building]", "building.name", "missing key"},
      {"MissingIsolatorKey", with(g, "yield_displacement_m = 0.01\n", ""), "[[isolator]]",
       "isolator[0].yield_displacement_m", "missing key"},
      {"MissingIsolatorKind", with(g, "kind = \"lead_rubber\"\n", ""), "[[isolator]]", "isolator[0].kind",
       "missing key"},
      {"MissingDamperElement", with(g, "element = 0\n", ""), "[[damper]]", "damper[0].element", "missing key"},
      // Wrong types.
      {"NameNotAString", with(g, "name = \"test-3dof\"", "name = 12"), "name = 12", "building.name",
       "expected a string"},
      {"MassesNotAnArray", with(g, "mass_kg = [3.0e5, 2.0e5, 2.0e5]", "mass_kg = 3.0e5"), "mass_kg",
       "building.mass_kg", "expected an array"},
      {"MassAString", with(g, "[3.0e5, 2.0e5, 2.0e5]", "[3.0e5, \"2.0e5\", 2.0e5]"), "mass_kg",
       "building.mass_kg[1]", "expected a number"},
      {"BuildingNotATable", "building = 3\n", "building = 3", "building", "expected a table"},
      // Masses, stiffnesses, dashpots.
      {"NanMass", with(g, "[3.0e5, 2.0e5, 2.0e5]", "[3.0e5, nan, 2.0e5]"), "mass_kg", "building.mass_kg[1]",
       "finite"},
      {"InfiniteMass", with(g, "[3.0e5, 2.0e5, 2.0e5]", "[3.0e5, 2.0e5, inf]"), "mass_kg", "building.mass_kg[2]",
       "finite"},
      {"NegativeMass", with(g, "[3.0e5, 2.0e5, 2.0e5]", "[-3.0e5, 2.0e5, 2.0e5]"), "mass_kg", "building.mass_kg[0]",
       "expected a value in (0, 1e+09] kg"},
      {"ZeroMass", with(g, "[3.0e5, 2.0e5, 2.0e5]", "[3.0e5, 0.0, 2.0e5]"), "mass_kg", "building.mass_kg[1]",
       "found 0"},
      {"MassAboveABuilding", with(g, "[3.0e5, 2.0e5, 2.0e5]", "[3.0e5, 2.0e5, 2.0e10]"), "mass_kg",
       "building.mass_kg[2]", "(0, 1e+09] kg"},
      {"NegativeStiffness", with(g, "[1.0e6, 4.0e8, 3.0e8]", "[1.0e6, 4.0e8, -3.0e8]"), "stiffness_n_m",
       "building.stiffness_n_m[2]", "expected a value > 0 N/m"},
      {"ZeroStoryStiffness", with(g, "[1.0e6, 4.0e8, 3.0e8]", "[1.0e6, 0.0, 3.0e8]"), "stiffness_n_m",
       "building.stiffness_n_m[1]", "story"},
      {"NegativeElementZeroStiffness", with(g, "[1.0e6, 4.0e8, 3.0e8]", "[-1.0e6, 4.0e8, 3.0e8]"), "stiffness_n_m",
       "building.stiffness_n_m[0]", "expected a value >= 0 N/m"},
      {"NegativeDamping", with(g, "[1.0e5, 1.0e6, 1.0e6]", "[-1.0e5, 1.0e6, 1.0e6]"), "damping_n_s_m",
       "building.damping_n_s_m[0]", "expected a value >= 0 N s/m"},
      {"StiffnessesShort", with(g, "[1.0e6, 4.0e8, 3.0e8]", "[1.0e6, 4.0e8]"), "stiffness_n_m",
       "building.stiffness_n_m", "expected 3 values"},
      {"DampingLong", with(g, "[1.0e5, 1.0e6, 1.0e6]", "[1.0e5, 1.0e6, 1.0e6, 1.0e6]"), "damping_n_s_m",
       "building.damping_n_s_m", "expected 3 values"},
      {"NoMasses", with(g, "[3.0e5, 2.0e5, 2.0e5]", "[]"), "mass_kg", "building.mass_kg", "at least one"},
      {"TooManyDofs", with(g, "[3.0e5, 2.0e5, 2.0e5]", many_masses(201)), "mass_kg", "building.mass_kg",
       "at most 200"},
      // The building's name and base.
      {"EmptyName", with(g, "name = \"test-3dof\"", "name = \"\""), "name =", "building.name", "1 to 100 bytes"},
      {"NameWithLineBreak", with(g, "name = \"test-3dof\"", "name = \"test\\n3dof\""), "name =", "building.name",
       "control characters"},
      {"UnknownBase", with(g, "name = \"test-3dof\"", "name = \"test-3dof\"\nbase = \"floating\""), "base =",
       "building.base", "\"isolated\" or \"fixed\""},
      // Damping forms.
      {"BothDampingForms",
       with(g, "damping_n_s_m = [1.0e5, 1.0e6, 1.0e6]\n",
            "damping_n_s_m = [1.0e5, 1.0e6, 1.0e6]\n\n[building.rayleigh]\nratio = 0.02\nmodes = [1, 2]\n"),
       "[building.rayleigh]", "building.rayleigh", "one of the two damping forms"},
      {"NoDampingForm", with(g, "damping_n_s_m = [1.0e5, 1.0e6, 1.0e6]\n", ""), "[building]",
       "building.damping_n_s_m", "missing key"},
      {"RayleighRatioZero",
       with(g, "damping_n_s_m = [1.0e5, 1.0e6, 1.0e6]", "rayleigh = { ratio = 0.0, modes = [1, 2] }"),
       "rayleigh =", "building.rayleigh.ratio", "(0, 1)"},
      {"RayleighRatioOne",
       with(g, "damping_n_s_m = [1.0e5, 1.0e6, 1.0e6]", "[building.rayleigh]\nratio = 1.0\nmodes = [1, 2]"),
       "ratio = 1.0", "building.rayleigh.ratio", "(0, 1)"},
      {"RayleighModesEqual",
       with(g, "damping_n_s_m = [1.0e5, 1.0e6, 1.0e6]", "[building.rayleigh]\nratio = 0.02\nmodes = [2, 2]"),
       "modes =", "building.rayleigh.modes", "two different modes"},
      {"RayleighModeAboveN",
       with(g, "damping_n_s_m = [1.0e5, 1.0e6, 1.0e6]", "[building.rayleigh]\nratio = 0.02\nmodes = [1, 4]"),
       "modes =", "building.rayleigh.modes[1]", "1..3"},
      {"RayleighModeZero",
       with(g, "damping_n_s_m = [1.0e5, 1.0e6, 1.0e6]", "[building.rayleigh]\nratio = 0.02\nmodes = [0, 1]"),
       "modes =", "building.rayleigh.modes[0]", "1..3"},
      {"RayleighThreeModes",
       with(g, "damping_n_s_m = [1.0e5, 1.0e6, 1.0e6]", "[building.rayleigh]\nratio = 0.02\nmodes = [1, 2, 3]"),
       "modes =", "building.rayleigh.modes", "two modes"},
      // Isolators.
      {"UnknownIsolatorKind", with(g, "kind = \"lead_rubber\"", "kind = \"high_damping_rubber\""), "kind =",
       "isolator[0].kind", "\"lead_rubber\" or \"friction_pendulum\""},
      {"LeadRubberWithPendulumKey", with(g, "count = 10", "count = 10\nradius_m = 2.0"), "radius_m = 2.0\n",
       "isolator[0].radius_m", "friction_pendulum key"},
      {"PendulumWithLeadRubberKey", with(g, "count = 4", "count = 4\npost_yield_stiffness_n_m = 1.0e6"),
       "post_yield_stiffness_n_m = 1.0e6\nradius", "isolator[1].post_yield_stiffness_n_m", "lead_rubber key"},
      {"IsolatorCountZero", with(g, "count = 10", "count = 0"), "count = 0", "isolator[0].count", "found 0"},
      {"IsolatorCountNotInteger", with(g, "count = 10", "count = 2.5"), "count = 2.5", "isolator[0].count",
       "an integer"},
      {"IsolatorCountNegative", with(g, "count = 4", "count = -4"), "count = -4", "isolator[1].count", "found -4"},
      {"IsolatorCountAString", with(g, "count = 4", "count = \"4\""), "count = \"4\"", "isolator[1].count",
       "an integer"},
      {"FrictionSlowAboveFast", with(g, "friction_slow = 0.03", "friction_slow = 0.08"), "friction_slow",
       "isolator[1].friction_slow", "at most friction_fast"},
      {"FrictionNegative", with(g, "friction_slow = 0.03", "friction_slow = -0.01"), "friction_slow",
       "isolator[1].friction_slow", "[0, 1)"},
      {"FrictionOne", with(g, "friction_fast = 0.06", "friction_fast = 1.0"), "friction_fast",
       "isolator[1].friction_fast", "[0, 1)"},
      {"RadiusZero", with(g, "radius_m = 2.0", "radius_m = 0.0"), "radius_m", "isolator[1].radius_m", "(0, 100]"},
      {"RadiusInMillimetres", with(g, "radius_m = 2.0", "radius_m = 2200.0"), "radius_m", "isolator[1].radius_m",
       "(0, 100]"},
      {"RateNegative", with(g, "rate_s_per_m = 25.0", "rate_s_per_m = -25.0"), "rate_s_per_m",
       "isolator[1].rate_s_per_m", "expected a value >= 0 s/m"},
      {"YieldDisplacementZero", with(g, "yield_displacement_m = 0.01", "yield_displacement_m = 0.0"),
       "yield_displacement_m", "isolator[0].yield_displacement_m", "(0, 1]"},
      {"YieldDisplacementInMillimetres", with(g, "yield_displacement_m = 0.01", "yield_displacement_m = 12.0"),
       "yield_displacement_m", "isolator[0].yield_displacement_m", "(0, 1]"},
      {"ExponentBelowOne", with(g, "yield_displacement_m = 0.01", "yield_displacement_m = 0.01\nexponent = 0.5"),
       "exponent", "isolator[0].exponent", "[1, 10]"},
      {"ExponentAboveTen", with(g, "yield_displacement_m = 0.0005", "yield_displacement_m = 0.0005\nexponent = 11"),
       "exponent", "isolator[1].exponent", "[1, 10]"},
      {"CapacityZero",
       with(g, "yield_displacement_m = 0.01", "yield_displacement_m = 0.01\ndisplacement_capacity_m = 0.0"),
       "displacement_capacity_m", "isolator[0].displacement_capacity_m", "(0, 5]"},
      {"WeightZero", with(g, "count = 4", "count = 4\nweight_n = 0.0"), "weight_n", "isolator[1].weight_n",
       "found 0"},
      {"StrengthNegative", with(g, "4.0e4", "-4.0e4"), "characteristic_strength_n",
       "isolator[0].characteristic_strength_n", "expected a value > 0 N"},
      // A strength in kN: 10 x 40 N = 400 N is 5.8e-5 of W = 6.865e6 N.
      {"StrengthInKilonewtons", with(g, "4.0e4", "40.0"), "characteristic_strength_n",
       "isolator[0].characteristic_strength_n", "is Q in N?"},
      // 10 x 4e7 N = 4e8 N is 58 W.
      {"StrengthAboveTheWeight", with(g, "4.0e4", "4.0e7"), "characteristic_strength_n",
       "isolator[0].characteristic_strength_n", "is Q in N?"},
      // A load in kN: 4 x 1560 N = 6240 N is 9.1e-4 of W.
      {"PendulumLoadInKilonewtons", with(g, "count = 4", "count = 4\nweight_n = 1560.0"), "weight_n",
       "isolator[1].weight_n", "is weight_n in N?"},
      {"TwoPendulumGroupsOneWithoutLoad", kBuilding + pend2 + kPendulum + kDamper, "[[isolator]]\nkind = \"friction_pendulum\"\ncount = 4",
       "isolator[1].weight_n", "more than one friction_pendulum group"},
      // Fixed base.
      {"FixedBaseWithIsolators", with(g, "name = \"test-3dof\"", "name = \"test-3dof\"\nbase = \"fixed\""),
       "[[isolator]]", "isolator[0]", "not allowed with building.base = \"fixed\""},
      {"FixedBaseWithoutFirstStory",
       with(with(kBuilding, "name = \"test-3dof\"", "name = \"test-3dof\"\nbase = \"fixed\""), "[1.0e6,", "[0.0,") +
           kDamper,
       "stiffness_n_m", "building.stiffness_n_m[0]", "first story"},
      // No restoring force.
      {"NoRestoringForceWithoutIsolators", with(kBuilding, "[1.0e6,", "[0.0,") + kDamper, "stiffness_n_m",
       "building.stiffness_n_m[0]", "no restoring force"},
      {"NoRestoringForceLeadRubberWithoutPostYieldStiffness",
       with(kBuilding, "[1.0e6,", "[0.0,") + with(kLead, "= 1.0e6", "= 0.0") + kDamper, "post_yield_stiffness_n_m",
       "isolator[0].post_yield_stiffness_n_m", "no restoring force"},
      // A post-yield stiffness in kN/m: 10 x 1000 N/m = 1e4 N/m, a period of
      // 2 pi sqrt(7e5 / 1e4) = 52.6 s.
      {"RestoringStiffnessInKilonewtonsPerMetre",
       with(kBuilding, "[1.0e6,", "[0.0,") + with(kLead, "= 1.0e6", "= 1000.0") + kDamper,
       "post_yield_stiffness_n_m", "isolator[0].post_yield_stiffness_n_m", "exceeds 30 s"},
      // Element 0 in kN/m without isolators: 2 pi sqrt(7e5 / 1000) = 166 s.
      {"ElementZeroStiffnessInKilonewtonsPerMetre", with(kBuilding, "[1.0e6,", "[1000.0,") + kDamper,
       "stiffness_n_m", "building.stiffness_n_m[0]", "exceeds 30 s"},
      // Dampers.
      {"DamperElementAboveN", with(g, "element = 0", "element = 3"), "element = 3", "damper[0].element", "0..2"},
      {"DamperElementNegative", with(g, "element = 0", "element = -1"), "element = -1", "damper[0].element", "0..2"},
      {"DamperCountZero", with(g, "element = 0\ncount = 1", "element = 0\ncount = 0"), "count = 0",
       "damper[0].count", "found 0"},
      {"DamperCountNotInteger", with(g, "element = 0\ncount = 1", "element = 0\ncount = 1.5"), "count = 1.5",
       "damper[0].count", "an integer"},
      {"TwoDamperTablesForOneElement", g + "\n[[damper]]\nelement = 0  # again\n", "element = 0  # again",
       "damper[1].element", "already has a [[damper]] table"},
  };
}

class BuildingFileRefuses : public ::testing::TestWithParam<BadFile> {};

TEST_P(BuildingFileRefuses, WithFileLineAndField) {
  const BadFile& c = GetParam();
  const std::string prefix = "bad.toml:" + std::to_string(line_of_text(c.text, c.needle)) + ": " +
                             (c.field.empty() ? std::string() : c.field + ": ");
  try {
    (void)parse_building_toml(c.text, "bad.toml");
    FAIL() << "accepted:\n" << c.text;
  } catch (const io::UsageError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(prefix, 0), 0u) << "expected the prefix \"" << prefix << "\", got: " << msg;
    EXPECT_NE(msg.find(c.what), std::string::npos) << "expected \"" << c.what << "\" in: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "a one-line message: " << msg;
  }
}

INSTANTIATE_TEST_SUITE_P(BadKinds, BuildingFileRefuses, ::testing::ValuesIn(bad_files()),
                         [](const ::testing::TestParamInfo<BadFile>& i) { return std::string(i.param.name); });

TEST(BuildingFileRefuses, TheGoodTextOfTheBadKindsIsAccepted) {
  // Each bad kind is one change away from this text: it must read.
  const BuildingParams b = parse_building_toml(kGood, "good.toml");
  EXPECT_EQ(b.isolators.size(), 2u);
  const BuildingParams two = parse_building_toml(
      kBuilding + with(kPendulum, "count = 4", "count = 4\nweight_n = 1.0e6") +
          with(kPendulum, "count = 4", "count = 2\nweight_n = 1.0e6") + kDamper,
      "good.toml");
  EXPECT_EQ(two.isolators.size(), 2u);
}

// ---- files that are not building files ------------------------------------------

class BuildingFileOnDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("building_file_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  std::string error_of(const fs::path& p) const {
    try {
      (void)read_building_file(p);
    } catch (const io::UsageError& e) {
      return e.what();
    }
    ADD_FAILURE() << "accepted " << p;
    return {};
  }
  fs::path dir_;
};

TEST_F(BuildingFileOnDisk, ErrorsNameThePathAsGiven) {
  const fs::path p = write("b.toml", with(kGood, "count = 10", "count = 0"));
  const std::string msg = error_of(p);
  const std::string prefix = p.string() + ":" + std::to_string(line_of_text(kGood, "count = 10")) + ": isolator[0].count: ";
  EXPECT_EQ(msg.rfind(prefix, 0), 0u) << msg;
}

TEST_F(BuildingFileOnDisk, RefusesAFolder) {
  const std::string msg = error_of(dir_);
  EXPECT_NE(msg.find(dir_.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("folder"), std::string::npos) << msg;
}

TEST_F(BuildingFileOnDisk, RefusesAFifoWithoutBlocking) {
  const fs::path fifo = dir_ / "pipe.toml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string msg = error_of(fifo);
  EXPECT_NE(msg.find(fifo.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("FIFO"), std::string::npos) << msg;
}

TEST_F(BuildingFileOnDisk, RefusesAFileLargerThanTheLimit) {
  // A valid file padded with a comment to one byte over 1 MiB.
  std::string text = kGood + "#";
  text.resize(kMaxBuildingFileBytes + 1, 'x');
  const fs::path p = write("huge.toml", text);
  const std::string msg = error_of(p);
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("larger than the limit of 1 MiB"), std::string::npos) << msg;
}

TEST_F(BuildingFileOnDisk, RefusesAMissingFile) {
  const fs::path p = dir_ / "none.toml";
  const std::string msg = error_of(p);
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
}

}  // namespace
}  // namespace mrd::structure
