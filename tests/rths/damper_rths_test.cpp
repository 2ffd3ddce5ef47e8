// The thesis's own RTHS set-up, emulated: the 6-DOF thesis building
// numerical, the 200 kN MR damper (with its idle effects) physical behind an
// actuator with a 10-20 ms delay and a 2 ms servo lag, ODBDCO (or
// passive-on) running beside it as in the closed loop, on El Centro at the
// thesis's PGA (Table 6.3: 0.1127 g).
//
// CI holds: with no delay and no lag the actuator is at the target at every
// sample and the run is the all-numerical closed loop's (run_closed_loop,
// what `mrd sim` runs); the model-based compensation tracks better than
// none; with it, the peak base displacement is within the 2 % of the
// closed loop's (15 ms in CI, 10/15/20 ms with MRD_RTHS_STUDY=1, which also
// prints the gaps beside the uncompensated ones).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "host_sim/excitation/ground_motion.hpp"
#include "host_sim/rths/damper_rths.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/motions.hpp"
#include "mrd/units.hpp"

namespace mrd::rths {
namespace {

std::vector<double> thesis_el_centro_1khz() {
  const auto g = excitation::read_ground_motion(std::filesystem::path(MRD_SHARED_DIR) / "ground_motions" /
                                                "elcentro_ns.csv");
  const auto scaled = excitation::scaled_to_pga(g, run::kThesisPga_g * units::kStandardGravity_m_s2);
  return excitation::resample_linear(scaled, 1e-3);
}

DamperRthsResult thesis_rths(control::ControlMode mode, double delay_s, double lag_s, bool compensate,
                             const std::vector<double>& ag, double model_force_scale = 1.0) {
  DamperRthsSpec spec;
  spec.model_force_scale = model_force_scale;
  spec.delay_s = delay_s;
  spec.lag_s = lag_s;
  spec.compensate = compensate;
  auto controller = run::make_controller(mode, spec.plant.step_s);
  return run_damper_rths(spec, ag, *controller);
}

double closed_loop_peak_m(control::ControlMode mode, const std::vector<double>& ag) {
  plant::PlantSpec spec;
  auto controller = run::make_controller(mode, spec.step_s);
  return run::run_closed_loop(spec, ag, *controller).peak_base_displacement_m;
}

TEST(DamperRths, WithoutDelayOrLagTheActuatorIsAtTheTarget) {
  // D = 0, τ = 0: the command made from x[n+1] is held over [t_n, t_{n+1}],
  // so the actuator reaches x[n+1] exactly (the emulation's zero point).
  const auto ag = thesis_el_centro_1khz();
  const DamperRthsResult r = thesis_rths(control::ControlMode::kSemiActive, 0.0, 0.0, false, ag);
  EXPECT_LT(r.peak_tracking_error_m, 1e-12);
  EXPECT_TRUE(std::isfinite(r.peak_base_displacement_m));
}

TEST(DamperRths, WithoutDelayOrLagItIsTheClosedLoop) {
  // D = 0, τ = 0: the actuator reaches the building's deformation and rate
  // at every sample, so the specimen gives the force the closed loop's damper
  // gives, and the building steps alike: the same run up to rounding.
  const auto ag = thesis_el_centro_1khz();
  for (const auto mode : {control::ControlMode::kPassiveOn, control::ControlMode::kSemiActive}) {
    const double ref = closed_loop_peak_m(mode, ag);
    for (const bool compensate : {false, true}) {
      const DamperRthsResult r = thesis_rths(mode, 0.0, 0.0, compensate, ag);
      EXPECT_LT(std::fabs(r.peak_base_displacement_m - ref), 1e-3 * ref) << control::mode_name(mode);
    }
  }
}

TEST(DamperRths, CompensationTracksBetterThanNone) {
  const auto ag = thesis_el_centro_1khz();
  for (const auto mode : {control::ControlMode::kPassiveOn, control::ControlMode::kSemiActive}) {
    const DamperRthsResult with = thesis_rths(mode, 0.015, 0.002, true, ag);
    const DamperRthsResult without = thesis_rths(mode, 0.015, 0.002, false, ag);
    EXPECT_TRUE(std::isfinite(with.peak_base_displacement_m));
    EXPECT_LT(with.rms_tracking_error_pct, without.rms_tracking_error_pct) << control::mode_name(mode);
  }
}

// The criterion: the peak base displacement within 2 % of the
// all-numerical closed loop, with compensation, for a 10-20 ms delay and the
// 2 ms lag. CI holds it at 15 ms per mode; MRD_RTHS_STUDY=1 holds it at 10,
// 15 and 20 ms and prints the gaps beside the uncompensated ones.
TEST(DamperRths, PeakBaseDisplacementWithinTwoPercentOfTheClosedLoop) {
  const bool study = std::getenv("MRD_RTHS_STUDY") != nullptr;
  const auto ag = thesis_el_centro_1khz();
  for (const auto mode : {control::ControlMode::kPassiveOn, control::ControlMode::kSemiActive}) {
    const double ref = closed_loop_peak_m(mode, ag);
    for (const double delay_s : study ? std::vector<double>{0.010, 0.015, 0.020} : std::vector<double>{0.015}) {
      const DamperRthsResult c = thesis_rths(mode, delay_s, 0.002, true, ag);
      EXPECT_LT(std::fabs(c.peak_base_displacement_m - ref), 0.02 * ref)
          << control::mode_name(mode) << ", delay " << 1e3 * delay_s << " ms";
      if (!study) continue;
      const DamperRthsResult u = thesis_rths(mode, delay_s, 0.002, false, ag);
      std::printf("%-12s delay %2.0f ms + 2 ms lag: peak base displacement gap compensated %+6.2f %% (tracking rms "
                  "%.2f %%, velocity %.2f %%), uncompensated %+6.2f %% (tracking rms %.2f %%)\n",
                  control::mode_name(mode), 1e3 * delay_s, 100.0 * (c.peak_base_displacement_m - ref) / ref,
                  c.rms_tracking_error_pct, c.rms_velocity_error_pct, 100.0 * (u.peak_base_displacement_m - ref) / ref,
                  u.rms_tracking_error_pct);
      for (const double scale : {0.9, 1.1}) {
        const DamperRthsResult m = thesis_rths(mode, delay_s, 0.002, true, ag, scale);
        std::printf("%-12s delay %2.0f ms, the compensator's damper model's force x %.1f: gap %+6.2f %% (tracking "
                    "rms %.2f %%, velocity %.2f %%)\n",
                    control::mode_name(mode), 1e3 * delay_s, scale, 100.0 * (m.peak_base_displacement_m - ref) / ref,
                    m.rms_tracking_error_pct, m.rms_velocity_error_pct);
      }
    }
  }
}

}  // namespace
}  // namespace mrd::rths
