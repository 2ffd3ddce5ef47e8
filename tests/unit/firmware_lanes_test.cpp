// The control core in lanes (fw::LanePolicy<N>) against the float build, one
// scalar controller per lane fed the lane's input: every output bit, every
// counter and the law's state equal, in every mode, on inputs full of what
// the masks decide (flagged, NaN, infinite, out-of-range and stuck signals,
// stale and future samples, drive faults, lanes restarted at different ticks)
// and on a damper loop that drives ODBDCO through all four branches.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "firmware/core/damper_controller.hpp"

namespace mrd::fw {
namespace {

using control::ControlMode;

/// A small deterministic generator (64-bit LCG, top bits).
class LanesTestRng {
 public:
  explicit LanesTestRng(std::uint64_t seed = 0) : s_(seed * 2862933555777941757ull + 3037000493ull) {}
  double uniform() {
    s_ = s_ * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s_ >> 11) * 0x1.0p-53;
  }
  bool chance(double p) { return uniform() < p; }

 private:
  std::uint64_t s_;
};

/// One lane's world: a sinusoidal stroke, a damper force that follows the
/// coil current (Bingham-like), a coil that lags its command, and faults.
struct LanesTestWorld {
  LanesTestRng rng{};
  double amplitude_m = 0.05;
  double omega_rad_s = 1.0;
  double coil_a = 0.0;
  std::uint64_t tick = 0;     ///< ticks since the lane's reset
  int stuck_left = 0;         ///< ticks the stroke and force stay frozen
  int drive_fault_left = 0;
  int bad_stroke_left = 0;    ///< ticks the stroke stays flagged (SAFE-2)
  float frozen_disp = 0.0f;
  float frozen_force = 0.0f;

  LanesTestWorld() = default;
  LanesTestWorld(std::uint64_t seed, double amplitude, double omega)
      : rng(seed), amplitude_m(amplitude), omega_rad_s(omega) {}

  control::ControllerInput next() {
    const double t = static_cast<double>(tick) * 1e-3;
    control::ControllerInput in;
    in.tick = tick;
    // A stroke whose amplitude swells and fades, so the direction rests too.
    const double envelope = 0.5 + 0.5 * std::sin(0.37 * t);
    const double x = amplitude_m * envelope * std::sin(omega_rad_s * t);
    const double v = amplitude_m * envelope * omega_rad_s * std::cos(omega_rad_s * t);
    const double fc = 2.0e4 + 6.0e4 * std::fabs(coil_a);
    const double force = (v > 0.0 ? fc : (v < 0.0 ? -fc : 0.0)) + 4.0e5 * v + 3.0e3 * (rng.uniform() - 0.5);
    in.damper_disp_m = static_cast<float>(x);
    in.damper_force_n = static_cast<float>(force);
    in.ground_accel_m_s2 = static_cast<float>(0.8 * std::sin(2.1 * t) + 0.05 * (rng.uniform() - 0.5));
    in.base_accel_m_s2 = static_cast<float>(0.3 * std::sin(1.3 * t));
    in.coil_current_a = static_cast<float>(coil_a + 0.004 * (rng.uniform() - 0.5));
    // Stuck stroke and force while the ground shakes (the guard's stuck test).
    if (stuck_left == 0 && rng.chance(2e-4)) {
      stuck_left = 700;
      frozen_disp = in.damper_disp_m;
      frozen_force = in.damper_force_n;
    }
    if (stuck_left > 0) {
      --stuck_left;
      in.damper_disp_m = frozen_disp;
      in.damper_force_n = frozen_force;
    }
    // Single-tick faults of every kind, on every signal.
    constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
    constexpr float inf_f = std::numeric_limits<float>::infinity();
    float* signals[] = {&in.damper_disp_m, &in.damper_force_n, &in.ground_accel_m_s2, &in.base_accel_m_s2,
                        &in.coil_current_a};
    for (float* s : signals) {
      if (stuck_left > 0) break;  // a fault would end the frozen run
      if (rng.chance(2e-3)) *s = kNan;
      if (rng.chance(1e-3)) *s = rng.chance(0.5) ? inf_f : -inf_f;
      if (rng.chance(1e-3)) *s = 1.0e7f;
    }
    if (stuck_left == 0 && rng.chance(2e-3)) in.flags.disp_valid = false;
    if (stuck_left == 0 && rng.chance(2e-3)) in.flags.force_valid = false;
    if (rng.chance(2e-3)) in.flags.ground_accel_valid = false;
    if (rng.chance(2e-3)) in.flags.base_accel_valid = false;
    // Runs of bad stroke samples (SAFE-2's hold, then its fallback).
    if (bad_stroke_left == 0 && rng.chance(3e-4)) bad_stroke_left = 20;
    if (bad_stroke_left > 0) {
      --bad_stroke_left;
      in.damper_disp_m = kNan;
    }
    // Stale (repeated or too old) and future samples.
    if (tick > 3 && rng.chance(2e-3)) in.tick = tick - 1 - static_cast<std::uint64_t>(rng.uniform() * 3.0);
    if (rng.chance(1e-3)) in.tick = tick + 1;
    // The drive's fault line, held for a while.
    if (drive_fault_left == 0 && rng.chance(1e-4)) drive_fault_left = 30;
    if (drive_fault_left > 0) {
      --drive_fault_left;
      in.flags.drive_fault = true;
    }
    ++tick;
    return in;
  }

  /// The coil follows the drive's command (a 25 ms lag), 0 A with the drive off.
  void drive(const control::ControllerOutput& out) {
    const double target = out.drive_enable ? static_cast<double>(out.current_command_a) : 0.0;
    coil_a += (target - coil_a) * 0.04;
  }
};

bool lanes_test_same_bits(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }

template <int N>
void expect_lanes_equal_float_build(ControlMode mode, std::uint64_t seed, int ticks) {
  const ControllerConfig config = default_controller_config(mode, 1e-3);
  DamperController<LanePolicy<N>> lanes;
  ASSERT_EQ(lanes.init(config), ConfigError::kNone);
  std::array<DamperController<num::Float32Policy>, N> one{};
  std::array<LanesTestWorld, N> world{};
  for (int l = 0; l < N; ++l) {
    const double d = static_cast<double>(l);
    world[l] = LanesTestWorld(seed * 97 + static_cast<std::uint64_t>(l), 0.02 + 0.06 * d / N, 1.2 + 0.9 * d);
  }
  for (auto& c : one) ASSERT_EQ(c.init(config), ConfigError::kNone);
  LanesTestRng restarts(seed + 1);
  using Mask = typename LaneTypes<LanePolicy<N>>::Mask;
  for (int k = 0; k < ticks; ++k) {
    // A lane restarts now and then (a new run in the batch), the others run on.
    Mask restart{};
    for (int l = 0; l < N; ++l) {
      if (restarts.chance(2e-4)) {
        restart[l] = -1;
        one[l].reset();
        world[l].tick = 0;
        world[l].coil_a = 0.0;
      }
    }
    if (num::any(restart)) lanes.reset(restart);
    typename DamperController<LanePolicy<N>>::Input in;
    std::array<control::ControllerInput, N> scalar_in;
    for (int l = 0; l < N; ++l) {
      const control::ControllerInput s = world[l].next();
      scalar_in[l] = s;
      in.tick[l] = static_cast<std::uint32_t>(s.tick);
      in.damper_disp_m[l] = s.damper_disp_m;
      in.damper_force_n[l] = s.damper_force_n;
      in.ground_accel_m_s2[l] = s.ground_accel_m_s2;
      in.base_accel_m_s2[l] = s.base_accel_m_s2;
      in.coil_current_a[l] = s.coil_current_a;
      in.flags.disp_valid[l] = s.flags.disp_valid ? -1 : 0;
      in.flags.force_valid[l] = s.flags.force_valid ? -1 : 0;
      in.flags.ground_accel_valid[l] = s.flags.ground_accel_valid ? -1 : 0;
      in.flags.base_accel_valid[l] = s.flags.base_accel_valid ? -1 : 0;
      in.flags.drive_fault[l] = s.flags.drive_fault ? -1 : 0;
    }
    const typename DamperController<LanePolicy<N>>::Output out = lanes.step(in);
    for (int l = 0; l < N; ++l) {
      const control::ControllerOutput o = one[l].step(scalar_in[l]);
      ASSERT_TRUE(lanes_test_same_bits(out.current_command_a[l], o.current_command_a))
          << "lane " << l << " tick " << k << ": " << out.current_command_a[l] << " A, float build "
          << o.current_command_a << " A";
      ASSERT_TRUE(lanes_test_same_bits(out.desired_force_n[l], o.desired_force_n)) << "lane " << l << " tick " << k;
      ASSERT_EQ(out.drive_enable[l] != 0, o.drive_enable) << "lane " << l << " tick " << k;
      ASSERT_EQ(lanes.law().direction()[l], one[l].law().direction()) << "lane " << l << " tick " << k;
      world[l].drive(o);
    }
  }
  // Every counter, per lane.
  const auto& ls = lanes.status();
  for (int l = 0; l < N; ++l) {
    const DamperControllerStatus& s = one[l].status();
    EXPECT_EQ(ls.ticks[l], s.ticks) << l;
    for (int f = 0; f < kInputFaultKinds; ++f) EXPECT_EQ(ls.invalid_by_kind[f][l], s.invalid_by_kind[f]) << l << " " << f;
    for (int g = 0; g < kInputSignals; ++g) {
      EXPECT_EQ(ls.invalid_by_signal[g][l], s.invalid_by_signal[g]) << l << " " << g;
      EXPECT_EQ(ls.last_faults[g][l], static_cast<int>(s.last_faults[g])) << l << " " << g;
    }
    for (int b = 0; b < kOdbdcoBranches; ++b) EXPECT_EQ(ls.branch_ticks[b][l], s.branch_ticks[b]) << l << " " << b;
    EXPECT_EQ(ls.stale_inputs[l], s.stale_inputs) << l;
    EXPECT_EQ(ls.drive_fault_ticks[l], s.drive_fault_ticks) << l;
    EXPECT_EQ(ls.drive_disabled_ticks[l], s.drive_disabled_ticks) << l;
    EXPECT_EQ(ls.held_ticks[l], s.held_ticks) << l;
    EXPECT_EQ(ls.fallback_ticks[l], s.fallback_ticks) << l;
    EXPECT_EQ(ls.desired_force_clamps[l], s.desired_force_clamps) << l;
    EXPECT_TRUE(lanes_test_same_bits(lanes.coil_i2t().ceiling_a()[l], one[l].coil_i2t().ceiling_a())) << l;
  }
}

/// What the inputs exercised, summed over the lanes' scalar twins: the test
/// means little unless every fault kind and every ODBDCO branch occurred.
template <int N>
void expect_inputs_exercise_every_mask(std::uint64_t seed, int ticks) {
  const ControllerConfig config = default_controller_config(ControlMode::kSemiActive, 1e-3);
  DamperController<num::Float32Policy> c;
  ASSERT_EQ(c.init(config), ConfigError::kNone);
  LanesTestWorld w(seed * 97, 0.08, 2.1);
  for (int k = 0; k < ticks; ++k) w.drive(c.step(w.next()));
  const DamperControllerStatus& s = c.status();
  for (InputFault f : {InputFault::kFlagged, InputFault::kNotANumber, InputFault::kInfinite, InputFault::kOutOfRange,
                       InputFault::kStuck}) {
    EXPECT_GT(s.invalid(f), 0u) << input_fault_name(f);
  }
  for (int b = 0; b < kOdbdcoBranches; ++b) EXPECT_GT(s.branch_ticks[b], 0u) << "branch " << b;
  EXPECT_GT(s.stale_inputs, 0u);
  EXPECT_GT(s.held_ticks, 0u);
  EXPECT_GT(s.fallback_ticks, 0u);
  EXPECT_GT(s.drive_fault_ticks, 0u);
  EXPECT_GT(s.drive_disabled_ticks, s.drive_fault_ticks);
}

TEST(FirmwareLanes, InputsExerciseEveryFaultAndBranch) { expect_inputs_exercise_every_mask<1>(5, 60000); }

TEST(FirmwareLanes, EightLanesEqualTheFloatBuildSemiActive) {
  expect_lanes_equal_float_build<8>(ControlMode::kSemiActive, 5, 60000);
}
TEST(FirmwareLanes, FourLanesEqualTheFloatBuildSemiActive) {
  expect_lanes_equal_float_build<4>(ControlMode::kSemiActive, 11, 30000);
}
TEST(FirmwareLanes, TwoLanesEqualTheFloatBuildSemiActive) {
  expect_lanes_equal_float_build<2>(ControlMode::kSemiActive, 17, 30000);
}
TEST(FirmwareLanes, EightLanesEqualTheFloatBuildPassiveOn) {
  expect_lanes_equal_float_build<8>(ControlMode::kPassiveOn, 23, 20000);
}
TEST(FirmwareLanes, EightLanesEqualTheFloatBuildPassiveOff) {
  expect_lanes_equal_float_build<8>(ControlMode::kPassiveOff, 29, 20000);
}

}  // namespace
}  // namespace mrd::fw
