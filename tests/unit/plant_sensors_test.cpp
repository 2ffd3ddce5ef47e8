// The hardware plant's sensors: LVDT, load cell and coil-current sensor,
// quantized, saturated, with seeded white noise.
#include <gtest/gtest.h>

#include <cmath>

#include "host_sim/plant/hardware_sensors.hpp"

namespace mrd::plant {
namespace {

HardwareSensorSpec noiseless() {
  HardwareSensorSpec s;
  s.lvdt_noise_rms_m = s.load_cell_noise_rms_n = s.current_noise_rms_a = 0.0;
  return s;
}

// step = span / 2^bits: 0.5842 m / 65536 = 8.914 µm; 500 kN / 65536 = 7.629 N;
// 30 A / 4096 = 7.324 mA.
TEST(HardwareSensors, QuantizationStepIsSpanOverTwoToTheBits) {
  const HardwareSensors h{HardwareSensorSpec{}};
  EXPECT_DOUBLE_EQ(h.lvdt().step(), 0.5842 / 65536.0);
  EXPECT_NEAR(h.lvdt().step(), 8.914e-6, 1e-9);
  EXPECT_DOUBLE_EQ(h.load_cell().step(), 500.0e3 / 65536.0);
  EXPECT_DOUBLE_EQ(h.current().step(), 30.0 / 4096.0);
  for (const SensorChannel* c : {&h.lvdt(), &h.load_cell(), &h.current()}) {
    const double q = c->step();
    EXPECT_DOUBLE_EQ(c->convert(37.0 * q + 0.4 * q), 37.0 * q);
    EXPECT_DOUBLE_EQ(c->convert(-5.0 * q - 0.6 * q), -6.0 * q);
  }
}

TEST(HardwareSensors, SaturateAtRange) {
  HardwareSensors h{noiseless()};
  PlantState s;
  s.base_disp_m = 0.5;
  s.damper_force_n = -400.0e3;
  s.coil_current_a = 20.0;
  const PlantSensors m = h.measure(s);
  EXPECT_FLOAT_EQ(m.damper_disp_m, 0.2921f);
  EXPECT_FLOAT_EQ(m.damper_force_n, -250.0e3f);
  EXPECT_FLOAT_EQ(m.coil_current_a, 15.0f);
}

TEST(HardwareSensors, OffsetsAndParkedStrokeAdd) {
  HardwareSensorSpec spec = noiseless();
  spec.load_cell_offset_n = 1000.0;
  HardwareSensors h{spec};
  PlantState s;
  const PlantSensors m = h.measure(s, 0.003);
  // 3 mm to the nearest 8.914 µm step: 337 steps = 3.00405 mm (0.003/8.914e-6 = 336.55).
  EXPECT_NEAR(m.damper_disp_m, 337.0 * 0.5842 / 65536.0, 1e-9);
  // 1000 N: 131.07 steps of 7.629 N → 131 steps = 999.45 N.
  EXPECT_NEAR(m.damper_force_n, 131.0 * 500.0e3 / 65536.0, 1e-3);
}

// Noise RMS: for N independent normal samples the sample RMS has a relative
// standard deviation of 1/sqrt(2N) = 0.5 % at N = 20000; the tolerance is
// 5 of those, 2.5 %. Quantization adds q²/12 to the variance (Sheppard; valid
// for σ ≳ q/2): load cell sqrt(250² + 7.629²/12) = 250.01 N, current sensor
// sqrt(5² + 7.324²/12) = 5.443 mA. The LVDT's 2 µm is below half its 8.9 µm
// step, so it is measured through a 32-bit converter (q²/12 negligible).
TEST(HardwareSensors, NoiseRmsWithinStatisticalTolerance) {
  HardwareSensorSpec spec;
  spec.lvdt_bits = 32;
  spec.seed = 7;
  HardwareSensors h{spec};
  PlantState s;
  s.base_disp_m = 0.01;
  s.damper_force_n = 50.0e3;
  s.coil_current_a = 2.5;
  const int n = 20000;
  double sx = 0, sf = 0, si = 0, mx = 0;
  for (int k = 0; k < n; ++k) {
    const PlantSensors m = h.measure(s);
    const double ex = m.damper_disp_m - s.base_disp_m;  // float rounding of 0.01 m: 1e-9 m, negligible
    const double ef = m.damper_force_n - s.damper_force_n;
    const double ei = m.coil_current_a - s.coil_current_a;
    sx += ex * ex;
    sf += ef * ef;
    si += ei * ei;
    mx += ex;
  }
  const double tol = 5.0 / std::sqrt(2.0 * n);
  EXPECT_NEAR(std::sqrt(sx / n) / 2.0e-6, 1.0, tol);
  EXPECT_NEAR(std::sqrt(sf / n) / std::sqrt(250.0 * 250.0 + std::pow(500.0e3 / 65536.0, 2) / 12.0), 1.0, tol);
  EXPECT_NEAR(std::sqrt(si / n) / std::sqrt(25e-6 + std::pow(30.0 / 4096.0, 2) / 12.0), 1.0, tol);
  // Zero mean: within 5 standard errors σ/sqrt(N).
  EXPECT_NEAR(mx / n, 0.0, 5.0 * 2.0e-6 / std::sqrt(n));
}

TEST(HardwareSensors, SameSeedSameReadings) {
  HardwareSensorSpec spec;
  spec.seed = 42;
  HardwareSensors a{spec}, b{spec};
  spec.seed = 43;
  HardwareSensors c{spec};
  PlantState s;
  s.damper_force_n = 1.0e3;
  int differ = 0;
  for (int k = 0; k < 100; ++k) {
    const PlantSensors ma = a.measure(s), mb = b.measure(s), mc = c.measure(s);
    EXPECT_EQ(ma.damper_force_n, mb.damper_force_n);
    EXPECT_EQ(ma.damper_disp_m, mb.damper_disp_m);
    EXPECT_EQ(ma.coil_current_a, mb.coil_current_a);
    differ += ma.damper_force_n != mc.damper_force_n;
  }
  EXPECT_GT(differ, 90);
}

}  // namespace
}  // namespace mrd::plant
