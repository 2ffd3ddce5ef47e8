// The thesis-shape lanes' peak bounds (host_sim/batch/peak_bounds.hpp): the
// lanes skip the floors' accelerations and the story drifts on ticks where a
// bound shows that no peak can rise, so each bound must hold for every state
// and input. Checked here against the rows themselves, evaluated by the test
// from the model's matrices, on the states that make each inequality tight
// (a mode's amplitude along a row, a step's change along (B_j − I)ᵀ c) and on
// random ones; the batch's peaks equal to the scalar loop's are
// plant_batch_test.cpp's.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>

#include "host_sim/batch/lane_block.hpp"
#include "host_sim/batch/lane_stepper.hpp"
#include "host_sim/batch/peak_bounds.hpp"
#include "host_sim/plant/plant.hpp"

namespace {

using mrd::batch::kBlockDofs;
using mrd::batch::kBlockModes;
using mrd::batch::kBlockStates;
using mrd::batch::PeakBoundModel;
using mrd::batch::SharedModel;

double largest_singular_value(double a, double b, double c, double d) {
  Eigen::Matrix2d m;
  m << a, b, c, d;
  return Eigen::JacobiSVD<Eigen::Matrix2d>(m).singularValues()(0);
}

TEST(PeakBounds, BlockNormIsTheLargestSingularValue) {
  // Hand values: diag(3, −2) → 3; 0.9 times a rotation → 0.9; the shear
  // [1 1; 0 1] → the golden ratio (1 + √5) / 2.
  EXPECT_DOUBLE_EQ(mrd::batch::block_norm(3.0, 0.0, 0.0, -2.0), 3.0);
  const double c = std::cos(0.3), s = std::sin(0.3);
  EXPECT_NEAR(mrd::batch::block_norm(0.9 * c, 0.9 * s, -0.9 * s, 0.9 * c), 0.9, 1e-15);
  EXPECT_NEAR(mrd::batch::block_norm(1.0, 1.0, 0.0, 1.0), (1.0 + std::sqrt(5.0)) / 2.0, 1e-15);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int k = 0; k < 1000; ++k) {
    const double a = u(rng), b = u(rng), cc = u(rng), d = u(rng);
    EXPECT_NEAR(mrd::batch::block_norm(a, b, cc, d), largest_singular_value(a, b, cc, d), 1e-14);
  }
}

/// The model's rows of one group: floors' accelerations (rows 1–5 of A·T),
/// or story drifts (row i − row i−1 of T).
struct Rows {
  Eigen::Matrix<double, kBlockDofs - 1, kBlockStates> c;
};

Rows floor_rows(const SharedModel& m) {
  Rows r;
  for (int i = 1; i < kBlockDofs; ++i) {
    for (int k = 0; k < kBlockStates; ++k) r.c(i - 1, k) = m.accel_rows[i][k];
  }
  return r;
}

Rows drift_rows(const SharedModel& m) {
  Rows r;
  for (int i = 1; i < kBlockDofs; ++i) {
    for (int k = 0; k < kBlockStates; ++k) r.c(i - 1, k) = m.disp_rows[i][k] - m.disp_rows[i - 1][k];
  }
  return r;
}

Eigen::Matrix2d block(const SharedModel& m, int j) {
  Eigen::Matrix2d b;
  b << m.blocks[2 * j][0], m.blocks[2 * j][1], m.blocks[2 * j + 1][0], m.blocks[2 * j + 1][1];
  return b;
}

Eigen::Matrix<double, kBlockStates, 1> step(const SharedModel& m, const Eigen::Matrix<double, kBlockStates, 1>& q,
                                            double ag, double force) {
  Eigen::Matrix<double, kBlockStates, 1> next;
  for (int j = 0; j < kBlockModes; ++j) next.segment<2>(2 * j) = block(m, j) * q.segment<2>(2 * j);
  for (int k = 0; k < kBlockStates; ++k) next(k) += m.gamma[k][0] * ag + m.gamma[k][1] * force;
  return next;
}

/// A state of mode j alone, of unit amplitude along `dir` (≠ 0).
Eigen::Matrix<double, kBlockStates, 1> mode_along(int j, const Eigen::Vector2d& dir) {
  Eigen::Matrix<double, kBlockStates, 1> q = Eigen::Matrix<double, kBlockStates, 1>::Zero();
  q.segment<2>(2 * j) = dir / dir.norm();
  return q;
}

double amplitude_bound(const PeakBoundModel& g, const Eigen::Matrix<double, kBlockStates, 1>& q) {
  double w = 0.0;
  for (int j = 0; j < kBlockModes; ++j) w += g.weight[j] * q.segment<2>(2 * j).norm();
  return w;
}

double rate_bound(const PeakBoundModel& g, const Eigen::Matrix<double, kBlockStates, 1>& q, double ag,
                  double force) {
  double w = g.per_ag * std::fabs(ag) + g.per_force * std::fabs(force);
  for (int j = 0; j < kBlockModes; ++j) w += g.rate_weight[j] * q.segment<2>(2 * j).norm();
  return w;
}

class ThesisBounds : public ::testing::Test {
 protected:
  const mrd::plant::PlantSpec spec_{};
  const SharedModel m_ = mrd::batch::thesis_shared_model(spec_);
};

TEST_F(ThesisBounds, EveryModeContracts) {
  ASSERT_TRUE(m_.peak_bounds);
  for (int j = 0; j < kBlockModes; ++j) {
    const Eigen::Matrix2d b = block(m_, j);
    EXPECT_LT(largest_singular_value(b(0, 0), b(0, 1), b(1, 0), b(1, 1)), 1.0) << "mode " << j;
  }
}

TEST_F(ThesisBounds, AmplitudeBoundIsEachModesLargestRowNorm) {
  for (const auto& [name, rows, g] :
       {std::tuple{"floors", floor_rows(m_), m_.floor_bound}, std::tuple{"drifts", drift_rows(m_), m_.drift_bound}}) {
    SCOPED_TRACE(name);
    for (int j = 0; j < kBlockModes; ++j) {
      double largest = 0.0;
      for (int i = 0; i < kBlockDofs - 1; ++i) {
        // A unit amplitude of mode j along row i's own part: |c·q| = ‖c^(j)‖.
        const Eigen::Vector2d cj = rows.c.row(i).segment<2>(2 * j).transpose();
        if (cj.norm() == 0.0) continue;
        const Eigen::Matrix<double, kBlockStates, 1> q = mode_along(j, cj);
        const double value = std::fabs(rows.c.row(i).dot(q));
        EXPECT_LE(value, amplitude_bound(g, q)) << "mode " << j << ", row " << i;
        largest = std::max(largest, value);
      }
      // The bound is the largest of them, widened by 1e-12 and for the
      // drifts by the two sums' roundings (16 u of each row's norm).
      EXPECT_NEAR(g.weight[j], largest, 1e-9 * largest + 1e-14) << "mode " << j;
    }
  }
}

TEST_F(ThesisBounds, RateBoundHoldsWhereAStepChangesARowMost) {
  for (const auto& [name, rows, g] :
       {std::tuple{"floors", floor_rows(m_), m_.floor_bound}, std::tuple{"drifts", drift_rows(m_), m_.drift_bound}}) {
    SCOPED_TRACE(name);
    for (int j = 0; j < kBlockModes; ++j) {
      double largest = 0.0;
      for (int i = 0; i < kBlockDofs - 1; ++i) {
        // The unit amplitude whose free step changes row i most: along
        // (B_j − I)ᵀ c^(j), where the change is ‖(B_j − I)ᵀ c^(j)‖.
        const Eigen::Vector2d cj = rows.c.row(i).segment<2>(2 * j).transpose();
        const Eigen::Vector2d dir = (block(m_, j) - Eigen::Matrix2d::Identity()).transpose() * cj;
        if (dir.norm() == 0.0) continue;
        const Eigen::Matrix<double, kBlockStates, 1> q = mode_along(j, dir);
        const double change = std::fabs(rows.c.row(i).dot(step(m_, q, 0.0, 0.0) - q));
        EXPECT_LE(change, rate_bound(g, q, 0.0, 0.0)) << "mode " << j << ", row " << i;
        largest = std::max(largest, change);
      }
      // A damped mode's block is e^{σT} times a rotation, so B_j − I is a
      // scaled rotation too and the product of the norms is attained.
      EXPECT_GE(largest, 0.999 * g.rate_weight[j]) << "mode " << j;
    }
    // The inputs alone (from rest): the change of each row within the inputs' terms.
    for (const auto& [ag, force] : {std::pair{1.0, 0.0}, std::pair{0.0, 1.0}, std::pair{-3.0, 2.0e5}}) {
      const Eigen::Matrix<double, kBlockStates, 1> q = Eigen::Matrix<double, kBlockStates, 1>::Zero();
      const Eigen::Matrix<double, kBlockStates, 1> next = step(m_, q, ag, force);
      for (int i = 0; i < kBlockDofs - 1; ++i) {
        EXPECT_LE(std::fabs(rows.c.row(i).dot(next)), rate_bound(g, q, ag, force));
      }
      EXPECT_LE(amplitude_bound(g, next),
                amplitude_bound(g, q) + g.per_ag * std::fabs(ag) + g.per_force * std::fabs(force));
    }
  }
}

TEST_F(ThesisBounds, BothBoundsHoldOnRandomStatesAndInputs) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < 20000; ++k) {
    Eigen::Matrix<double, kBlockStates, 1> q;
    const double scale = std::pow(10.0, -4.0 + 3.0 * (k % 4));  // 0.1 mm to 0.1 km of modal amplitude
    for (int s = 0; s < kBlockStates; ++s) q(s) = scale * n(rng);
    const double ag = 5.0 * n(rng);
    const double force = 2.0e5 * n(rng);
    const Eigen::Matrix<double, kBlockStates, 1> next = step(m_, q, ag, force);
    for (const auto& [rows, g] : {std::pair{floor_rows(m_), m_.floor_bound}, std::pair{drift_rows(m_), m_.drift_bound}}) {
      for (int i = 0; i < kBlockDofs - 1; ++i) {
        EXPECT_LE(std::fabs(rows.c.row(i).dot(q)), amplitude_bound(g, q));
        EXPECT_LE(std::fabs(rows.c.row(i).dot(next - q)), rate_bound(g, q, ag, force));
      }
      EXPECT_LE(amplitude_bound(g, next),
                amplitude_bound(g, q) + g.per_ag * std::fabs(ag) + g.per_force * std::fabs(force));
    }
  }
}

TEST(PeakBounds, ABlockThatDoesNotContractTurnsTheBoundsOff) {
  const mrd::plant::PlantSpec spec;
  SharedModel m = mrd::batch::thesis_shared_model(spec);
  ASSERT_TRUE(m.peak_bounds);
  // Mode 0's block made a growth by 0.1 % a step.
  m.blocks[0][0] = 1.001;
  m.blocks[0][1] = 0.0;
  m.blocks[1][0] = 0.0;
  m.blocks[1][1] = 1.001;
  mrd::batch::set_peak_bounds(m);
  EXPECT_FALSE(m.peak_bounds);
}

}  // namespace
