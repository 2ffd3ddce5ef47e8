// Coil heating (i²R into a first-order thermal model) and the coil figures
// every plant reports.
#include <gtest/gtest.h>

#include <cmath>

#include "host_sim/plant/coil_figures.hpp"
#include "host_sim/plant/coil_thermal.hpp"

namespace mrd::plant {
namespace {

// Steady state: ΔT = P R_th = (2.5 A)² · 4.8 Ω · 2 K/W = 30 W · 2 K/W = 60 K.
// After one time constant: 60 K (1 − e^−1) = 37.927 K.
TEST(CoilThermal, SteadyRiseIsPowerTimesThermalResistance) {
  CoilThermal t{CoilThermalParams{}, 1.0};
  for (int k = 0; k < 1200; ++k) t.step(2.5 * 2.5);
  EXPECT_NEAR(t.rise_k(), 60.0 * (1.0 - std::exp(-1.0)), 1e-9);
  for (int k = 0; k < 1200 * 39; ++k) t.step(2.5 * 2.5);
  EXPECT_NEAR(t.rise_k(), 60.0, 1e-9 * 60.0 + 60.0 * std::exp(-40.0));
  // Cooling with no current: back to e^−1 of the rise after τ.
  const double hot_k = t.rise_k();
  for (int k = 0; k < 1200; ++k) t.step(0.0);
  EXPECT_NEAR(t.rise_k(), hot_k * std::exp(-1.0), 1e-9);
}

// Ticks of 0.5 s: currents 0, 3, −3, 1 A; commands 0, 1, 1, 2 A.
// peak 3 A; RMS sqrt((0 + 9 + 9 + 1)/4) = sqrt(4.75) A; above 2.5 A: 2 ticks = 1 s;
// command changes: 0→1 and 1→2 against 0 before the first tick: 2 in 2 s = 1 per s.
TEST(CoilFigures, HandCountedRun) {
  CoilFigureCounter c;
  const double i[] = {0.0, 3.0, -3.0, 1.0};
  const double u[] = {0.0, 1.0, 1.0, 2.0};
  const double rise[] = {0.1, 0.4, 0.3, 0.2};
  for (int k = 0; k < 4; ++k) c.add(i[k], u[k], rise[k]);
  const CoilFigures f = c.figures(0.5);
  EXPECT_DOUBLE_EQ(f.peak_coil_current_a, 3.0);
  EXPECT_DOUBLE_EQ(f.rms_coil_current_a, std::sqrt(4.75));
  EXPECT_DOUBLE_EQ(f.time_above_rated_s, 1.0);
  EXPECT_DOUBLE_EQ(f.command_changes_per_s, 1.0);
  EXPECT_DOUBLE_EQ(f.peak_coil_temperature_rise_k, 0.4);
  EXPECT_DOUBLE_EQ(kRatedCoilCurrent_a, 2.5);
}

TEST(CoilFigures, EmptyRunIsZero) {
  const CoilFigures f = CoilFigureCounter{}.figures(1e-3);
  EXPECT_EQ(f.rms_coil_current_a, 0.0);
  EXPECT_EQ(f.command_changes_per_s, 0.0);
}

}  // namespace
}  // namespace mrd::plant
