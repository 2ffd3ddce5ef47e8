// The Bingham law's shape terms (baseline.hpp): the current laws' exponent,
// the viscous exponent (Herschel–Bulkley) and the spring beside the law,
// against values worked by hand; their damper.toml keys; and a calibration
// that recovers them from records the model made and keeps them on check
// records.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "host_sim/discrepancy/baseline_file.hpp"
#include "host_sim/discrepancy/calibrate.hpp"
#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::discrepancy {
namespace {

constexpr double kShapePi = 3.14159265358979323846;

TEST(BaselineShape, CurrentExponentBendsTheLawAndKeepsItsValueAtOneAmpere) {
  // Y(I) = 1100 + (100 − 1100) exp(−|I|^2): at 0.5 A 1100 − 1000 e^−0.25 =
  // 1100 − 778.8008 = 321.1992 N (the exponent 1 law: 1100 − 1000 e^−0.5 =
  // 493.4693 N); at 1 A 1100 − 1000 e^−1 = 732.1206 N whatever the exponent.
  CurrentLaw q2{100.0, 1100.0, 1.0, 2.0};
  CurrentLaw q1{100.0, 1100.0, 1.0};
  EXPECT_NEAR(q2.at(0.5), 321.1992, 1e-4);
  EXPECT_NEAR(q1.at(0.5), 493.4693, 1e-4);
  EXPECT_NEAR(q2.at(1.0), 732.1206, 1e-4);
  EXPECT_NEAR(q2.at(-0.5), q2.at(0.5), 1e-12);
  EXPECT_DOUBLE_EQ(q2.at(0.0), 100.0);
}

/// A record moving at a constant `v_m_s` from `x0_m` at 1 kHz for 1 s, current `i_a`.
MeasuredData shape_ramp(double x0_m, double v_m_s, double i_a) {
  MeasuredData d;
  d.source = "ramp";
  for (int k = 0; k <= 1000; ++k) {
    const double t = 1e-3 * k;
    d.time_s.push_back(t);
    d.displacement_m.push_back(x0_m + v_m_s * t);
    d.current_cmd_a.push_back(i_a);
    d.force_n.push_back(0.0);
  }
  return d;
}

TEST(BaselineShape, ViscousExponentAndSpringAgainstHandValues) {
  // Constant laws Y = 500 N, C = 4000 N·s/m, tanh transition over 1 mm/s,
  // viscous exponent 0.5 about v_r = 80 mm/s, spring 2000 N/m, no lag.
  // At v = 20 mm/s and x = 10 mm: 500 tanh(20) + 4000 · 0.08 · (0.02/0.08)^0.5
  // + 2000 · 0.01 = 500 + 320 · 0.5 + 20 = 680 N (tanh 20 = 1 to 1e-17).
  // Linear viscous force instead: 500 + 4000 · 0.02 + 20 = 600 N.
  Baseline b = thesis_baseline();
  b.yield_n = {500.0, 500.0, 1.0};
  b.viscous_ns_m = {4000.0, 4000.0, 1.0};
  b.tanh_transition = true;
  b.v_tf_m_s = 0.001;
  b.viscous_exponent = 0.5;
  b.viscous_ref_m_s = 0.08;
  b.stiffness_n_m = 2000.0;
  ASSERT_TRUE(b.has_viscous_exponent());
  ASSERT_TRUE(b.has_bingham_stiffness());
  EXPECT_EQ(baseline_form_name(b), "bingham_tanh+stiffness+viscous_exponent");
  // x = −0.01 + 0.02 t reaches 10 mm at t = 1 s: sample 1000 is the last; the
  // middle sample t = 0.5 s is at x = 0 (force 660 N).
  const MeasuredData d = shape_ramp(-0.01, 0.02, 1.0);
  ModelWorkspace ws;
  std::vector<double> f;
  DamperModel(model_input(d), b).simulate(EffectSet{}, {}, ws, f);
  EXPECT_NEAR(f[500], 660.0, 0.5);
  EXPECT_NEAR(f[750], 670.0, 0.5);  // x = 5 mm
  b.viscous_exponent = 1.0;
  EXPECT_FALSE(b.has_viscous_exponent());
  DamperModel(model_input(d), b).simulate(EffectSet{}, {}, ws, f);
  EXPECT_NEAR(f[750], 590.0, 0.5);  // 500 + 80 + 10
  // The Bouc–Wen law's stiffness is its own k_0, not the Bingham spring.
  b.law = BaseLaw::bouc_wen;
  EXPECT_FALSE(b.has_bingham_stiffness());
}

std::string shape_error_of(const std::string& text) {
  try {
    (void)parse_baseline_toml(text, "damper.toml");
  } catch (const io::UsageError& e) {
    return e.what();
  }
  return "";
}

BaselineFile shape_file() {
  BaselineFile f;
  f.baseline = thesis_baseline();
  f.baseline.name = "shaped";
  f.baseline.tanh_transition = true;
  f.baseline.v_tf_m_s = 0.004;
  f.baseline.yield_n = {80.0, 1500.0, 0.3, 1.8};
  f.baseline.viscous_ns_m = {1200.0, 9000.0, 0.5, 1.4};
  f.baseline.viscous_exponent = 0.7;
  f.baseline.viscous_ref_m_s = 0.05;
  f.baseline.stiffness_n_m = 900.0;
  f.baseline.series_compliance_m_per_n = 3.4e-7;
  f.baseline.range = {0.0, 1.0, 0.09, 1700.0, 0.0016, 0.025, 0.25, 5.0};
  f.sigma.yield_n = {1.0, 20.0, 0.01, 0.05};
  f.sigma.viscous_ns_m = {10.0, 100.0, 0.02, 0.04};
  f.sigma.viscous_exponent = 0.02;
  f.sigma.stiffness_n_m = 60.0;
  f.sigma.series_compliance_m_per_n = 2e-8;
  f.source_records = {"a.csv"};
  return f;
}

TEST(BaselineShape, DamperTomlRoundTripsTheShapeAndRefusesHalfOfIt) {
  const BaselineFile f = shape_file();
  const std::string text = baseline_toml(f);
  const BaselineFile g = parse_baseline_toml(text, "damper.toml");
  const Baseline& a = f.baseline;
  const Baseline& b = g.baseline;
  EXPECT_EQ(b.yield_n.current_exponent, a.yield_n.current_exponent);
  EXPECT_EQ(b.viscous_ns_m.current_exponent, a.viscous_ns_m.current_exponent);
  EXPECT_EQ(g.sigma.yield_n.current_exponent, f.sigma.yield_n.current_exponent);
  EXPECT_EQ(b.viscous_exponent, a.viscous_exponent);
  EXPECT_EQ(b.viscous_ref_m_s, a.viscous_ref_m_s);
  EXPECT_EQ(g.sigma.viscous_exponent, f.sigma.viscous_exponent);
  EXPECT_EQ(b.stiffness_n_m, a.stiffness_n_m);
  EXPECT_EQ(g.sigma.stiffness_n_m, f.sigma.stiffness_n_m);
  EXPECT_EQ(b.series_compliance_m_per_n, a.series_compliance_m_per_n);
  EXPECT_EQ(g.sigma.series_compliance_m_per_n, f.sigma.series_compliance_m_per_n);
  EXPECT_EQ(baseline_form_name(b), "bingham_tanh+current_exponent+stiffness+viscous_exponent+series_compliance");
  // A negative compliance: refused, naming the field and what was expected.
  std::string negative = text;
  negative.insert(negative.find("series_compliance_m_per_n = ") + 28, "-");
  EXPECT_NE(shape_error_of(negative).find("bingham.series_compliance_m_per_n"), std::string::npos)
      << shape_error_of(negative);
  EXPECT_NE(shape_error_of(negative).find("expected a compliance in [0, 0.001]"), std::string::npos)
      << shape_error_of(negative);
  // A plain law writes none of the keys.
  const std::string plain = baseline_toml(BaselineFile{});
  for (const char* key : {"current_exponent", "viscous_exponent", "viscous_ref_m_s", "stiffness_n_m", "series_compliance"})
    EXPECT_EQ(plain.find(key), std::string::npos) << key;
  // The exponent without its reference velocity: refused, naming the file,
  // the line of the key and the field.
  const std::size_t at = text.find("viscous_ref_m_s = ");
  ASSERT_NE(at, std::string::npos);
  const std::string half = text.substr(0, at) + text.substr(text.find('\n', at) + 1);
  int line = 1;
  for (std::size_t k = 0; k < half.find("viscous_exponent = "); ++k) line += half[k] == '\n' ? 1 : 0;
  const std::string e = shape_error_of(half);
  EXPECT_EQ(e.rfind("damper.toml:" + std::to_string(line) + ": ", 0), 0u) << e;
  EXPECT_NE(e.find("bingham.viscous_exponent"), std::string::npos) << e;
  EXPECT_NE(e.find("viscous_ref_m_s"), std::string::npos) << e;
  // Out of range: an exponent of 20.
  std::string big = text;
  big.replace(big.find("viscous_exponent = ") + 19, 3, "20 ");
  EXPECT_NE(shape_error_of(big).find("expected an exponent in [0.01, 10]"), std::string::npos) << shape_error_of(big);
}

/// A 1 kHz sine record through `truth` with 2 % white noise.
MeasuredData shape_sine(const Baseline& truth, double amplitude_m, double freq_hz, double current_a, unsigned seed) {
  MeasuredData d;
  d.source = "synthetic";
  for (int k = 0; k <= 2500; ++k) {
    const double t = 1e-3 * k;
    d.time_s.push_back(t);
    d.displacement_m.push_back(amplitude_m * std::sin(2.0 * kShapePi * freq_hz * t));
    d.current_cmd_a.push_back(current_a);
    d.force_n.push_back(0.0);
  }
  ModelWorkspace ws;
  std::vector<double> f;
  DamperModel(model_input(d), truth).simulate(EffectSet{}, {}, ws, f);
  double ss = 0.0;
  for (const double x : f) ss += x * x;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.02 * std::sqrt(ss / static_cast<double>(f.size())));
  for (std::size_t k = 0; k < f.size(); ++k) d.force_n[k] = f[k] + noise(rng);
  return d;
}

TEST(BaselineShape, CalibrationRecoversTheShapeAndKeepsItOnCheckRecords) {
  // A small damper whose yield force rises as |I|^2 at low current (q = 2)
  // and whose viscous force thins as |v|^0.6: fitted at 0, 0.25, 0.5, 0.75
  // and 1 A on 4 mm / 1.5 Hz and 2 mm / 4 Hz (peaks 38 and 50 mm/s), checked
  // on 3 mm / 5 Hz (94 mm/s), where a linear C v extrapolates too high.
  Baseline truth = thesis_baseline();
  truth.tanh_transition = true;
  truth.v_tf_m_s = 0.004;
  truth.force_delay_s = 0.003;
  truth.yield_n = {80.0, 1500.0, 0.8, 2.0};
  truth.viscous_ns_m = {1500.0, 6000.0, 1.0};
  truth.viscous_exponent = 0.6;
  truth.viscous_ref_m_s = 0.05;
  std::vector<MeasuredData> recs, check;
  unsigned seed = 11;
  for (const double i : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    recs.push_back(shape_sine(truth, 0.004, 1.5, i, seed++));
    recs.push_back(shape_sine(truth, 0.002, 4.0, i, seed++));
  }
  for (const double i : {0.25, 1.0}) check.push_back(shape_sine(truth, 0.003, 5.0, i, seed++));
  CalibrateOptions opt;
  opt.law = BaseLaw::bingham;
  opt.transition = TransitionShape::tanh;
  opt.transition_time = false;
  opt.lost_motion = false;
  opt.stiffness = false;
  opt.series_compliance = false;
  opt.samples_per_record = 1000;
  const CalibrationResult r = calibrate(recs, opt, check);
  // tanh; with the current exponent; with that and the viscous exponent.
  ASSERT_EQ(r.fits.size(), 3u);
  const Baseline& b = r.best().baseline;
  std::string notes;
  for (const std::string& n : r.notes) notes += n + "\n";
  EXPECT_EQ(baseline_form_name(b), "bingham_tanh+current_exponent+viscous_exponent") << r.choice_reason << "\n"
                                                                                        << notes;
  EXPECT_NEAR(b.yield_n.current_exponent, 2.0, 0.3);
  EXPECT_NEAR(b.viscous_exponent, 0.6, 0.1);
  // 2 % noise: with the shape the check records' gap is the noise's.
  for (const double g : baseline_gaps(b, check)) EXPECT_LT(g, 0.03);
}

}  // namespace
}  // namespace mrd::discrepancy
