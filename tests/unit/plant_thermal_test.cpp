// Coil heating (i²R into a first-order thermal model) and the coil figures
// every plant reports.
#include <gtest/gtest.h>

#include <cmath>

#include "host_sim/plant/coil_figures.hpp"
#include "host_sim/plant/coil_thermal.hpp"
#include "host_sim/plant/plant.hpp"

namespace mrd::plant {
namespace {

// Steady state: ΔT = P R_th = (2.5 A)² · 4.8 Ω · 2 K/W = 30 W · 2 K/W = 60 K.
// After one time constant: 60 K (1 − e^−1) = 37.927 K.
TEST(CoilThermal, SteadyRiseIsPowerTimesThermalResistance) {
  CoilThermal t{physics::CoilHeatParams{}, 1.0};
  for (int k = 0; k < 1200; ++k) t.step(2.5 * 2.5);
  EXPECT_NEAR(t.rise_k(), 60.0 * (1.0 - std::exp(-1.0)), 1e-9);
  for (int k = 0; k < 1200 * 39; ++k) t.step(2.5 * 2.5);
  EXPECT_NEAR(t.rise_k(), 60.0, 1e-9 * 60.0 + 60.0 * std::exp(-40.0));
  // Cooling with no current: back to e^−1 of the rise after τ.
  const double hot_k = t.rise_k();
  for (int k = 0; k < 1200; ++k) t.step(0.0);
  EXPECT_NEAR(t.rise_k(), hot_k * std::exp(-1.0), 1e-9);
}

// The plant heats the damper's own coil (MrDamperParams::coil_heat), both
// plants. 1 A held for 600 s at rest in a coil of 12 Ω with R_th = 3 K/W and
// τ = 60 s: the steady rise is (1 A)² · 12 Ω · 3 K/W = 36 K, reached within
// 36 K · e^−10 = 1.6 mK after 10 τ (the coil's lag of Eq. 4.5, 0.7 s on the
// thesis plant, withholds about 0.7 s of 12 W in the first seconds, decayed by
// e^−9.9 since: 1 mK more at most). The thesis coil at 1 A: 4.8 Ω · 2 K/W = 9.6 K.
TEST(CoilThermal, ThePlantHeatsTheDampersOwnCoil) {
  for (const PlantKind kind : {PlantKind::kThesis, PlantKind::kHardware}) {
    SCOPED_TRACE(plant_kind_name(kind));
    const auto rise_after_600_s = [kind](const physics::CoilHeatParams& heat) {
      PlantSpec spec;
      spec.kind = kind;
      spec.damper.coil_heat = heat;  // the hardware plant drives and heats this one resistance
      Plant p;
      p.init(spec);
      for (int n = 0; n < 600000; ++n) {
        (void)p.sense(0.0);
        p.advance(CoilDrive{1.0, true});
      }
      return p.summary().coil.peak_coil_temperature_rise_k;
    };
    EXPECT_NEAR(rise_after_600_s(physics::CoilHeatParams{12.0, 3.0, 60.0}), 36.0, 3e-3);
    EXPECT_NEAR(rise_after_600_s(physics::CoilHeatParams{4.8, 2.0, 60.0}), 9.6, 1e-3);
  }
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
