// The firmware control core on the hardware plant (host_sim/plant: PWM drive,
// R–L(i) coil, the rig's quantized and noisy sensors, the damper parked
// 3 mm off its stroke centre): at rest it must leave the coil alone whatever
// the current sensor's bias, and in the four records of Table 6.2 at
// 0.1127 g (four synthetic motions when the shared records are absent) it
// must hold the coil to its rating and still beat passive-off.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "host_sim/plant/coil_figures.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/motions.hpp"
#include "mrd/units.hpp"

namespace mrd::run {
namespace {

plant::PlantSpec hardware_spec(double idle_years, double current_bias_a = 0.0, std::uint64_t seed = 1) {
  plant::PlantSpec spec;
  spec.kind = plant::PlantKind::kHardware;
  spec.idle_time_s = units::years_to_s(idle_years);
  spec.hardware.stroke_offset_m = 3.0e-3;  // `mrd sim --plant hardware` default
  spec.hardware.sensors.current_offset_a = current_bias_a;
  spec.hardware.sensors.seed = seed;
  return spec;
}

template <class Policy>
plant::PlantSummary run_semi_active(const plant::PlantSpec& spec, const std::vector<double>& accel_m_s2) {
  FirmwareController<Policy> c(fw::default_controller_config(control::ControlMode::kSemiActive, spec.step_s));
  const plant::PlantSummary s = run_closed_loop(spec, accel_m_s2, c);
  EXPECT_EQ(c.status().fallback_ticks + c.status().held_ticks + c.status().stale_inputs, 0u);
  return s;
}

template <class Policy>
class HardwareAtRestTest : public ::testing::Test {};
using Policies = ::testing::Types<num::Float32Policy, num::Fixed32Policy>;
TYPED_TEST_SUITE(HardwareAtRestTest, Policies);

TYPED_TEST(HardwareAtRestTest, LeavesTheCoilAloneForTenMinutesWhateverTheCurrentSensorsBias) {
  // No ground motion for 600 s; the LVDT reads 3 mm (RILD asks −kη·x ≈ −7.9 kN)
  // through 8.9 µm steps and 2 µm noise, the current sensor reads 5 mA noise
  // plus a bias. The velocity estimate's noise (σ ≈ 0.6 mm/s, one LVDT step
  // 1.5 mm/s; odbdco.hpp) stays far below v_on = 6 mm/s, so the direction is
  // never known and the target stays 0 A: the drive is asked for 0 A and the
  // coil carries none. Limits (RMS ≤ 0.05 A, peak ≤ 0.25 A) are the issue's;
  // the law gives exactly 0 A.
  const std::vector<double> rest(600000, 0.0);
  for (double bias_a : {0.0, 0.020, -0.020}) {
    for (std::uint64_t seed : {1u, 2u}) {
      const plant::PlantSummary s = run_semi_active<TypeParam>(hardware_spec(0.0, bias_a, seed), rest);
      EXPECT_LE(s.coil.rms_coil_current_a, 0.05) << bias_a << " A, seed " << seed;
      EXPECT_LE(s.coil.peak_coil_current_a, 0.25) << bias_a << " A, seed " << seed;
      EXPECT_EQ(s.coil.command_changes_per_s, 0.0) << bias_a << " A, seed " << seed;
      EXPECT_LT(s.coil.peak_coil_temperature_rise_k, 0.01) << bias_a << " A, seed " << seed;
    }
  }
}

const std::vector<StudyMotion>& motions() {
  static const std::vector<StudyMotion> m = thesis_study_motions(kThesisPga_g, 1e-3);
  return m;
}

/// One run, each computed once per test program. `control`: passive-off | float | fixed.
plant::PlantSummary hardware_run(const StudyMotion& motion, const std::string& control, double idle_years) {
  static std::map<std::tuple<std::string, std::string, double>, plant::PlantSummary> cache;
  const auto key = std::make_tuple(motion.name, control, idle_years);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  const plant::PlantSpec spec = hardware_spec(idle_years);
  plant::PlantSummary s;
  if (control == "passive-off") {
    auto off = make_controller(control::ControlMode::kPassiveOff, spec.step_s);
    s = run_closed_loop(spec, motion.accel_m_s2, *off);
  } else if (control == "float") {
    s = run_semi_active<num::Float32Policy>(spec, motion.accel_m_s2);
  } else {
    s = run_semi_active<num::Fixed32Policy>(spec, motion.accel_m_s2);
  }
  cache.emplace(key, s);
  return s;
}

TEST(HardwareClosedLoop, HoldsTheCoilToItsRatingAndBeatsPassiveOff) {
  // The steady ceiling is 2.5 A; over-drive ends 0.1 A short of it and the
  // drive (72 V into 4.8 Ω and 3–5 H) rises at most ~24 A/s, ≤ 24 mA per 1 ms
  // tick, so the coil may pass 2.5 A by the drive's PI overshoot only: the
  // issue's 2.75 A (10 % over the rating) bounds it. Peak base displacement
  // below passive-off's on every record and idle time: the damper adds
  // force in the direction that opposes the motion only.
  ASSERT_EQ(motions().size(), 4u);
  for (const auto& m : motions()) {
    const double off_m = hardware_run(m, "passive-off", 0.0).peak_base_displacement_m;
    for (double idle : {0.0, 2.5}) {
      const plant::PlantSummary sa = hardware_run(m, "float", idle);
      EXPECT_LE(sa.coil.peak_coil_current_a, 2.75) << m.name << ", idle " << idle;
      EXPECT_LT(sa.peak_base_displacement_m, off_m) << m.name << ", idle " << idle;
      // Bounded switching: the 30 ms dwell allows at most 2 target changes per
      // 30 ms (a move and its end) and 2 forcing changes each: < 140 per s.
      EXPECT_LT(sa.coil.command_changes_per_s, 140.0) << m.name << ", idle " << idle;
    }
  }
}

TEST(HardwareClosedLoop, FixedPointFollowsFloat) {
  // Both builds see the same sensor samples (same seed). Their decisions
  // differ only where a quantity rounds differently across a threshold
  // (F_db, v_on, I_band), which shifts a target change by a tick or a dwell
  // (30 ms); at the structure's 0.25 Hz and a coil that follows with a 0.7 s
  // field lag, one dwell shifts the force by at most a few percent for a
  // fraction of a cycle. Peaks within 3 % (displacement) and 5 % (force);
  // the coil's peak within 0.1 A (I_band).
  for (const auto& m : motions()) {
    for (double idle : {0.0, 2.5}) {
      const plant::PlantSummary f = hardware_run(m, "float", idle);
      const plant::PlantSummary q = hardware_run(m, "fixed", idle);
      EXPECT_NEAR(q.peak_base_displacement_m / f.peak_base_displacement_m, 1.0, 0.03) << m.name << ", idle " << idle;
      EXPECT_NEAR(q.peak_damper_force_n / f.peak_damper_force_n, 1.0, 0.05) << m.name << ", idle " << idle;
      EXPECT_NEAR(q.coil.peak_coil_current_a, f.coil.peak_coil_current_a, 0.1) << m.name << ", idle " << idle;
    }
  }
}

}  // namespace
}  // namespace mrd::run
