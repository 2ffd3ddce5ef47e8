// The plant (host_sim/plant): tick order, sensor and command stages, and the
// idle time that sets the settling quotient.
#include "host_sim/plant/plant.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mrd/physics/settling.hpp"
#include "mrd/units.hpp"

namespace mrd::plant {
namespace {

/// 1.5 m/s² at 0.8 Hz, sampled at the default 1 ms step.
double ground(std::size_t k) { return 1.5 * std::sin(2.0 * units::kPi * 0.8 * 1e-3 * static_cast<double>(k)); }

TEST(Plant, AtRestWithoutGroundMotionOrCurrent) {
  Plant p;
  p.init({});
  for (int k = 0; k < 500; ++k) {
    const PlantSensors s = p.sense(0.0);
    EXPECT_EQ(s.damper_disp_m, 0.0f);
    EXPECT_EQ(s.damper_force_n, 0.0f);
    p.advance({0.0, true});
  }
  const PlantSummary s = p.summary();
  EXPECT_EQ(s.ticks, 500u);
  EXPECT_DOUBLE_EQ(s.duration_s, 0.5);
  EXPECT_EQ(s.peak_base_displacement_m, 0.0);
  EXPECT_EQ(s.peak_superstructure_accel_m_s2, 0.0);
}

// Sensor stage: ideal sensors hand over the state rounded to float.
TEST(Plant, SensorsAreTheStateRoundedToFloat) {
  Plant p;
  p.init({});
  for (std::size_t k = 0; k < 3000; ++k) {
    const PlantSensors s = p.sense(ground(k));
    const PlantState& x = p.state();
    ASSERT_EQ(s.damper_disp_m, static_cast<float>(x.base_disp_m));
    ASSERT_EQ(s.damper_force_n, static_cast<float>(x.damper_force_n));
    ASSERT_EQ(s.ground_accel_m_s2, static_cast<float>(ground(k)));
    ASSERT_EQ(s.base_accel_m_s2, static_cast<float>(x.base_accel_m_s2));
    ASSERT_EQ(s.coil_current_a, static_cast<float>(x.coil_current_a));
    p.advance({2.5, true});
  }
  EXPECT_GT(p.state().coil_current_a, 2.4) << "the coil follows the drive (Eq. 4.5)";
}

// Command stage: a drive whose output is off drives the coil to 0 A, exactly
// as a 0 A command does.
TEST(Plant, DriveOutputOffIsZeroCurrent) {
  Plant off, zero;
  off.init({});
  zero.init({});
  for (std::size_t k = 0; k < 4000; ++k) {
    off.sense(ground(k));
    zero.sense(ground(k));
    off.advance({2.5, false});
    zero.advance({0.0, true});
  }
  const PlantSummary a = off.summary(), b = zero.summary();
  EXPECT_EQ(a.peak_base_displacement_m, b.peak_base_displacement_m);
  EXPECT_EQ(a.peak_damper_force_n, b.peak_damper_force_n);
  EXPECT_EQ(a.peak_current_a, 0.0);
}

// The idle time in seconds sets SQ through Eq. 5.4–5.5.
TEST(Plant, IdleTimeSetsTheSettlingQuotient) {
  const double tmax_s = physics::max_settling_time_s({});
  for (const double idle_s : {0.0, 0.5 * tmax_s, tmax_s, 3.0 * tmax_s}) {
    PlantSpec spec;
    spec.idle_time_s = idle_s;
    Plant p;
    p.init(spec);
    EXPECT_EQ(p.summary().sq, physics::settling_quotient_after_idle(idle_s, spec.settling));
  }
  PlantSpec half;
  half.idle_time_s = 0.5 * tmax_s;
  Plant p;
  p.init(half);
  EXPECT_DOUBLE_EQ(p.summary().sq, 0.5);
}

// Peaks are of the states the ticks sensed, plus the state the last advance
// reached; the acceleration peaks are of the states each advance reached.
TEST(Plant, PeaksCoverEveryStateReached) {
  Plant p;
  p.init({});
  double disp = 0.0, force = 0.0, floor = 0.0;
  for (std::size_t k = 0; k < 5000; ++k) {
    p.sense(ground(k));
    disp = std::max(disp, std::fabs(p.state().base_disp_m));
    force = std::max(force, std::fabs(p.state().damper_force_n));
    p.advance({1.0, true});
    floor = std::max(floor, p.peak_floor_accel_m_s2());
  }
  p.sense(0.0);
  disp = std::max(disp, std::fabs(p.state().base_disp_m));
  const PlantSummary s = p.summary();
  EXPECT_EQ(s.peak_base_displacement_m, disp);
  EXPECT_EQ(s.peak_damper_force_n, force);
  EXPECT_EQ(s.peak_superstructure_accel_m_s2, floor);
  EXPECT_GT(s.peak_base_displacement_m, 0.0);
}

}  // namespace
}  // namespace mrd::plant
