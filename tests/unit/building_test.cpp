// Building matrices against Fig. 6.2 and Table 6.1 of the thesis, and the
// continuous state-space form built from them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "host_sim/structure/building.hpp"
#include "thesis_building_sizes.hpp"

namespace mrd::structure {
namespace {

using namespace thesis_sizes;

constexpr double kKiloNewton = 1000.0;

TEST(BuildingMatrices, MassMatchesFig62) {
  const Matrix6 m = mass_matrix(BuildingParams{});
  // Fig. 6.2: diag(244800, 212292 × 5) kg.
  EXPECT_DOUBLE_EQ(m(0, 0), 244800.0);
  for (int i = 1; i < kDofs; ++i) EXPECT_DOUBLE_EQ(m(i, i), 212292.0) << i;
  EXPECT_DOUBLE_EQ(m.sum(), m.trace());  // diagonal
  // 244800 + 5 × 212292 = 1,306,260 kg.
  EXPECT_DOUBLE_EQ(total_mass_kg(BuildingParams{}), 1306260.0);
}

TEST(BuildingMatrices, StiffnessMatchesFig62) {
  const Matrix6 k = stiffness_matrix(BuildingParams{}) / kKiloNewton;  // kN/m, as printed
  // Fig. 6.2, kN/m. Entries are integers except K(0,0); tolerance is half of
  // the last printed digit of K(0,0).
  const double fig[kDofs][kDofs] = {
      {408071.3, -404784, 0, 0, 0, 0},       {-404784, 753900, -349116, 0, 0, 0},
      {0, -349116, 692568, -343452, 0, 0},   {0, 0, -343452, 642900, -299448, 0},
      {0, 0, 0, -299448, 528156, -228708},   {0, 0, 0, 0, -228708, 228708},
  };
  for (int i = 0; i < kDofs; ++i) {
    for (int j = 0; j < kDofs; ++j) EXPECT_NEAR(k(i, j), fig[i][j], 0.05) << i << "," << j;
  }
}

TEST(BuildingMatrices, DampingMatchesFig62WithinRounding) {
  const Matrix6 c = damping_matrix(BuildingParams{}) / 1.0e6;  // units of 1e6 kg/s, as printed
  // Fig. 6.2, 1e6 kg/s, four decimals. A diagonal entry is the sum of two
  // story values each known to ±50 N·s/m plus the printed rounding of ±50,
  // hence 150 N·s/m = 1.5e-4 in these units (e.g. C(1,1): 1044.4 + 904.1 =
  // 1948.5 kN·s/m against the printed 1.9486e6).
  const double fig[kDofs][kDofs] = {
      {1.2542, -1.0444, 0, 0, 0, 0},        {-1.0444, 1.9486, -0.9041, 0, 0, 0},
      {0, -0.9041, 1.7927, -0.8885, 0, 0},  {0, 0, -0.8885, 1.668, -0.7794, 0},
      {0, 0, 0, -0.7794, 1.3718, -0.5924},  {0, 0, 0, 0, -0.5924, 0.5924},
  };
  for (int i = 0; i < kDofs; ++i) {
    for (int j = 0; j < kDofs; ++j) EXPECT_NEAR(c(i, j), fig[i][j], 1.5e-4) << i << "," << j;
  }
  // The brief's spot values: C(0,0) = 209.8 + 1044.4 kN·s/m, C(3,3) = 888.5 + 779.4.
  EXPECT_NEAR(c(0, 0), 1.2542, 1e-12);
  EXPECT_NEAR(c(3, 3), 1.6679, 1e-12);
}

TEST(BuildingMatrices, ShearBuildingStructure) {
  const BuildingParams p;
  const Matrix6 k = stiffness_matrix(p);
  const Matrix6 c = damping_matrix(p);
  EXPECT_TRUE(k.isApprox(k.transpose(), 0.0));
  EXPECT_TRUE(c.isApprox(c.transpose(), 0.0));
  // A uniform displacement stretches only the isolation layer: K·1 = k_0 e_0.
  const Vector6 f = k * Vector6::Ones();
  EXPECT_DOUBLE_EQ(f(0), 3287.3e3);
  for (int i = 1; i < kDofs; ++i) EXPECT_NEAR(f(i), 0.0, 1e-6) << i;
  // Tridiagonal.
  for (int i = 0; i < kDofs; ++i) {
    for (int j = 0; j < kDofs; ++j) {
      if (std::abs(i - j) > 1) {
        EXPECT_EQ(k(i, j), 0.0);
        EXPECT_EQ(c(i, j), 0.0);
      }
    }
  }
}

TEST(BuildingMatrices, TableValuesInSi) {
  const BuildingParams p;
  // Table 6.1 base row: 244.8 t, 209.8 kN·s/m, 3,287 kN/m (Fig. 6.2 gives 3,287.3).
  EXPECT_DOUBLE_EQ(p.mass_kg[0], 244.8e3);
  EXPECT_DOUBLE_EQ(p.story_damping_n_s_m[0], 209.8e3);
  EXPECT_NEAR(p.story_stiffness_n_m[0], 3287.0e3, 0.5e3);
  // Table 6.1 floor 5: 592.4 kN·s/m, 228,708 kN/m.
  EXPECT_DOUBLE_EQ(p.story_damping_n_s_m[5], 592.4e3);
  EXPECT_DOUBLE_EQ(p.story_stiffness_n_m[5], 228708.0e3);
}

TEST(BuildingStateSpace, BlocksOfAandB) {
  const BuildingParams p;
  const ContinuousModel cm = continuous_model(p);
  const Matrix6 m = mass_matrix(p);
  // Top rows: ẋ = ẋ.
  EXPECT_TRUE((cm.a.topLeftCorner<6, 6>().isZero(0.0)));
  EXPECT_TRUE((cm.a.topRightCorner<6, 6>().isIdentity(0.0)));
  EXPECT_TRUE(cm.b.topRows<6>().isZero(0.0));
  // Bottom rows times M give back −K and −C.
  EXPECT_TRUE(((m * cm.a.bottomLeftCorner<6, 6>()).isApprox(-stiffness_matrix(p), 1e-14)));
  EXPECT_TRUE(((m * cm.a.bottomRightCorner<6, 6>()).isApprox(-damping_matrix(p), 1e-14)));
  // −M·1·a_g / M: −1 in every acceleration row; damper force only on the base, −1/m_0.
  for (int i = 0; i < kDofs; ++i) EXPECT_DOUBLE_EQ(cm.b(6 + i, 0), -1.0) << i;
  EXPECT_DOUBLE_EQ(cm.b(6, 1), -1.0 / 244800.0);
  for (int i = 1; i < kDofs; ++i) EXPECT_EQ(cm.b(6 + i, 1), 0.0) << i;
}

TEST(BuildingStateSpace, RejectsInvalidParameters) {
  BuildingParams p;
  p.mass_kg[3] = 0.0;
  EXPECT_THROW(continuous_model(p), std::invalid_argument);
  p = BuildingParams{};
  p.story_stiffness_n_m[0] = -1.0;
  EXPECT_THROW(continuous_model(p), std::invalid_argument);
  p = BuildingParams{};
  p.story_damping_n_s_m[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(continuous_model(p), std::invalid_argument);
  p = BuildingParams{};
  p.story_damping_n_s_m[2] = 0.0;  // undamped is allowed
  EXPECT_NO_THROW(continuous_model(p));
}

}  // namespace
}  // namespace mrd::structure
