// The independent generator against hand calculations from the thesis's
// equations (numbers worked in the comments), and its ENR and determinism.
#include <gtest/gtest.h>

#include <cmath>

#include "damper_physics.hpp"
#include "independent_synth.hpp"
#include "plant.hpp"

namespace indep {
namespace {

// Eq. 4.2–4.3 with Table 4.1 at 2.5 A:
//   f_c = 170 + (4.1 − 170) e^(−0.7·2.5)    = 170 − 165.9 · 0.173774 = 141.171 kN
//   c_0 = 0.365 + (0.0825 − 0.365) e^(−2.875) = 0.365 − 0.2825 · 0.056416 = 0.349062 kN·s/mm
constexpr double kYieldAt25_n = 141.1709e3;
constexpr double kViscousAt25_n_s_m = 0.3490624e6;

/// Constant velocity v from x = 0 at constant current i, `effects` added.
Scenario ramp(double v_m_s, double i_a, EffectParams effects = {}, double duration_s = 2.0) {
  Scenario s;
  s.motion.ramp_m_s = v_m_s;
  s.current.levels_a = {i_a};
  s.effects = effects;
  s.duration_s = duration_s;
  return s;
}

/// Fine-grid index of time t.
std::size_t at(const FineRun& r, double t_s) { return static_cast<std::size_t>(std::llround(t_s / r.step_s)); }

TEST(IndependentDamper, BinghamForceAboveTheTransitionVelocityIsTable41) {
  // 0.1 m/s > 10 mm/s: TF = 1, F = 141.171 kN + 349.062 kN·s/m · 0.1 m/s = 176.077 kN.
  const FineRun r = simulate(ramp(0.1, 2.5));
  EXPECT_NEAR(r.force_channel_n[at(r, 1.0)], kYieldAt25_n + kViscousAt25_n_s_m * 0.1, 1.0);
  EXPECT_NEAR(r.force_channel_n[at(r, 1.0)], 176.077e3, 5.0);
  // Negative velocity: the same force with the opposite sign.
  const FineRun n = simulate(ramp(-0.1, 2.5));
  EXPECT_NEAR(n.force_channel_n[at(n, 1.0)], -176.077e3, 5.0);
}

TEST(IndependentDamper, TransitionFunctionScalesBelowTenMillimetresPerSecond) {
  // Eq. 4.4 at 5 mm/s: TF = 0.5, F = 0.5 (141.171 + 0.349062 · 5) kN = 71.458 kN.
  const FineRun r = simulate(ramp(0.005, 2.5));
  EXPECT_NEAR(r.force_channel_n[at(r, 1.0)], 71.458e3, 5.0);
  // At 0 A: f_c = 4.1 kN, c_0 = 82.5 kN·s/m; 0.1 m/s → 4.1 + 8.25 = 12.35 kN.
  const FineRun z = simulate(ramp(0.1, 0.0));
  EXPECT_NEAR(z.force_channel_n[at(z, 1.0)], 12.35e3, 1.0);
}

TEST(IndependentDamper, CoilCurrentFollowsEq45) {
  // Step 0 → 2 A at t0 = 0.50005 s (between grid points). With unity DC gain,
  //   i(t0 + t) = 2 (1 − ½ e^(−t/0.7) − ½ e^(−t/0.03)):
  //   t = 0.03 s: 2 (1 − ½ · 0.958048 − ½ · 0.367879) = 0.674073 A
  //   t = 0.7 s:  2 (1 − ½ · 0.367879 − ½ · 7.6e−11) = 1.632121 A (63.2 % of the slow half + all the fast)
  Scenario s = ramp(0.1, 0.0);
  s.current.start_s = {0.0, 0.50005};
  s.current.levels_a = {0.0, 2.0};
  const FineRun r = simulate(s);
  const double t0 = 0.50005;
  auto current_at = [&](double t) {
    // Linear interpolation between the grid points around t.
    const double pos = t / r.step_s;
    const auto j = static_cast<std::size_t>(pos);
    const double w = pos - static_cast<double>(j);
    return (1.0 - w) * r.coil_current_a[j] + w * r.coil_current_a[j + 1];
  };
  EXPECT_NEAR(r.coil_current_a[at(r, 0.5)], 0.0, 1e-12);
  EXPECT_NEAR(current_at(t0 + 0.03), 0.674073, 2e-3);
  EXPECT_NEAR(current_at(t0 + 0.7), 1.632121, 1e-4);
  // Scaled by 2 (coil_lag): at t = 1.4 s the slow half is again at 63.2 %.
  EffectParams slow;
  slow.coil_tau_scale = 2.0;
  Scenario s2 = s;
  s2.effects = slow;
  const FineRun r2 = simulate(s2);
  EXPECT_NEAR(r2.coil_current_a[at(r2, 0.5 + 1.4)], 1.632121, 2e-4);
}

TEST(IndependentDamper, ParticipantRatioFollowsChapter5) {
  // SQ = 1 (Eq. 5.6–5.8, Table 5.6):
  //   a_PR = 0.1 + 0.9 e^(−7)      = 0.100821
  //   b_PR = 0.605 + 0.395 e^(−4.5) = 0.609388
  //   c_PR = 5.474 e^(−3.65)       = 0.142275 per litre
  const PrLaw law = pr_law(1.0);
  EXPECT_NEAR(law.a_pr, 0.100821, 1e-6);
  EXPECT_NEAR(law.b_pr, 0.609388, 1e-6);
  EXPECT_NEAR(law.c_pr_per_l, 0.142275, 1e-6);
  // 0.1 m/s for 5 s through 0.01062 m²: 5.31 L; Eq. 5.9: PR = 0.609388 − 0.508567 e^(−0.755483) = 0.370471.
  EffectParams e;
  e.settling_quotient = 1.0;
  const FineRun r = simulate(ramp(0.1, 2.5, e, 6.0));
  EXPECT_NEAR(r.participant_ratio[0], 0.100821, 1e-6);
  EXPECT_NEAR(r.participant_ratio[at(r, 5.0)], 0.370471, 1e-5);
  // Eq. 5.10–5.12: f_c,b and c_0,b multiplied by PR.
  const double pr = r.participant_ratio[at(r, 5.0)];
  const double fc = pr * 170e3 + (4.1e3 - pr * 170e3) * std::exp(-0.7 * 2.5);
  const double c0 = pr * 0.365e6 + (0.0825e6 - pr * 0.365e6) * std::exp(-1.15 * 2.5);
  EXPECT_NEAR(r.force_channel_n[at(r, 5.0)], fc + c0 * 0.1, 1.0);
}

TEST(IndependentDamper, HardPlayHoldsTheRodAfterAReversalUntilTheActuatorCrossesIt) {
  // x_a = 50 mm sin(π t), 2 mm of play (x_d within x_a ± 1 mm), the rod starting in contact.
  // Pushed up, x_d = x_a − 1 mm: 49 mm at the reversal (0.5 s). Going down, the actuator meets
  // the rod again at x_a = 48 mm: sin(π t) = 0.96, t = (π − asin 0.96)/π = (3.14159 − 1.28700)/π
  // = 0.59033 s. No force in between; at 0.6 s v = 50π cos(0.6π) mm/s = −48.54 mm/s,
  // F = −(141.171 + 0.349062 · 48.54) kN = −158.115 kN, and x_d = x_a + 1 mm.
  Scenario s;
  s.motion.sines = {{0.05, 0.5, 0.0}};
  s.current.levels_a = {2.5};
  s.effects.free_play_m = 0.002;
  s.duration_s = 1.0;
  const FineRun r = simulate(s);
  EXPECT_NEAR(r.force_channel_n[at(r, 0.3)], 141.171e3 + 0.349062e6 * 0.05 * 3.14159265 * std::cos(0.3 * 3.14159265),
              10.0);
  EXPECT_EQ(r.force_channel_n[at(r, 0.52)], 0.0);
  EXPECT_EQ(r.force_channel_n[at(r, 0.585)], 0.0);
  EXPECT_NEAR(r.force_channel_n[at(r, 0.6)], -158.115e3, 20.0);
  EXPECT_NEAR(r.rod_disp_m[at(r, 0.6)] - 0.05 * std::sin(0.6 * 3.14159265), 0.001, 1e-9);
  // Smooth play (contact length 5 % of the play): the same rod position to within a few contact lengths.
  s.effects.contact_fraction = 0.05;
  const FineRun m = simulate(s);
  EXPECT_NEAR(m.rod_disp_m[at(m, 0.6)] - 0.05 * std::sin(0.6 * 3.14159265), 0.001, 0.5e-3);
  EXPECT_LT(std::abs(m.force_channel_n[at(m, 0.55)]), 1e3);
}

TEST(IndependentDamper, GasSpringDelayAndFilter) {
  // k x (1 + ε x²) with k = 1 MN/m, ε = 50 /m², x = 0.1 m at 1 s: 100 kN · 1.5 = 150 kN on top of 176.077 kN.
  EffectParams e;
  e.gas_stiffness_n_m = 1e6;
  e.gas_nonlinearity_per_m2 = 50.0;
  const FineRun r = simulate(ramp(0.1, 2.5, e));
  EXPECT_NEAR(r.force_channel_n[at(r, 1.0)], 176.077e3 + 150e3, 5.0);
  // Delay 12.34 ms: F(1 s − τ) = 176.077 kN + k x (1 + ε x²), x = 0.098766 m → 98.766 kN · 1.487737.
  const std::vector<double> f = sample_force(r, {1.0}, 0.01234);
  EXPECT_NEAR(f[0], 176.077e3 + 98.766e3 * (1.0 + 50.0 * 0.098766 * 0.098766), 5.0);
  // A 20 ms first-order filter on a force that starts at 176.077 kN: 63.2 % after 20 ms.
  EffectParams lp;
  lp.force_filter_s = 0.02;
  const FineRun l = simulate(ramp(0.1, 2.5, lp));
  EXPECT_NEAR(l.force_channel_n[at(l, 0.02)] / 176.077e3, 1.0 - std::exp(-1.0), 1e-3);
}

TEST(IndependentDamper, LinearThermalFadeMatchesItsClosedForm) {
  // Equal coefficients α: F = F_0 (1 − α ΔT), C dΔT/dt = F v  ⇒  ΔT = (1 − e^(−α F_0 v t / C)) / α.
  // α = 0.001 /K, F_0 = 176.077 kN, v = 0.1 m/s, C = 60 kJ/K, t = 10 s: exponent 0.00293462,
  // ΔT = 2.93032 K, F = F_0 e^(−0.00293462) = 175.561 kN.
  EffectParams e;
  e.fade_yield_per_k = 0.001;
  e.fade_viscous_per_k = 0.001;
  const FineRun r = simulate(ramp(0.1, 2.5, e, 11.0));
  EXPECT_NEAR(r.temperature_rise_k[at(r, 10.0)], 2.93032, 2e-4);
  EXPECT_NEAR(r.force_channel_n[at(r, 10.0)], 175.561e3, 10.0);
}

TEST(IndependentDamper, DirectionAsymmetryScalesExtensionUpAndCompressionDown) {
  // a = 0.2: extension 1.2 · 176.077 kN, compression −0.8 · 176.077 kN.
  EffectParams g;
  g.asymmetry = 0.2;
  EXPECT_NEAR(simulate(ramp(0.1, 2.5, g)).force_channel_n[10000], 1.2 * 176.077e3, 6.0);
  EXPECT_NEAR(simulate(ramp(-0.1, 2.5, g)).force_channel_n[10000], -0.8 * 176.077e3, 5.0);
}

TEST(IndependentDamper, OutOfCatalogueForms) {
  // tanh transition, v0 = 5 mm/s at 10 mm/s: tanh(2) (141.171 + 3.49062) kN = 0.964028 · 144.662 kN.
  EffectParams t;
  t.tanh_velocity_m_s = 0.005;
  const FineRun a = simulate(ramp(0.01, 2.5, t));
  EXPECT_NEAR(a.force_channel_n[at(a, 1.0)], 0.964028 * 144.6615e3, 10.0);
  // Fluid inertia 500 kg on a 10 mm, 2 Hz sine: at the crest the rod stands still (Eq. 4.4 gives
  // no damper force) and a = −(4π)² · 0.01 m = −1.57914 m/s², so F = −789.568 N.
  EffectParams m;
  m.fluid_mass_kg = 500.0;
  Scenario crest = ramp(0.0, 0.0, m, 0.2);
  crest.motion = Motion{};
  crest.motion.sines.push_back({0.01, 2.0, 0.0});
  const FineRun ci = simulate(crest);
  EXPECT_NEAR(ci.force_channel_n[at(ci, 0.125)], -789.568, 0.01);  // a quarter period
  // Series spring 100 MN/m (+ 0.1 MN·s/m): at steady velocity the rod moves with the actuator,
  // the spring carrying 176.077 kN → 1.76077 mm behind it.
  EffectParams c;
  c.series_stiffness_n_m = 1e8;
  c.series_damping_n_s_m = 1e5;
  const FineRun s = simulate(ramp(0.1, 2.5, c));
  EXPECT_NEAR(s.rod_vel_m_s[at(s, 1.0)], 0.1, 1e-6);
  EXPECT_NEAR(0.1 * 1.0 - s.rod_disp_m[at(s, 1.0)], 1.76077e-3, 1e-6);
}

TEST(IndependentDamper, ForceOnlyRunIntegratesLikeAFullOne) {
  // Keeping only the force channel must not change the integration: the same
  // force bit for bit, with smooth play, a filter, a thermal fade with cooling
  // and settling all carrying state from step to step, and no states kept.
  EffectParams e;
  e.free_play_m = 0.004;
  e.contact_fraction = 0.1;
  e.force_filter_s = 0.005;
  e.fade_yield_per_k = 0.002;
  e.cooling_time_s = 30.0;
  e.settling_quotient = 0.5;
  Scenario s = ramp(0.0, 1.5, e, 1.5);
  s.motion = Motion{};
  s.motion.sines.push_back({0.02, 1.5, 0.3});
  const FineRun all = simulate(s);
  const FineRun force = simulate(s, Channels::force_only);
  ASSERT_EQ(force.force_channel_n.size(), all.force_channel_n.size());
  for (std::size_t j = 0; j < all.force_channel_n.size(); ++j) {
    ASSERT_EQ(force.force_channel_n[j], all.force_channel_n[j]) << "at j = " << j;
  }
  EXPECT_TRUE(force.rod_disp_m.empty() && force.coil_current_a.empty() && force.temperature_rise_k.empty());
  EXPECT_GT(all.temperature_rise_k.back(), 0.0);
  EXPECT_LT(all.participant_ratio.front(), 1.0);
}

TEST(IndependentSynth, EffectToNoiseRatio) {
  // RMS of {1, −1, 1, −1} is 1; over a noise RMS of 0.5 that is 2.
  EXPECT_DOUBLE_EQ(effect_to_noise_ratio({1, -1, 1, -1}, {0, 0, 0, 0}, 0.5), 2.0);
  // An offset changes every sample by F_0, so ENR = |F_0| / RMS(noise): an independent check of the sizing.
  Spec spec;
  spec.effects = {Effect::force_offset};
  spec.target_enr = 4.0;
  spec.seed = 7;
  const Case c = generate(spec);
  ASSERT_EQ(c.enr.size(), 1u);
  EXPECT_NEAR(c.enr[0], 4.0, 0.01);
  EXPECT_NEAR(std::abs(c.params.force_offset_n) / c.force_noise_rms_n, c.enr[0], 1e-9);
  // The measured force minus the noise-free truth is the noise: its RMS is the one quoted (within
  // the 10 N quantization).
  double ss = 0.0;
  for (std::size_t k = 0; k < c.force_n.size(); ++k) ss += std::pow(c.force_n[k] - c.clean_force_n[k], 2);
  EXPECT_NEAR(std::sqrt(ss / static_cast<double>(c.force_n.size())), c.force_noise_rms_n, 5.0);
}

TEST(IndependentSynth, EffectsAreSizedOverTheWholeRangeWithoutRedraws) {
  // Drawn ENRs are log-uniform in [0.25, 64]: of 24 draws, some below 1 and some above 16 (each
  // quarter of the log range; the chance that none of 24 falls in one is 0.75^24 = 0.1 %).
  int below_1 = 0, above_16 = 0;
  for (std::uint64_t seed = 1; seed <= 24; ++seed) {
    Spec spec;
    spec.effects = {Effect::force_offset};
    spec.seed = seed;
    spec.duration_s = 4.0;
    const Case c = generate(spec);
    // On target, or short of it with the offset at the top of its range (15 kN).
    if (std::abs(c.params.force_offset_n) < 15.0e3 * (1.0 - 1e-9)) {
      EXPECT_NEAR(c.enr[0], c.target_enr[0], 0.01 * c.target_enr[0]);
    } else {
      EXPECT_LT(c.enr[0], c.target_enr[0]);
    }
    below_1 += c.enr[0] < 1.0;
    above_16 += c.enr[0] > 16.0;
  }
  EXPECT_GT(below_1, 0);
  EXPECT_GT(above_16, 0);
}

TEST(IndependentSynth, DeterministicPerSeed) {
  Spec spec;
  spec.effects = {Effect::thermal_fade};
  spec.seed = 11;
  spec.duration_s = 4.0;
  const Case a = generate(spec);
  const Case b = generate(spec);
  EXPECT_EQ(a.force_n, b.force_n);
  EXPECT_EQ(a.displacement_m, b.displacement_m);
  EXPECT_EQ(a.description, b.description);
  spec.seed = 12;
  EXPECT_NE(generate(spec).force_n, a.force_n);
  EXPECT_EQ(a.force_n.size(), 4000u);
}

TEST(IndependentSynth, RecordsStayWithinTheDampersRange) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    Spec spec;
    spec.seed = seed;
    const Case c = generate(spec);
    // Velocity over 10 ms: LVDT noise of 20 µm adds √2 · 20 µm / 10 ms = 2.8 mm/s RMS (5σ: 14 mm/s).
    double vmax = 0.0;
    for (std::size_t k = 10; k < c.displacement_m.size(); ++k) {
      vmax = std::max(vmax, std::abs(c.displacement_m[k] - c.displacement_m[k - 10]) / 0.010);
    }
    // Table 3.1: 0.2491 m/s; a quantized displacement adds up to one quantum over the 10 ms.
    EXPECT_LT(vmax, kMaxVelocity_m_s + 0.014 + c.sensors.disp_quantum_m / 0.010) << c.description;
    for (const double i : c.current_cmd_a) {
      EXPECT_GE(i, 0.0);
      EXPECT_LE(i, 2.5);
    }
  }
}

// ---- The second forms of the effects, the noise and the motions ---------------

TEST(IndependentDamper, SingleLagCoilHasEq45sMeanDelay) {
  // One lag of τ = ½·0.7 + ½·0.03 = 0.365 s: a step 0 → 2 A at 0.5 s reaches
  // 2 (1 − e^(−1)) = 1.264241 A at 0.865 s; scaled by 2, the same at 0.5 + 0.73 s.
  Scenario s = ramp(0.1, 0.0);
  s.current.start_s = {0.0, 0.5};
  s.current.levels_a = {0.0, 2.0};
  s.effects.coil_single_lag = true;
  const FineRun r = simulate(s);
  EXPECT_NEAR(r.coil_current_a[at(r, 0.865)], 1.264241, 1e-4);
  s.effects.coil_tau_scale = 2.0;
  const FineRun r2 = simulate(s);
  EXPECT_NEAR(r2.coil_current_a[at(r2, 1.23)], 1.264241, 1e-4);
}

TEST(IndependentDamper, FullyRecoveringSettledLayer) {
  // SQ = 1: a_PR = 0.100821 (Eq. 5.6). 0.1 m/s through 0.01062 m² displaces 1.062 L in 1 s; with
  // V_r = 2 L, PR = 1 − 0.899179 e^(−0.531) = 1 − 0.899179 · 0.588017 = 0.471268, and after
  // 20 s (21.24 L) 1 − 0.899179 e^(−10.62) = 0.999978: no lasting deficit (Eq. 5.9 keeps 1 − b_PR).
  EffectParams e;
  e.settling_quotient = 1.0;
  e.settling_recovery_l = 2.0;
  const FineRun r = simulate(ramp(0.1, 2.5, e, 20.0));
  EXPECT_NEAR(r.participant_ratio[0], 0.100821, 1e-6);
  EXPECT_NEAR(r.participant_ratio[at(r, 1.0)], 0.471268, 1e-5);
  EXPECT_NEAR(r.participant_ratio[at(r, 20.0)], 0.999978, 1e-5);
}

TEST(IndependentDamper, GasSpringPreloadIsAConstantForceOfTheSpring) {
  // 2.5 A at 0.1 m/s from x = 0: 176.077 kN; k = 100 kN/m at x = 0.1 m adds 10 kN, the 10 kN preload 10 kN more.
  EffectParams e;
  e.gas_stiffness_n_m = 1.0e5;
  e.gas_preload_n = 10.0e3;
  const FineRun r = simulate(ramp(0.1, 2.5, e));
  EXPECT_NEAR(r.force_channel_n[at(r, 1.0)], 196.077e3, 5.0);
}

TEST(IndependentDamper, ImpactSpringCompressesByTheForceOverItsStiffness) {
  // 2 mm of play and a contact spring of 100 MN/m: pushed at 0.1 m/s and 2.5 A, the rod moves with
  // the actuator once the spring carries F = 176.077 kN, 1.76077 mm of compression (the lag of the
  // rod, c_0 / k = 349 kN·s/m / 100 MN/m = 3.5 ms, long over by 1 s). So x_d = 0.1 − 0.001 − 0.00176077.
  EffectParams e;
  e.free_play_m = 0.002;
  e.contact_stiffness_n_m = 1.0e8;
  const FineRun r = simulate(ramp(0.1, 2.5, e));
  EXPECT_NEAR(r.force_channel_n[at(r, 1.0)], 176.077e3, 20.0);
  EXPECT_NEAR(r.rod_disp_m[at(r, 1.0)], 0.1 - 0.001 - 0.00176077, 1e-6);
  EXPECT_NEAR(r.rod_vel_m_s[at(r, 1.0)], 0.1, 1e-5);
}

TEST(IndependentDamper, DelayBehindAnAntiAliasFilterLagsARampByBoth) {
  // F = 176.077 kN + k v t with k = 1 MN/m, v = 0.1 m/s: a ramp of 100 kN/s. A first-order filter
  // (1 ms) lags a ramp by its time constant once settled, the delay (5 ms) by itself: at 1 s the
  // channel reads 176.077 kN + 100 kN/s · (1 − 0.006 s) = 275.477 kN.
  Scenario s = ramp(0.1, 2.5);
  s.effects.gas_stiffness_n_m = 1.0e6;
  s.effects.delay_filter_s = 1e-3;
  s.effects.force_delay_s = 5e-3;
  const FineRun r = simulate(s);
  const std::vector<double> f = sample_force(r, {1.0}, s.effects.force_delay_s);
  // The held input of each fine step (0.1 ms) adds half a step of lag: 5 N.
  EXPECT_NEAR(f[0], 275.477e3, 20.0);
}

TEST(IndependentDamper, ChirpFollowsItsPhase) {
  // x = A sin(2π (f₀ t + ½ r t²)) with f₀ = 0.5 Hz, r = 0.25 Hz/s, A = 20 mm: at t = 1 s the phase
  // is 2π · 0.625 (sin = −0.707107) and the frequency 0.75 Hz, v = A 2π 0.75 cos(2π · 0.625)
  // = −3.332162 A.
  Scenario s;
  s.motion.chirp = {0.020, 0.5, 0.25};
  s.duration_s = 2.0;
  const FineRun r = simulate(s);
  EXPECT_NEAR(r.rod_disp_m[at(r, 1.0)], -0.707107 * 0.020, 1e-8);
  EXPECT_NEAR(r.rod_vel_m_s[at(r, 1.0)], -3.332162 * 0.020, 1e-7);
}

TEST(IndependentSynth, NoiseFormsKeepTheirRms) {
  // Whatever the colour, the force noise is the drawn components' RMS summed in quadrature
  // (independent processes), within the sampling spread of a 20 s record (the 2 s section of the
  // 1/f noise has only 10 correlation times in it: its share of the RMS spreads by tens of percent).
  int pink = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    Spec spec;
    spec.seed = seed;
    const Case c = generate(spec);
    const SensorModel& m = c.sensors;
    const double expected = std::sqrt(m.force_white_n * m.force_white_n + m.force_coloured_n * m.force_coloured_n +
                                      m.force_pink_n * m.force_pink_n + m.force_drift_n * m.force_drift_n / 12.0);
    EXPECT_NEAR(c.force_noise_rms_n, expected, 0.25 * expected) << c.noise_form;
    pink += c.noise_form == "pink";
  }
  EXPECT_GT(pink, 0);
}

TEST(IndependentSynth, RefusesAnEffectTwice) {
  Spec spec;
  spec.effects = {Effect::gas_spring, Effect::gas_spring};
  EXPECT_THROW((void)generate(spec), std::invalid_argument);
}

}  // namespace
}  // namespace indep
