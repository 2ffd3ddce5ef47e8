// The spencer baseline law (Spencer et al. 1997, physics/spencer_law.hpp):
// the laboratory's published fit evaluated by the project on its shared
// records against an evaluation written here in the units the fit was
// published in (N, mm, s), and the [spencer] table's refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <filesystem>
#include <string>
#include <vector>

#include "host_sim/discrepancy/baseline.hpp"
#include "host_sim/discrepancy/baseline_file.hpp"
#include "host_sim/discrepancy/calibrate.hpp"
#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/io/usage_error.hpp"
#include "mrd/physics/mr_damper.hpp"

namespace mrd::discrepancy {
namespace {
namespace fs = std::filesystem;

fs::path spencer_lab_dir() { return fs::path(MRD_SHARED_DIR) / "lab_data" / "quiroz_utfsm"; }

/// The published fit as printed (N, mm, s; A = 300, n = 2, β = γ), at a
/// current i in A, and its model integrated in mm by RK4 with 64 fixed
/// sub-steps per sample: the stroke's velocity held over a sample and the
/// stroke advancing with it, y starting at the first stroke and z at 0, the
/// force F = c1 ẏ + k1 (x − x0) at each sample from the state there.
std::vector<double> published_force_in_mm(const std::vector<double>& t_s, const std::vector<double>& x_m,
                                          const std::vector<double>& v_m_s, double i_a) {
  const double k0 = 1.501e-4, k1 = 1.2388, x0 = 2.309e-3;  // N/mm, N/mm, mm
  const double alpha = -38.152 * i_a * i_a + 41.508 * i_a + 15.221;  // N/mm
  const double gamma = 1.8941 * std::exp(-3.6561 * i_a);             // 1/mm²
  const double beta = gamma, big_a = 300.0;
  const double c0 = 7.626 * i_a + 0.9249, c1 = 78.337 * i_a + 9.867;  // N·s/mm
  const std::size_t n = t_s.size();
  std::vector<double> f(n);
  double y = x_m[0] * 1e3, z = 0.0;  // mm
  const auto ydot = [&](double x, double v, double yy, double zz) {
    return (alpha * zz + c0 * v + k0 * (x - yy)) / (c0 + c1);
  };
  const auto zdot = [&](double v, double yd, double zz) {
    const double u = v - yd;
    return -gamma * std::fabs(u) * zz * std::fabs(zz) - beta * u * zz * zz + big_a * u;
  };
  for (std::size_t k = 0; k < n; ++k) {
    const double x = x_m[k] * 1e3, v = v_m_s[k] * 1e3;  // mm, mm/s
    f[k] = c1 * ydot(x, v, y, z) + k1 * (x - x0);
    const double dt = k + 1 < n ? t_s[k + 1] - t_s[k] : 0.0;
    const int m = 64;
    const double h = dt / m;
    double xs = x;
    for (int j = 0; j < m; ++j) {
      const double y1 = ydot(xs, v, y, z), z1 = zdot(v, y1, z);
      const double y2 = ydot(xs + 0.5 * h * v, v, y + 0.5 * h * y1, z + 0.5 * h * z1);
      const double z2 = zdot(v, y2, z + 0.5 * h * z1);
      const double y3 = ydot(xs + 0.5 * h * v, v, y + 0.5 * h * y2, z + 0.5 * h * z2);
      const double z3 = zdot(v, y3, z + 0.5 * h * z2);
      const double y4 = ydot(xs + h * v, v, y + h * y3, z + h * z3);
      const double z4 = zdot(v, y4, z + h * z3);
      y += h / 6.0 * (y1 + 2.0 * y2 + 2.0 * y3 + y4);
      z += h / 6.0 * (z1 + 2.0 * z2 + 2.0 * z3 + z4);
      xs += h * v;
    }
  }
  return f;
}

double spencer_rms(const std::vector<double>& a, std::size_t begin, std::size_t end) {
  double s = 0.0;
  for (std::size_t k = begin; k < end; ++k) s += a[k] * a[k];
  return std::sqrt(s / static_cast<double>(end - begin));
}

Baseline published_baseline() {
  Baseline b = thesis_baseline();
  b.name = "published";
  b.law = BaseLaw::spencer;
  b.spencer = published_lab_spencer();
  b.range.current_max_a = 1.0;
  return b;
}

// (a) The project's law on the published parameters against the evaluation
// above, on two records of different families and currents.
//
// Tolerance: the project integrates with sub-steps of at most 1 over a bound
// on the system's largest rate (RK4's error on a decaying mode 7e-3 of the
// mode per sub-step, on the fast mode only, which decays within the
// sub-step's few multiples); the evaluation here with 64 per 1 ms sample
// (0.12 at the fastest rate of these records, some 7500 1/s at 0 A, error
// 1e-7 of the mode). The fast mode carries the force only through reversals,
// so the two must agree to well within 1e-3 of the record's RMS force at
// every sample; 1e-3 is a hundredth of the published model's gap on these
// records (below), so that an agreement at it leaves the gap unchanged in
// its second digit. The SI conversion is checked along: a factor of 10³ wrong anywhere
// moves the force by far more.
//
// The published model's gap: the issue reports 0.10–0.13 for it on the raw
// sine families, a figure per family computed outside the project. Here it
// is one record's, over the moving span, with the project's smoothed
// displacement and derived velocity and no force-channel lag (the published
// fit has none); records of a family spread about its figure (the 0 A ones
// the worst: the fit's γ(0) saturates z early). The band is the issue's
// range widened by a factor 1.5 each way, [0.067, 0.195]: a gap outside it
// is a model other than the one published, not a difference of input.
TEST(SpencerLaw, PublishedFitMatchesAnEvaluationInItsOwnUnits) {
  ASSERT_TRUE(fs::exists(spencer_lab_dir())) << spencer_lab_dir() << " not found";
  for (const auto& [file, current_a] : {std::pair{"5mm_3Hz_0p50A.csv", 0.5}, std::pair{"2mm_5Hz_0p00A.csv", 0.0}}) {
    const MeasuredData rec = read_measured(spencer_lab_dir() / file);
    const ModelInput in = model_input(rec);
    const DamperModel model(in, published_baseline());
    ModelWorkspace ws;
    std::vector<double> project;
    model.simulate(EffectSet{}, {}, ws, project);
    const std::vector<double> own = published_force_in_mm(in.time_s, in.disp_m, in.vel_m_s, current_a);
    const SampleRange moving = moving_span(in.vel_m_s);
    const double scale = spencer_rms(own, moving.begin, moving.end);
    ASSERT_GT(scale, 1.0) << file;
    double worst = 0.0;
    for (std::size_t k = 0; k < own.size(); ++k) worst = std::max(worst, std::fabs(project[k] - own[k]));
    EXPECT_LT(worst, 1e-3 * scale) << file << ": largest difference " << worst << " N, RMS force " << scale << " N";
    const double gap = normalized_rms_gap(
        std::span<const double>(rec.force_n).subspan(moving.begin, moving.size()),
        std::span<const double>(own).subspan(moving.begin, moving.size()));
    std::printf("%s: published spencer fit, NRMSE %.4f; project against own evaluation: %.2e of the RMS force\n",
                file, gap, worst / scale);
    EXPECT_GT(gap, 0.10 / 1.5) << file;
    EXPECT_LT(gap, 0.13 * 1.5) << file;
  }
}

// (d) The closed loop's damper (physics::MrDamper, ForceLaw::kSpencer) on the
// published parameters, stepped through two shared records sample by sample
// at their constant current, against the evaluation above in N, mm and s:
// the same 1e-3 of the RMS force as (a) (the same integration, from y = 0
// where the evaluation starts y at the first stroke: k0 = 0.15 N/m times a
// few millimetres, under 1e-3 N).
TEST(SpencerLaw, ThePlantsDamperStepsThePublishedFit) {
  ASSERT_TRUE(fs::exists(spencer_lab_dir())) << spencer_lab_dir() << " not found";
  for (const auto& [file, current_a] : {std::pair{"5mm_3Hz_0p50A.csv", 0.5}, std::pair{"2mm_5Hz_0p00A.csv", 0.0}}) {
    const MeasuredData rec = read_measured(spencer_lab_dir() / file);
    const ModelInput in = model_input(rec);
    physics::MrDamperParams p;
    p.law = physics::ForceLaw::kSpencer;
    p.spencer = published_lab_spencer();
    p.rating.current_a = 1.0;
    // A fluid that stays fully mixed: PR = 1 whatever the stroke (Eq. 5.6–5.9
    // with every a and b at 1).
    p.pr.a_initial = p.pr.b_initial = p.pr.a_final = p.pr.b_final = 1.0;
    const double dt = in.time_s[1] - in.time_s[0];
    physics::MrDamper damper(p, dt, 0.0);
    damper.reset(0.0, current_a);
    std::vector<double> plant(in.time_s.size());
    for (std::size_t k = 0; k < plant.size(); ++k) plant[k] = damper.step(current_a, in.vel_m_s[k], in.disp_m[k]);
    EXPECT_EQ(damper.participant_ratio(), 1.0);
    EXPECT_NEAR(damper.current_a(), current_a, 1e-12);
    const std::vector<double> own = published_force_in_mm(in.time_s, in.disp_m, in.vel_m_s, current_a);
    const SampleRange moving = moving_span(in.vel_m_s);
    const double scale = spencer_rms(own, moving.begin, moving.end);
    double worst = 0.0;
    for (std::size_t k = 0; k < own.size(); ++k) worst = std::max(worst, std::fabs(plant[k] - own[k]));
    EXPECT_LT(worst, 1e-3 * scale) << file << ": largest difference " << worst << " N, RMS force " << scale << " N";
  }
}

// (b) [spencer] tables with bad values are refused naming file, line and field.
std::string spencer_file_text() {
  BaselineFile f;
  f.baseline = published_baseline();
  f.baseline.range = {0.0, 1.0, 0.1, 1500.0, 0.002, 0.025, 0.25, 5.0};
  f.baseline.expected_gap = 0.2;
  return baseline_toml(f);
}

std::string spencer_error_of(const std::string& text) {
  try {
    (void)parse_baseline_toml(text, "damper.toml");
  } catch (const io::UsageError& e) {
    return e.what();
  }
  return {};
}

int spencer_line_of(const std::string& text, const std::string& key) {
  int line = 1;
  for (std::size_t pos = 0; pos < text.size(); ++line) {
    if (text.compare(pos, key.size(), key) == 0) return line;
    pos = text.find('\n', pos);
    if (pos == std::string::npos) break;
    ++pos;
  }
  return -1;
}

TEST(SpencerLaw, FileReadsBackAndRefusesBadTables) {
  const std::string good = spencer_file_text();
  ASSERT_EQ(spencer_error_of(good), "") << good;
  const BaselineFile back = parse_baseline_toml(good, "damper.toml");
  EXPECT_EQ(back.baseline.law, BaseLaw::spencer);
  // Published: α(1 A) = −38.152 + 41.508 + 15.221 = 18.577 N/mm; c1(0) = 9.867 N·s/mm.
  EXPECT_NEAR(back.baseline.spencer.alpha_at(1.0), 18577.0, 1e-6);
  EXPECT_NEAR(back.baseline.spencer.c1_at(0.0), 9867.0, 1e-9);
  EXPECT_NEAR(back.baseline.spencer.gamma_at(0.0), 1.8941e6, 1e-3);

  struct Case {
    std::string from, to, key, field, problem;
  };
  // Each case replaces the whole line that starts with `from`.
  const std::vector<Case> cases = {
      {"n = ", "n = 0.5", "n = ", "spencer.n", "expected an exponent in [1, 10], got 0.5"},
      {"a = ", "a = -300.0", "a = ", "spencer.a", "got -300.0"},
      {"gamma_per_m_pow_n = ", "gamma_per_m_pow_n = nan", "gamma_per_m_pow_n", "spencer.gamma_per_m_pow_n",
       "expected a finite number"},
      {"k1_n_m = ", "k1_n_m = \"soft\"", "k1_n_m", "spencer.k1_n_m", "expected a number"},
      {"x0_m = ", "x0_m = 0.0\nx1_m = 0.0", "x1_m", "spencer.x1_m", "unknown key"},
      // c1(1 A) = 9867 − 20000 < 0: ẏ would divide by a negative c0 + c1.
      {"c1_per_a_ns_m = ", "c1_per_a_ns_m = -20000.0", "c1_per_a_ns_m", "spencer.c1_per_a_ns_m",
       "expected more than 0"},
      // −100000 i² + 41508 i + 15221 N/m is positive at 0 A and at its vertex
      // (0.21 A), −43271 N/m at 1 A, the top of the validity range.
      {"alpha_per_a2_n_m = ", "alpha_per_a2_n_m = -100000.0", "alpha_per_a_n_m", "spencer.alpha_per_a_n_m",
       "expected a stiffness of at least 0"},
      {"x0_m = ", "x0_m = 0.0\n\n[yield_n]\nat_zero = 1.0", "[yield_n]", "yield_n", "not allowed"},
  };
  for (const Case& c : cases) {
    std::string text = good;
    const auto at = text.find("\n" + c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    const auto eol = text.find('\n', at + 1);
    text.replace(at + 1, eol - at - 1, c.to);
    const std::string e = spencer_error_of(text);
    EXPECT_EQ(e.rfind("damper.toml:" + std::to_string(spencer_line_of(text, c.key)) + ": " + c.field + ": ", 0), 0u)
        << c.field << " -> " << e;
    EXPECT_NE(e.find(c.problem), std::string::npos) << e;
  }
  // A missing key names the table.
  std::string text = good;
  const auto at = text.find("\nbeta_over_gamma = ");
  ASSERT_NE(at, std::string::npos);
  text.erase(at + 1, text.find('\n', at + 1) - at);
  EXPECT_NE(spencer_error_of(text).find("spencer.beta_over_gamma"), std::string::npos) << spencer_error_of(text);
}

// (c) A joint calibration of the spencer law recovers the published model
// from records the evaluation above made (sines of the stroke, the current
// held, 1 kHz, no noise), and judges it on check records of a motion and
// currents it was not fitted to. The records are the model's own force, so
// the fit's gap must fall far below the published fit's 0.1 on real records:
// 0.01 on every record; α, c_0, c_1 at the fitted currents and γ(0) within
// 5 % (k_0 and k_1 carry a few newtons on these strokes and are left out).
MeasuredData spencer_sine_record(double amplitude_m, double frequency_hz, double current_a) {
  MeasuredData d;
  d.source = "sine";
  const double w = 2.0 * std::numbers::pi * frequency_hz;
  for (int k = 0; k < 1000; ++k) {
    const double t = 1e-3 * k;
    d.time_s.push_back(t);
    d.displacement_m.push_back(amplitude_m * std::sin(w * t));
    d.velocity_m_s.push_back(amplitude_m * w * std::cos(w * t));
    d.current_cmd_a.push_back(current_a);
  }
  d.force_n = published_force_in_mm(d.time_s, d.displacement_m, d.velocity_m_s, current_a);
  return d;
}

TEST(SpencerLaw, JointCalibrationRecoversThePublishedModel) {
  std::vector<MeasuredData> fit, check;
  for (const double i : {0.0, 0.5, 1.0}) {
    fit.push_back(spencer_sine_record(0.002, 5.0, i));
    fit.push_back(spencer_sine_record(0.005, 2.0, i));
  }
  for (const double i : {0.25, 0.75}) check.push_back(spencer_sine_record(0.0035, 3.0, i));
  CalibrateOptions opt;
  opt.law = BaseLaw::spencer;
  opt.samples_per_record = 500;
  const CalibrationResult r = calibrate(fit, opt, check);
  ASSERT_EQ(r.fits.size(), 1u);
  const Baseline& b = r.best().baseline;
  ASSERT_EQ(b.law, BaseLaw::spencer);
  for (const double g : r.best().record_gaps) EXPECT_LT(g, 0.01);
  for (const double g : baseline_gaps(b, check)) EXPECT_LT(g, 0.01);
  const physics::SpencerParams truth = published_lab_spencer();
  for (const double i : {0.0, 0.5, 1.0}) {
    EXPECT_NEAR(b.spencer.alpha_at(i), truth.alpha_at(i), 0.05 * truth.alpha_at(i)) << i;
    EXPECT_NEAR(b.spencer.c0_at(i), truth.c0_at(i), 0.05 * truth.c0_at(i)) << i;
    EXPECT_NEAR(b.spencer.c1_at(i), truth.c1_at(i), 0.05 * truth.c1_at(i)) << i;
  }
  EXPECT_NEAR(b.spencer.gamma_at(0.0), truth.gamma_at(0.0), 0.05 * truth.gamma_at(0.0));
}

}  // namespace
}  // namespace mrd::discrepancy
