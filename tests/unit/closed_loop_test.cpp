// Closed-loop runner: wiring, signs and the idle-time behaviour of §6.5.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>

#include "mrd/units.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/motions.hpp"
#include "host_sim/run/sweep.hpp"
#include "host_sim/structure/building.hpp"

namespace mrd::run {
namespace {

std::vector<double> harmonic(double amp_m_s2, double freq_hz, double duration_s, double step_s) {
  std::vector<double> a;
  for (double t = 0.0; t < duration_s; t += step_s) a.push_back(amp_m_s2 * std::sin(2 * units::kPi * freq_hz * t));
  return a;
}

class RecordingController final : public Controller {
 public:
  explicit RecordingController(double current_a) : current_a_(current_a) {}
  void reset() override { inputs.clear(); }
  control::ControllerOutput step(const control::ControllerInput& in) override {
    inputs.push_back(in);
    control::ControllerOutput out;
    out.current_command_a = static_cast<float>(current_a_);
    return out;
  }
  std::vector<control::ControllerInput> inputs;

 private:
  double current_a_;
};

TEST(ClosedLoop, AtRestWithoutGroundMotion) {
  ConstantCurrentController c(2.5);
  const auto s = run_closed_loop({}, std::vector<double>(2000, 0.0), c);
  EXPECT_EQ(s.peak_base_displacement_m, 0.0);
  EXPECT_EQ(s.peak_damper_force_n, 0.0);
  EXPECT_EQ(s.peak_superstructure_accel_m_s2, 0.0);
}

// Without a damper the loop is the linear building: its steady response to
// a_g = A sin(ωt) follows from the frequency-domain solution, computed here
// independently of the simulator: (K − ω²M + iωC) X = −M·1·A.
TEST(ClosedLoop, WithoutDamperMatchesFrequencyDomainSolution) {
  plant::PlantSpec spec;
  spec.damper.bingham.fc_a_n = spec.damper.bingham.fc_b_n = 0.0;
  spec.damper.bingham.c0_a_ns_m = spec.damper.bingham.c0_b_ns_m = 0.0;
  const double f_hz = 0.4;
  const double amp = 0.5;
  const double w = 2 * units::kPi * f_hz;
  ConstantCurrentController c(0.0);
  // Let the 0.25 Hz mode's transient (ζ ≈ 5 %, decay time 1/(ζω) ≈ 13 s) die
  // out over 150 s, then look at the last 10 s.
  ClosedLoopRecord rec;
  run_closed_loop(spec, harmonic(amp, f_hz, 150.0, spec.step_s), c, &rec);
  const auto M = structure::mass_matrix(spec.building);
  const auto K = structure::stiffness_matrix(spec.building);
  const auto C = structure::damping_matrix(spec.building);
  const Eigen::Matrix<std::complex<double>, 6, 6> D =
      K.cast<std::complex<double>>() - (w * w) * M.cast<std::complex<double>>() +
      std::complex<double>(0.0, w) * C.cast<std::complex<double>>();
  const Eigen::Matrix<std::complex<double>, 6, 1> rhs = (-M * Eigen::Matrix<double, 6, 1>::Ones() * amp).cast<std::complex<double>>();
  const Eigen::Matrix<std::complex<double>, 6, 1> X = D.partialPivLu().solve(rhs);
  double peak = 0.0;
  for (std::size_t k = rec.time_s.size() - 10000; k < rec.time_s.size(); ++k) peak = std::max(peak, std::fabs(rec.base_disp_m[k]));
  EXPECT_NEAR(peak, std::abs(X(0)), 1e-3 * std::abs(X(0)));
}

// The damper only ever dissipates: F·v ≥ 0 at every step, in every mode.
TEST(ClosedLoop, DamperForceOpposesBaseVelocity) {
  for (double current : {0.0, 2.5}) {
    RecordingController c(current);
    ClosedLoopRecord rec;
    const auto m = synthetic_study_motion(3, kThesisPga_g, 1e-3, 20.0);
    run_closed_loop({}, m.accel_m_s2, c, &rec);
    for (std::size_t k = 0; k < rec.time_s.size(); ++k) ASSERT_GE(rec.damper_force_n[k] * rec.base_vel_m_s[k], 0.0);
    // The controller sees what the plant does.
    ASSERT_EQ(c.inputs.size(), rec.time_s.size());
    for (std::size_t k = 0; k < rec.time_s.size(); k += 997) {
      EXPECT_FLOAT_EQ(c.inputs[k].damper_disp_m, static_cast<float>(rec.base_disp_m[k]));
      EXPECT_FLOAT_EQ(c.inputs[k].damper_force_n, static_cast<float>(rec.damper_force_n[k]));
      EXPECT_EQ(c.inputs[k].tick, k);
    }
  }
}

// More current, more damping force, less base displacement.
TEST(ClosedLoop, PassiveOnReducesBaseDisplacement) {
  const auto m = synthetic_study_motion(2, kThesisPga_g, 1e-3, 30.0);
  ConstantCurrentController off(0.0), on(fw::kPassiveOnCurrent_a);
  const auto s_off = run_closed_loop({}, m.accel_m_s2, off);
  const auto s_on = run_closed_loop({}, m.accel_m_s2, on);
  EXPECT_LT(s_on.peak_base_displacement_m, s_off.peak_base_displacement_m);
  EXPECT_GT(s_on.peak_damper_force_n, s_off.peak_damper_force_n);
}

// §6.5: past the maximum settling time (0.853 years, Eq. 5.4) SQ is 1 and
// every result is the same; before it, idle time weakens the damper.
TEST(ClosedLoop, IdleTimeEffectSaturatesPastMaxSettlingTime) {
  const auto m = synthetic_study_motion(4, kThesisPga_g, 1e-3, 20.0);
  ConstantCurrentController on(fw::kPassiveOnCurrent_a);
  plant::PlantSpec spec;
  const auto at = [&](double years) {
    spec.idle_time_s = units::years_to_s(years);
    return run_closed_loop(spec, m.accel_m_s2, on);
  };
  const auto fresh = at(0.0), settled_09 = at(0.9), settled_1 = at(1.0), settled_25 = at(2.5), half = at(0.4);
  EXPECT_EQ(settled_09.sq, 1.0);
  EXPECT_EQ(settled_09.peak_base_displacement_m, settled_1.peak_base_displacement_m);
  EXPECT_EQ(settled_1.peak_damper_force_n, settled_25.peak_damper_force_n);
  EXPECT_LT(settled_1.peak_damper_force_n, half.peak_damper_force_n);
  EXPECT_LT(half.peak_damper_force_n, fresh.peak_damper_force_n);
  EXPECT_GT(settled_1.peak_base_displacement_m, fresh.peak_base_displacement_m);
}

TEST(Sweep, IdleGridIncludesItsEnd) {
  const auto g = idle_grid(0.0, 1.0, 0.05);
  ASSERT_EQ(g.size(), 21u);
  EXPECT_DOUBLE_EQ(g.front(), 0.0);
  EXPECT_NEAR(g.back(), 1.0, 1e-12);
}

TEST(Sweep, ParallelEqualsSerialAndKeepsOrder) {
  SweepSpec spec;
  spec.motions = {synthetic_study_motion(5, kThesisPga_g, 1e-3, 8.0), synthetic_study_motion(6, kThesisPga_g, 1e-3, 8.0)};
  spec.modes = {control::ControlMode::kPassiveOff, control::ControlMode::kPassiveOn};
  spec.idle_years = {0.0, 0.5, 1.0};
  spec.threads = 1;
  const auto serial = run_sweep(spec);
  spec.threads = 4;
  std::size_t calls = 0;
  const auto parallel = run_sweep(spec, [&](std::size_t done, std::size_t total) {
    ++calls;
    EXPECT_LE(done, total);
  });
  EXPECT_EQ(calls, 12u);
  ASSERT_EQ(serial.size(), 12u);
  for (std::size_t i = 0; i < serial.size(); ++i) {
    EXPECT_EQ(serial[i].motion_index, i / 6);
    EXPECT_EQ(serial[i].mode, spec.modes[(i / 3) % 2]);
    EXPECT_EQ(serial[i].idle_years, spec.idle_years[i % 3]);
    EXPECT_EQ(serial[i].summary.peak_base_displacement_m, parallel[i].summary.peak_base_displacement_m);
  }
}

}  // namespace
}  // namespace mrd::run
