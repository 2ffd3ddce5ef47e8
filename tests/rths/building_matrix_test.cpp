// The building file's full matrices: the benchmark's file reads to the
// published stiffness matrix, K and C come out of the structure as given,
// the writer's text reads back to the same values, and bad matrices are
// refused with "<file>:<line>: <field>: ..." (lines counted in the test's
// own text).

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "host_sim/io/usage_error.hpp"
#include "host_sim/rths/benchmark.hpp"
#include "host_sim/structure/building.hpp"
#include "host_sim/structure/building_file.hpp"

namespace mrd::structure {
namespace {

const std::string kMatrixHeader =
    "[building]\n"                 // line 1
    "name = \"m\"\n"               // line 2
    "base = \"fixed\"\n"           // line 3
    "mass_kg = [1000.0, 1000.0]\n";  // line 4

std::string refusal_of(const std::string& text) {
  try {
    (void)parse_building_toml(text, "b.toml");
  } catch (const io::UsageError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(BuildingMatrixFile, BenchmarkFileReadsToThePublishedMatrix) {
  const BuildingParams b = read_building_file(std::filesystem::path(MRD_BUILDINGS_DIR) / "silva-2020-3dof.toml");
  ASSERT_EQ(b.stiffness_matrix_n_m.size(), 9u);
  for (std::size_t i = 0; i < 9; ++i) EXPECT_EQ(b.stiffness_matrix_n_m[i], rths::kBenchmarkStiffness_n_m[i]) << i;
  const Matrix k = stiffness_matrix(b);
  EXPECT_EQ(k(0, 2), 5937035.46);
  EXPECT_EQ(k(2, 1), -14419970.78);
  // The chain seen from it: k_1 = −K(1,0), k_2 = −K(2,1), k_0 = K(0,0) − k_1.
  EXPECT_EQ(b.story_stiffness_n_m[1], 23133938.88);
  EXPECT_EQ(b.story_stiffness_n_m[2], 14419970.78);
  EXPECT_NEAR(b.story_stiffness_n_m[0], 26054883.88 - 23133938.88, 1e-6);
  ASSERT_TRUE(b.rayleigh.has_value());
  EXPECT_EQ(b.rayleigh->ratio, 0.05);
}

TEST(BuildingMatrixFile, FullDampingMatrixIsUsedAsGiven) {
  const BuildingParams b = parse_building_toml(kMatrixHeader +
                                                   "stiffness_matrix_n_m = [[3.0e6, -1.0e6], [-1.0e6, 1.0e6]]\n"
                                                   "damping_matrix_n_s_m = [[3000.0, -1000.0], [-1000.0, 1000.0]]\n",
                                               "b.toml");
  validate(b);
  const Matrix c = damping_matrix(b);
  EXPECT_EQ(c(0, 1), -1000.0);
  EXPECT_EQ(c(1, 1), 1000.0);
  EXPECT_EQ(stiffness_matrix(b)(0, 0), 3.0e6);
}

TEST(BuildingMatrixFile, WriterReadsBack) {
  const BuildingParams b = rths::benchmark_structure(3);
  const BuildingParams back = parse_building_toml(building_toml(b), "written.toml");
  EXPECT_EQ(back.stiffness_matrix_n_m, b.stiffness_matrix_n_m);
  EXPECT_EQ(back.mass_kg, b.mass_kg);
  ASSERT_TRUE(back.rayleigh.has_value());
  EXPECT_EQ(back.rayleigh->ratio, 0.03);
}

TEST(BuildingMatrixFile, RefusesAsymmetryWithTheEntry) {
  const std::string e = refusal_of(kMatrixHeader +
                                   "stiffness_matrix_n_m = [[3.0e6, -1.0e6], [-1.5e6, 1.0e6]]\n"  // line 5
                                   "[building.rayleigh]\nratio = 0.05\nmodes = [1, 2]\n");
  EXPECT_NE(e.find("b.toml:5: building.stiffness_matrix_n_m[1][0]: expected a symmetric matrix"), std::string::npos)
      << e;
}

TEST(BuildingMatrixFile, RefusesAMatrixThatIsNotPositiveDefinite) {
  // [[1, 2], [2, 1]] has the eigenvalues 3 and −1.
  const std::string e = refusal_of(kMatrixHeader +
                                   "stiffness_matrix_n_m = [[1.0e6, 2.0e6], [2.0e6, 1.0e6]]\n"  // line 5
                                   "[building.rayleigh]\nratio = 0.05\nmodes = [1, 2]\n");
  EXPECT_NE(e.find("b.toml:5: building.stiffness_matrix_n_m: expected a positive definite matrix"), std::string::npos)
      << e;
}

TEST(BuildingMatrixFile, RefusesBothStiffnessFormsAndWrongRows) {
  std::string e = refusal_of(kMatrixHeader +
                             "stiffness_matrix_n_m = [[3.0e6, -1.0e6], [-1.0e6, 1.0e6]]\n"  // line 5
                             "stiffness_n_m = [2.0e6, 1.0e6]\n"                             // line 6
                             "[building.rayleigh]\nratio = 0.05\nmodes = [1, 2]\n");
  EXPECT_NE(e.find("b.toml:6: building.stiffness_n_m: not allowed with building.stiffness_matrix_n_m"),
            std::string::npos)
      << e;
  e = refusal_of(kMatrixHeader + "stiffness_matrix_n_m = [[3.0e6, -1.0e6]]\n"  // line 5
                 "[building.rayleigh]\nratio = 0.05\nmodes = [1, 2]\n");
  EXPECT_NE(e.find("b.toml:5: building.stiffness_matrix_n_m: expected 2 rows"), std::string::npos) << e;
  e = refusal_of(kMatrixHeader +
                 "stiffness_matrix_n_m = [[3.0e6, -1.0e6], [-1.0e6, 1.0e6]]\n"
                 "damping_matrix_n_s_m = [[1.0, 2.0], [2.0, 1.0]]\n");  // line 6
  EXPECT_NE(e.find("b.toml:6: building.damping_matrix_n_s_m: expected a positive semi-definite matrix"),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace mrd::structure
