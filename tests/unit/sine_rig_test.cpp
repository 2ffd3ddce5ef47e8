// Sine-test rig of §5.2 and the calibration of ∫Q dt (Table 5.2).
#include <gtest/gtest.h>

#include <cmath>

#include "host_sim/run/mixing_calibration.hpp"
#include "host_sim/run/sine_rig.hpp"
#include "mrd/units.hpp"

namespace mrd::run {
namespace {

// Peak velocity of 25.4 mm at 0.5 Hz: 0.0254 · 2π · 0.5 = 0.0797965 m/s.
// Fully mixed at 2.5 A (Eq. 4.1–4.3, Table 4.1):
//   f_c = 141.1709 kN, c_0 = 0.349062 kN·s/mm · 79.7965 mm/s = 27.8539 kN
//   F = 169.0248 kN
TEST(SineRig, FullyMixedForceIsEq41AtPeakVelocity) {
  SineRigSpec s{0.0254, 0.5, 2.5, 0.0, 4.0, 1e-3};
  const SineMetrics m = run_sine_rig(s);
  EXPECT_NEAR(m.fully_mixed_force_n / 1e3, 169.0248, 1e-3);
  // Fully mixed: nothing to recover, max equals the fully mixed force and
  // the 90 % level is met at once.
  EXPECT_NEAR(m.max_force_n, m.fully_mixed_force_n, 1e-6);
  EXPECT_DOUBLE_EQ(m.rise_time_90_s, 0.0);
}

// Case 3 (2.5 years ⇒ SQ = 1): a_PR = 0.100821 (Eq. 5.6). Eq. 5.10–5.12 at
// the first velocity peak (t = 0, nothing displaced yet):
//   f_c = 0.100821·170 + (4.1 − 17.1396)·e^−1.75 = 17.1396 − 2.2660 = 14.8736 kN
//   c_0 = 0.100821·0.365 + (0.0825 − 0.0368)·e^−2.875 = 0.036800 + 0.002578 = 0.039378 kN·s/mm
//   F = 14.8736 + 0.039378·79.7965 = 18.0158 kN   (Table 5.2 measured 20.06 kN)
TEST(SineRig, InitialForceUsesTheInitialParticipantRatio) {
  SineRigSpec s{0.0254, 0.5, 2.5, units::years_to_s(2.5), 2.0, 1e-3};
  const SineMetrics m = run_sine_rig(s);
  EXPECT_DOUBLE_EQ(m.sq, 1.0);
  EXPECT_NEAR(m.initial_force_n / 1e3, 18.0158, 1e-3);
}

// The false ceiling of Eq. 5.7: however long the mixing, PR stays below
// b_PR = 0.609388 at SQ = 1, so the force stays below Eq. 5.12 at that PR:
//   f_c = 0.609388·170 + (4.1 − 103.596)·e^−1.75 = 103.596 − 17.290 = 86.306 kN
//   c_0 = 0.609388·0.365 + (0.0825 − 0.222427)·e^−2.875 = 0.222427 − 0.007894 = 0.214533 kN·s/mm
//   F = 86.306 + 0.214533·79.7965 = 103.425 kN
TEST(SineRig, MaxForceBoundedByFinalParticipantRatio) {
  SineRigSpec s{0.0254, 0.5, 2.5, units::years_to_s(2.5), 200.0, 1e-3};
  const SineMetrics m = run_sine_rig(s);
  EXPECT_LE(m.max_force_n / 1e3, 103.425 + 1e-3);
  EXPECT_GT(m.max_force_n / 1e3, 103.0);  // and it gets close after 100 cycles
}

TEST(SineRig, RecordHoldsTheTimeSeries) {
  SineRigSpec s{0.0254, 0.5, 2.5, units::years_to_s(0.5), 2.0, 1e-3};
  SineRecord rec;
  run_sine_rig(s, {}, {}, &rec);
  ASSERT_EQ(rec.time_s.size(), 2001u);
  EXPECT_DOUBLE_EQ(rec.disp_m[500], 0.0254);  // sin(π/2) at t = 0.5 s
  EXPECT_NEAR(rec.current_a[0], 2.5, 1e-12);  // steady current from the start
  for (std::size_t k = 1; k < rec.pr.size(); ++k) ASSERT_GE(rec.pr[k], rec.pr[k - 1]);
}

// Table 5.2 rise times with the calibrated ∫Q dt: the model meets the six
// measured values with an RMS log error below 0.2 (≈ 20 %), and each 90 %
// rise time within 20 %. (Case 1's 95 % time is quantized by the 1 s
// spacing of force peaks at 0.5 Hz: the model crosses 95 % at the third
// peak, 2.9 s, against 1.956 s measured.)
TEST(SineRig, CalibratedMixingReproducesTable52RiseTimes) {
  const MixingCalibration c = evaluate_rise_times({});
  EXPECT_LT(c.rms_log_error, 0.20);
  ASSERT_EQ(c.cases.size(), 3u);
  for (const auto& k : c.cases) {
    SCOPED_TRACE(k.name);
    EXPECT_NEAR(k.model_rise_90_s / k.thesis_rise_90_s, 1.0, 0.20);
  }
  // The slow case stays slow and the fast one fast: order as measured.
  EXPECT_LT(c.cases[0].model_rise_90_s, c.cases[1].model_rise_90_s);
  EXPECT_LT(c.cases[1].model_rise_90_s, c.cases[2].model_rise_90_s);
}

// Only A/unit matters: doubling the area and the unit changes nothing.
TEST(SineRig, OnlyTheRatioOfAreaToUnitMatters) {
  physics::MrDamperParams a;
  physics::MrDamperParams b;
  b.pr.flow_area_m2 *= 2.0;
  b.pr.volume_unit_m3 *= 2.0;
  SineRigSpec s{0.00762, 1.0, 2.5, units::years_to_s(0.5), 20.0, 1e-3};
  EXPECT_NEAR(run_sine_rig(s, a).rise_time_90_s, run_sine_rig(s, b).rise_time_90_s, 1e-9);
}

}  // namespace
}  // namespace mrd::run
