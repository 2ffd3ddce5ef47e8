// The damper model of the discrepancy workflow against independent
// references: the project's MrDamper block (Eq. 4.1–4.5, 5.6–5.12), the
// analytic coil step response, a hand-derived thermal-fade solution, and
// exact shifts and dead bands for the delay and the free play.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "host_sim/discrepancy/damper_model.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/units.hpp"

namespace mrd::discrepancy {
namespace {

constexpr double kDt = 1e-3;

/// Sine displacement of amplitude a and frequency f with its exact velocity,
/// a current command stepping through `levels` every `hold_s`.
ModelInput sine_input(std::size_t n, double a, double f, std::vector<double> levels, double hold_s) {
  ModelInput in;
  const double w = 2 * units::kPi * f;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * kDt;
    in.time_s.push_back(t);
    in.disp_m.push_back(a * std::sin(w * t));
    in.vel_m_s.push_back(a * w * std::cos(w * t));
    in.current_cmd_a.push_back(levels[static_cast<std::size_t>(t / hold_s) % levels.size()]);
  }
  return in;
}

TEST(DiscrepancyModel, BaselineMatchesMrDamper) {
  const ModelInput in = sine_input(6000, 0.02, 0.7, {0.0, 2.5, 1.0, 0.3}, 1.3);
  const DamperModel model(in);
  ModelWorkspace ws;
  std::vector<double> f;
  model.simulate(EffectSet{}, {}, ws, f);
  physics::MrDamper ref(physics::MrDamperParams{}, kDt, 0.0);
  ref.reset(0.0, in.current_cmd_a[0]);
  for (std::size_t k = 0; k < in.time_s.size(); ++k) {
    const double expect = ref.step(in.current_cmd_a[k], in.vel_m_s[k]);
    ASSERT_NEAR(f[k], expect, 1e-6 * (1.0 + std::fabs(expect))) << k;
  }
}

// A measured coil current stands for Eq. 4.5's fast branch; the field lags it
// by the slow one alone. A step of the measured current from 0 to 2 A at
// sample k0, weights ½, τ_slow = 0.7 s, ZOH at 1 kHz:
//   i[k0]       = ½ · 2 + ½ · 0                      = 1 A (the slow branch has seen no 2 A yet)
//   i[k0 + 700] = ½ · 2 + ½ · 2 (1 − e^(−700 · 1e-3 / 0.7)) = 1 + (1 − 0.367879) = 1.632121 A
// The command (here a constant 2.5 A the drive did not deliver) is not used.
TEST(DiscrepancyModel, AMeasuredCoilCurrentReplacesTheFastBranch) {
  ModelInput in = sine_input(3000, 0.02, 0.7, {2.5}, 10.0);
  constexpr std::size_t k0 = 1000;
  for (std::size_t k = 0; k < in.time_s.size(); ++k) in.current_meas_a.push_back(k < k0 ? 0.0 : 2.0);
  const DamperModel model(in);
  const std::vector<double>& i = model.baseline_current_a();
  EXPECT_DOUBLE_EQ(i[k0 - 1], 0.0);
  EXPECT_NEAR(i[k0], 1.0, 1e-12);
  EXPECT_NEAR(i[k0 + 700], 1.632121, 1e-6);
  // coil_lag scales the slow branch it keeps: at twice τ_slow, 700 samples are half a time constant.
  ModelWorkspace ws;
  std::vector<double> f_lag;
  const std::vector<double> twice{2.0};
  model.simulate(EffectSet{{Effect::coil_lag}}, twice, ws, f_lag);
  ASSERT_EQ(ws.current_a.size(), in.time_s.size());
  EXPECT_NEAR(ws.current_a[k0 + 700], 1.0 + (1.0 - std::exp(-0.5)), 1e-6);
}

// A model put on another baseline (as a calibration does at every
// evaluation) gives, bit for bit, the force of a model built on it: for new
// current laws with the same coil, for another coil, and for a baseline that
// needs the averaged acceleration the first one did not.
TEST(DiscrepancyModel, PutOnAnotherBaselineEqualsBuiltOnIt) {
  const ModelInput in = sine_input(4000, 0.02, 0.7, {0.0, 2.5, 1.0, 0.3}, 0.9);
  Baseline laws = thesis_baseline();
  laws.yield_n.at_zero *= 1.3;
  laws.viscous_ns_m.rate_per_a *= 0.7;
  Baseline coil = laws;
  coil.coil.tau_slow_s *= 2.0;
  Baseline timed = coil;
  timed.transition_time_s = 0.004;
  ASSERT_TRUE(timed.has_transition_time());
  DamperModel moved(in);
  ModelWorkspace ws;
  for (const Baseline* b : {&laws, &coil, &timed}) {
    moved.set_baseline(*b);
    const DamperModel built(in, *b);
    std::vector<double> f_moved, f_built;
    moved.simulate(EffectSet{}, {}, ws, f_moved);
    built.simulate(EffectSet{}, {}, ws, f_built);
    EXPECT_EQ(f_moved, f_built);
    EXPECT_EQ(moved.baseline_current_a(), built.baseline_current_a());
  }
  // The coil's constants matter: the second coil's current differs from the first's.
  EXPECT_NE(DamperModel(in, laws).baseline_current_a(), DamperModel(in, coil).baseline_current_a());
}

TEST(DiscrepancyModel, IdleSettlingMatchesMrDamperWithTheSameSq) {
  const ModelInput in = sine_input(8000, 0.0254, 0.5, {2.5}, 100.0);
  const DamperModel model(in);
  ModelWorkspace ws;
  std::vector<double> f;
  const double sq = 0.586;  // 0.5 year (Table 5.1, case 2) by Eq. 5.5
  const std::vector<double> p{sq};
  model.simulate(EffectSet{{Effect::idle_settling}}, p, ws, f);
  physics::MrDamper ref(physics::MrDamperParams{}, kDt, sq);
  ref.reset(sq, 2.5);
  for (std::size_t k = 0; k < in.time_s.size(); ++k) {
    const double expect = ref.step(2.5, in.vel_m_s[k]);
    ASSERT_NEAR(f[k], expect, 1e-6 * (1.0 + std::fabs(expect))) << k;
  }
}

// Step of the command from 0 to 2 A at t = 0 (the coil at rest at 0 A):
// i(t) = 2 (1 − ½ e^{−t/(0.7 s)} − ½ e^{−t/(0.03 s)}), exact at the samples
// (ZOH), with both time constants scaled by s for coil_lag.
TEST(DiscrepancyModel, CoilLagScalesTheStepResponse) {
  ModelInput in = sine_input(5000, 0.01, 1.0, {2.0}, 100.0);
  in.current_cmd_a[0] = 0.0;  // at rest before the step
  const DamperModel model(in);
  for (const double s : {1.0, 3.0}) {
    std::vector<double> i;
    model.coil_current(s, i);
    for (std::size_t k = 2; k < i.size(); k += 97) {
      const double t = static_cast<double>(k - 1) * kDt;  // the step acts from sample 1 on
      const double expect = 2.0 * (1.0 - 0.5 * std::exp(-t / (0.7 * s)) - 0.5 * std::exp(-t / (0.03 * s)));
      ASSERT_NEAR(i[k], expect, 1e-9) << "scale " << s << " k " << k;
    }
  }
}

TEST(DiscrepancyModel, TimeDelayShiftsTheForce) {
  const ModelInput in = sine_input(3000, 0.02, 1.0, {1.5}, 100.0);
  const DamperModel model(in);
  ModelWorkspace ws;
  std::vector<double> base, d7, d75;
  model.simulate(EffectSet{}, {}, ws, base);
  const std::vector<double> p7{0.007};
  const std::vector<double> p75{0.0075};
  model.simulate(EffectSet{{Effect::time_delay}}, p7, ws, d7);
  model.simulate(EffectSet{{Effect::time_delay}}, p75, ws, d75);
  for (std::size_t k = 10; k < base.size(); ++k) {
    ASSERT_NEAR(d7[k], base[k - 7], 1e-6) << k;
    ASSERT_NEAR(d75[k], 0.5 * (base[k - 7] + base[k - 8]), 1e-6) << k;  // halfway between samples
  }
  EXPECT_DOUBLE_EQ(d7[3], base[0]);  // before the record: its first force
}

// Triangle displacement at ±v0 = 50 mm/s: after each reversal the rod stands
// still (zero velocity, zero force: TF(0) = 0, Eq. 4.4) while the actuator
// crosses the whole free play, i.e. for free_play / v0 = 2 mm / 50 mm/s =
// 40 ms, then follows it again with the baseline force. The engagement is
// averaged over ±3 ms, so 6 ms are left out at each end.
/// Triangle displacement at ±v0 reversing every half_period_s, 1 A.
ModelInput triangle_input(std::size_t n, double v0, double half_period_s) {
  ModelInput in;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * kDt;
    const double ph = std::fmod(t, 2 * half_period_s);
    const bool up = ph < half_period_s;
    in.time_s.push_back(t);
    in.disp_m.push_back(up ? v0 * ph : v0 * (2 * half_period_s - ph));
    in.vel_m_s.push_back(up ? v0 : -v0);
    in.current_cmd_a.push_back(1.0);
  }
  return in;
}

TEST(DiscrepancyModel, BacklashHoldsTheRodForTheFreePlay) {
  const double v0 = 0.05;
  const DamperModel model(triangle_input(4000, v0, 0.8));
  ModelWorkspace ws;
  std::vector<double> base, bl;
  model.simulate(EffectSet{}, {}, ws, base);
  const std::vector<double> p{0.002, 0.0};  // a hard stop
  model.simulate(EffectSet{{Effect::backlash}}, p, ws, bl);
  for (const double rev : {0.8, 1.6, 2.4}) {
    for (double t = rev + 0.0065; t < rev + 0.0335; t += 0.001) {
      const auto k = static_cast<std::size_t>(std::lround(t / kDt));
      EXPECT_NEAR(bl[k], 0.0, 1e-6) << "t " << t;
    }
    for (double t = rev + 0.0465; t < rev + 0.3; t += 0.01) {
      const auto k = static_cast<std::size_t>(std::lround(t / kDt));
      EXPECT_NEAR(bl[k], base[k], 1e-6) << "t " << t;
    }
  }
}

// A compliant stop over a quarter of a 2 mm play (contact length c = 0.5 mm),
// the same triangle at v0 = 50 mm/s. After a reversal the rod stands still
// while the actuator crosses 2 mm − c = 1.5 mm (30 ms); from there the stop
// takes up the motion linearly with penetration, d rod/dx = 1 − (h − w)/c,
// so the rod's velocity is v0 (1 − exp(−(t − t_c)/τ)), τ = c / v0 = 10 ms.
// The model's engagement is that velocity's central difference over ±1
// sample (the exponential's share scaled by sinh(0.1)/0.1) averaged over
// the 7 samples of ±3 ms (scaled by (1 + 2 cosh 0.1 + 2 cosh 0.2 + 2 cosh
// 0.3)/7 = 1.02012). The force is then the baseline's at that velocity.
TEST(DiscrepancyModel, BacklashWithACompliantStopTakesUpTheMotionOverTheContact) {
  const double v0 = 0.05, tau_s = 0.0005 / v0;
  const ModelInput in = triangle_input(4000, v0, 0.8);
  const DamperModel model(in);
  ModelWorkspace ws;
  std::vector<double> bl;
  const std::vector<double> p{0.002, 0.25};
  model.simulate(EffectSet{{Effect::backlash}}, p, ws, bl);
  const double a = kDt / tau_s;
  const double scale = std::sinh(a) / a * (1.0 + 2.0 * (std::cosh(a) + std::cosh(2 * a) + std::cosh(3 * a))) / 7.0;
  // The expected force: the baseline driven at the rod's velocity.
  ModelInput rod = in;
  for (const double rev : {0.8, 1.6, 2.4}) {
    const double v_act = in.vel_m_s[static_cast<std::size_t>(std::lround((rev + 0.01) / kDt))];  // ±v0
    for (std::size_t k = 0; k < rod.time_s.size(); ++k) {
      const double after = in.time_s[k] - (rev + 0.030);
      if (in.time_s[k] > rev && in.time_s[k] < rev + 0.8)
        rod.vel_m_s[k] = after < 0.0 ? 0.0 : v_act * (1.0 - scale * std::exp(-after / tau_s));
    }
  }
  std::vector<double> expect;
  DamperModel(rod).simulate(EffectSet{}, {}, ws, expect);
  for (const double rev : {0.8, 1.6, 2.4}) {
    for (double t = rev + 0.034; t < rev + 0.1; t += 0.002) {
      const auto k = static_cast<std::size_t>(std::lround(t / kDt));
      EXPECT_NEAR(bl[k], expect[k], 1e-3 * std::fabs(expect[k]) + 1e-6) << "t " << t;
    }
    // Still at rest a sample before the contact's reach (t_c − 3 ms − 1 ms).
    const auto k = static_cast<std::size_t>(std::lround((rev + 0.026) / kDt));
    EXPECT_NEAR(bl[k], 0.0, 1e-6);
  }
}

TEST(DiscrepancyModel, GasSpringAndOffsetAddTheirForces) {
  const ModelInput in = sine_input(2000, 0.03, 0.5, {0.0, 2.0}, 0.5);
  const DamperModel model(in);
  ModelWorkspace ws;
  std::vector<double> base, f;
  model.simulate(EffectSet{}, {}, ws, base);
  const std::vector<double> p{4.0e5, -1500.0};
  model.simulate(EffectSet{{Effect::gas_spring, Effect::force_offset}}, p, ws, f);
  for (std::size_t k = 0; k < f.size(); k += 13) ASSERT_NEAR(f[k], base[k] + 4.0e5 * in.disp_m[k] - 1500.0, 1e-6);
}

// Constant velocity v above v_TF and constant current, yield fading only:
// F = f_c (1 − β E) + c_0 v with β = α/C and dE/dt = F v, so
// E(t) = (f_c + c_0 v)/(f_c β) · (1 − exp(−v f_c β t))  (linear ODE, by hand).
TEST(DiscrepancyModel, ThermalFadeFollowsTheEnergyBalance) {
  ModelInput in;
  const double v = 0.1, i = 2.0;
  for (std::size_t k = 0; k < 20001; ++k) {
    in.time_s.push_back(static_cast<double>(k) * kDt);
    in.disp_m.push_back(v * in.time_s.back());
    in.vel_m_s.push_back(v);
    in.current_cmd_a.push_back(i);
  }
  const DamperModel model(in);
  const physics::BinghamParams bp{};
  const double fc = physics::coulomb_force_n(bp, i);
  const double c0 = physics::viscous_coeff_ns_m(bp, i);
  const double alpha = 0.02;
  const double beta = alpha / kThermalCapacity_j_per_k;
  ModelWorkspace ws;
  std::vector<double> f;
  const std::vector<double> p{alpha, 0.0};
  model.simulate(EffectSet{{Effect::thermal_fade}}, p, ws, f);
  for (const double t : {0.0, 5.0, 10.0, 20.0}) {
    const double e = (fc + c0 * v) / (fc * beta) * (1.0 - std::exp(-v * fc * beta * t));
    const double expect = fc * (1.0 - beta * e) + c0 * v;
    EXPECT_NEAR(f[static_cast<std::size_t>(std::lround(t / kDt))], expect, 2e-4 * expect) << t;
  }
  // β E(20 s) = 1.26 (1 − e^{−0.086}) = 0.104 by hand: the yield force has lost over 8 %.
  EXPECT_LT(f.back(), fc * 0.92 + c0 * v);
}

TEST(DiscrepancyModel, NormalizedRmsGap) {
  // sqrt((1² + 1²) / (3² + 4²)) = sqrt(2)/5.
  const std::vector<double> m{3.0, 4.0}, s{2.0, 5.0};
  EXPECT_NEAR(normalized_rms_gap(m, s), std::sqrt(2.0) / 5.0, 1e-15);
}

TEST(DiscrepancyModel, MovingSpanLeavesOutTheStandstillEachSide) {
  // 500 samples at rest, then x = A(1 − cos ωt') for two periods (v = Aω sin ωt'
  // from 0), then 300 samples at rest. Peak |v| = Aω; the actuator counts as
  // moving where |sin ωt'| > 0.02, i.e. from t' = asin(0.02)/ω and up to
  // t' = 2T − asin(0.02)/ω. With T = 1 s, 1 kHz: asin(0.02)/(2π) = 3.18 ms, so
  // the first moving sample is t' = 4 ms (index 504) and the last is
  // t' = 1996 ms (index 2496); the end is one past it.
  const double a = 0.01, w = 2.0 * units::kPi;
  std::vector<double> v(500, 0.0);
  for (int k = 0; k <= 2000; ++k) v.push_back(a * w * std::sin(w * k * kDt));
  v.resize(v.size() + 300, 0.0);
  const SampleRange r = moving_span(v);
  EXPECT_EQ(r.begin, 504u);
  EXPECT_EQ(r.end, 2497u);
  // Nothing moves: the whole record.
  const std::vector<double> still(50, 0.0);
  const SampleRange all = moving_span(still);
  EXPECT_EQ(all.begin, 0u);
  EXPECT_EQ(all.end, 50u);
}

}  // namespace
}  // namespace mrd::discrepancy
