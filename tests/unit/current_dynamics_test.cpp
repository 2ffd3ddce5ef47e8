// Coil-current dynamics, Eq. 4.5 normalized to unity DC gain.
#include "mrd/physics/current_dynamics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mrd::physics {
namespace {

// Continuous step response of H(s)/2 = ½/(0.7s+1) + ½/(0.03s+1):
//   y(t) = 1 − ½ e^(−t/0.7) − ½ e^(−t/0.03)
double step_response(double t_s) { return 1.0 - 0.5 * std::exp(-t_s / 0.7) - 0.5 * std::exp(-t_s / 0.03); }

TEST(CurrentDynamics, UnityDcGain) {
  CurrentDynamics cd({}, 1e-3);
  EXPECT_DOUBLE_EQ(cd.dc_gain(), 1.0);
  double y = 0.0;
  for (int i = 0; i < 20000; ++i) y = cd.step(2.5);  // 20 s ≫ 0.7 s
  EXPECT_NEAR(y, 2.5, 1e-9);
}

// Hand values: y(0.03 s) = 1 − ½e^(−0.042857) − ½e^(−1) = 0.337036;
//              y(0.7 s)  = 1 − ½e^(−1) − ½e^(−23.33) = 0.816060.
TEST(CurrentDynamics, TimeConstantsOfBothBranches) {
  CurrentDynamics cd({}, 1e-3);
  double y = 0.0;
  for (int i = 0; i < 30; ++i) y = cd.step(1.0);
  EXPECT_NEAR(y, 0.337036, 1e-6);
  for (int i = 30; i < 700; ++i) y = cd.step(1.0);
  EXPECT_NEAR(y, 0.816060, 1e-6);
}

// Exact for piecewise-constant commands: a staircase command sampled at a
// coarse 10 ms period agrees with the superposition of continuous step
// responses at every sample, to rounding.
TEST(CurrentDynamics, ExactForPiecewiseConstantCommands) {
  const double T = 0.01;
  CurrentDynamics cd({}, T);
  const double commands[] = {1.0, 1.0, 3.0, -2.0, -2.0, 0.5, 0.5, 0.5, 0.0, 10.0};
  double prev = 0.0;
  double step_times[10];
  double step_sizes[10];
  for (int k = 0; k < 10; ++k) {
    step_times[k] = k * T;
    step_sizes[k] = commands[k] - prev;
    prev = commands[k];
  }
  for (int n = 0; n < 10; ++n) {
    const double y = cd.step(commands[n]);
    const double t = (n + 1) * T;
    double expected = 0.0;
    for (int k = 0; k <= n; ++k) expected += step_sizes[k] * step_response(t - step_times[k]);
    EXPECT_NEAR(y, expected, 1e-12) << "sample " << n;
  }
}

TEST(CurrentDynamics, ResetHoldsASteadyCurrent) {
  CurrentDynamics cd({}, 1e-3);
  cd.reset(1.5);
  EXPECT_DOUBLE_EQ(cd.current_a(), 1.5);
  EXPECT_NEAR(cd.step(1.5), 1.5, 1e-15);
}

}  // namespace
}  // namespace mrd::physics
