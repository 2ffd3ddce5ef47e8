// Calibration on the real laboratory records of ../shared/lab_data (a small
// commercial damper nobody on this project made): calibrated on two
// families, judged on the third, against facts read off the records
// themselves (peaks, the plateau after a reversal).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "host_sim/discrepancy/baseline.hpp"
#include "host_sim/discrepancy/calibrate.hpp"
#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/workflow.hpp"

namespace mrd::discrepancy {
namespace {
namespace fs = std::filesystem;

fs::path lab_dir() { return fs::path(MRD_SHARED_DIR) / "lab_data" / "quiroz_utfsm"; }

std::vector<MeasuredData> lab_family(const std::string& family) {
  std::vector<MeasuredData> out;
  for (const char* c : {"0p00A", "0p25A", "0p50A", "0p75A", "1p00A"})
    out.push_back(read_measured(lab_dir() / (family + "_" + c + ".csv")));
  return out;
}

/// The records of two families, the first's then the second's.
std::vector<MeasuredData> lab_families(const std::string& first, const std::string& second) {
  std::vector<MeasuredData> out = lab_family(first);
  for (auto& d : lab_family(second)) out.push_back(std::move(d));
  return out;
}

TEST(CalibrateLab, TwoFamiliesPredictTheThird) {
  ASSERT_TRUE(fs::exists(lab_dir())) << lab_dir() << " not found: the shared data folder belongs beside the clone";
  const std::vector<MeasuredData> fit = lab_families("2mm_5Hz", "25mm_0p25Hz");
  const std::vector<MeasuredData> held = lab_family("5mm_3Hz");
  // The lost motion as a share of the force (the viscous form: below).
  CalibrateOptions opt;
  opt.current_exponent = opt.viscous_exponent = opt.stiffness = false;  // LawShape below
  opt.series_compliance = false;  // SeriesComplianceTakesTheLagThatGrowsWithTheForce
  opt.lost_motion_form = LostMotionForm::share;
  // The spencer law's fit takes minutes on these records: README,
  // discrepancy section, for its figures on them.
  opt.auto_spencer = false;
  const CalibrationResult r = calibrate(fit, opt, held);
  // Bingham with Eq. 4.4's transition and with the tanh one, Bouc–Wen; each
  // Bingham with a transition time and that with a lost motion, Bouc–Wen
  // with a lost motion.
  ASSERT_EQ(r.fits.size(), 8u);
  EXPECT_EQ(r.currents_a.size(), 5u);
  // The transition time generalizes: at 5 mm / 3 Hz the reversals come at
  // |a| = Aω² = 1.8 m/s² (nominal stroke), near the 2 mm / 5 Hz ones
  // (2.0 m/s²) and far from the 25 mm / 0.25 Hz ones (0.06 m/s²), and the
  // force builds after them over the same time (measured: RMS gap on the
  // 5 mm records 0.153 with it, 0.180 without, tanh transition). The time
  // itself must be a few milliseconds: the response time of MR fluid is of
  // that order, and the least-squares fit outside the code (README) gave
  // 4.1–7.5 ms from the three pairs of families.
  ASSERT_TRUE(r.best().baseline.has_transition_time()) << r.choice_reason;
  EXPECT_GT(r.best().baseline.transition_time_s, 0.002);
  EXPECT_LT(r.best().baseline.transition_time_s, 0.015);
  const auto rms = [](const std::vector<double>& g) {
    double s = 0.0;
    for (const double x : g) s += x * x;
    return std::sqrt(s / static_cast<double>(g.size()));
  };
  EXPECT_LT(rms(baseline_gaps(r.best().baseline, held)), rms(baseline_gaps(r.fits[0].baseline, held)));
  // The smooth transition carries to the held-out family better than Eq.
  // 4.4's, each with its transition time (measured: 0.153 against 0.172),
  // and the choice among the forms each with its kept extras is made on
  // the check records: Bouc–Wen with a lost motion has the lower BIC on the
  // fitted records (by about 200) but holds out 0.204.
  EXPECT_TRUE(r.best().baseline.has_tanh_transition()) << r.choice_reason;
  for (const LawFit& f : r.fits) {
    if (!f.baseline.has_transition_time() || f.baseline.has_tanh_transition() || f.baseline.has_lost_motion())
      continue;
    EXPECT_LT(rms(baseline_gaps(r.best().baseline, held)), rms(baseline_gaps(f.baseline, held)));
  }
  // The lost motion, on top, lowers the BIC on the 2 mm and 25 mm records
  // but not the gap on the 5 mm ones (measured: RMS 0.207 with it, 0.171
  // without): it does not generalize from these two families, not kept.
  EXPECT_FALSE(r.best().baseline.has_lost_motion()) << r.choice_reason;
  bool said = false;
  for (const std::string& n : r.notes) said = said || n.find("does not generalize") != std::string::npos;
  EXPECT_TRUE(said);

  // The thesis's 200 kN damper is about 100× too strong for these records
  // (README): its gap is far above 1.
  for (const double g : baseline_gaps(thesis_baseline(), held)) EXPECT_GT(g, 10.0);

  // Held-out 5 mm / 3 Hz records. Neither law has the force plateau the
  // records show just after each reversal, nor one pre-yield length for
  // 2 mm and 25 mm strokes, so the gap stays far from the noise level.
  // Measured, with the force lag fitted (about 7 ms): Bingham 0.11–0.26,
  // with the transition time 0.11–0.25, with it and the lost motion
  // 0.17–0.26 (either transition), Bouc–Wen 0.21–0.36 (of the five).
  // Bounds: 0.35 and 0.50, to allow for the start values.
  for (const LawFit& f : r.fits) {
    const double bound = f.baseline.law == BaseLaw::bingham ? 0.35 : 0.50;
    for (const double g : baseline_gaps(f.baseline, held)) EXPECT_LT(g, bound) << baseline_form_name(f.baseline);
  }

  // Independent facts: the records' own peaks at 1 A (1.40 kN at 2 mm / 5 Hz,
  // 1.70 kN at 25 mm / 0.25 Hz; the lab README's "about 1.5–1.9 kN"). The
  // calibrated model's peak on each must be within 30 % of it: the model
  // form misses the force held just after each reversal and the start of
  // the 25 mm records, which is where the peaks are (measured: −3 % and
  // −24 %). The held-out 5 mm / 3 Hz records reach 88 mm/s, beyond the
  // 50 mm/s of the fit; their peak is an extrapolation and is not checked.
  ModelWorkspace ws;
  std::vector<double> force;
  for (const std::size_t i : {std::size_t{4}, std::size_t{9}}) {
    const DamperModel m(model_input(fit[i]), r.best().baseline);
    m.simulate(EffectSet{}, {}, ws, force);
    double peak = 0.0;
    double measured = 0.0;
    for (const double f : force) peak = std::max(peak, std::fabs(f));
    for (const double f : fit[i].force_n) measured = std::max(measured, std::fabs(f));
    EXPECT_GT(measured, 1300.0) << fit[i].source;
    EXPECT_LT(measured, 2000.0) << fit[i].source;
    EXPECT_NEAR(peak, measured, 0.3 * measured) << fit[i].source;
  }
  EXPECT_LT(r.best().baseline.range.velocity_max_m_s, 0.07);
  // The 5 mm / 3 Hz check records (±4.6 mm) repeat neither the ±1.6 mm of
  // the 2 mm records nor the ±25 mm of the 25 mm ones.
  for (const std::string& n : r.notes) EXPECT_EQ(n.find("repeats the amplitude"), std::string::npos) << n;

  // Verdicts on the held-out family through `mrd discrepancy` with this
  // baseline. Its expected gap covers the check records, which are these
  // held-out records: here it is taken on its own calibration records alone
  // (0.20), as if they had not been seen. A record inside 1.25 times that has no
  // discrepancy to explain, whatever shape its residual has, so it is
  // `none`: the five records are of the same damper in the same state,
  // measured minutes apart (the lab README), so none of them holds an
  // effect the calibration records do not. At most a third may be
  // `unexplained`, and only with a gap beyond the tolerance.
  DiscrepancyOptions dopt;
  dopt.baseline = r.best().baseline;
  EXPECT_EQ(dopt.baseline.expected_gap_basis, GapBasis::check_records);
  ASSERT_EQ(r.best().held_out_gaps.size(), held.size());
  for (const double g : r.best().held_out_gaps) EXPECT_LE(g, dopt.baseline.expected_gap);
  dopt.baseline.expected_gap = *std::max_element(r.best().record_gaps.begin(), r.best().record_gaps.end());
  dopt.baseline.expected_gap_basis = GapBasis::calibration_records;
  ASSERT_GT(dopt.baseline.expected_gap, 0.0);
  int unexplained = 0;
  for (const MeasuredData& d : held) {
    const DiscrepancyResult v = run_discrepancy(d, dopt);
    EXPECT_NE(v.verdict, Verdict::baseline_mismatch) << d.source;
    EXPECT_NE(v.verdict, Verdict::explained) << d.source << ": " << (v.findings.empty() ? "" : v.findings.front());
    if (v.verdict == Verdict::unexplained) {
      ++unexplained;
      EXPECT_GT(v.gap_before, 1.25 * dopt.baseline.expected_gap) << d.source;
    }
    // A record within it is told why: the baseline's own error, on which records.
    const double tolerance = 1.25 * dopt.baseline.expected_gap;
    if (v.verdict == Verdict::none && v.gap_before <= tolerance && v.gap_validation_before <= tolerance) {
      bool told = false;
      for (const std::string& f : v.findings)
        told = told || (f.find("known model-form error") != std::string::npos &&
                        f.find("the records it was calibrated on") != std::string::npos);
      EXPECT_TRUE(told) << d.source << ": " << (v.findings.empty() ? "" : v.findings.front());
    }
  }
  EXPECT_LE(3 * unexplained, static_cast<int>(held.size()));
}

TEST(CalibrateLab, CheckRecordsThatRepeatTheFittedMotionsAreNamed) {
  ASSERT_TRUE(fs::exists(lab_dir())) << lab_dir() << " not found: the shared data folder belongs beside the clone";
  // Fitted at 0, 0.5 and 1 A, checked at 0.25 and 0.75 A of the same 2 mm /
  // 5 Hz motion: such check records judge the current laws, not other
  // motions, and the calibration says so.
  const std::vector<MeasuredData> family = lab_family("2mm_5Hz");
  const std::vector<MeasuredData> fit{family[0], family[2], family[4]};
  const std::vector<MeasuredData> check{family[1], family[3]};
  CalibrateOptions opt;
  opt.current_exponent = opt.viscous_exponent = opt.stiffness = false;  // LawShape below
  opt.series_compliance = false;  // SeriesComplianceTakesTheLagThatGrowsWithTheForce
  opt.law = BaseLaw::bingham;
  opt.transition = TransitionShape::tanh;
  opt.transition_time = false;
  opt.lost_motion = false;
  const CalibrationResult r = calibrate(fit, opt, check);
  bool said = false;
  for (const std::string& n : r.notes) said = said || n.find("repeats the amplitude and frequency") != std::string::npos;
  EXPECT_TRUE(said);
}

// The viscous lost motion (baseline.hpp) on the laboratory damper. After
// each reversal the measured force–displacement loops at 1 A (F against x,
// as in the plots of the README's discrepancy section) rise steeply, hold a
// plateau and reach the full force some 0.3–0.5 mm past the reversal at all
// three strokes; the plateau is about 500 N at 2 mm / 5 Hz, where the piston
// crosses it at 25–35 mm/s, and 150–250 N at 25 mm / 0.25 Hz, at about
// 5 mm/s, of a full force of 1.0–1.4 kN: a level that follows the velocity
// (Y tanh(v / v_p) with v_p between about 20 and 70 mm/s), not one share of
// the force. Fitted on the 2 mm and 5 mm families with the form the check
// records choose there (the tanh transition with a transition time) and
// judged on the 25 mm family, the viscous form must carry to the slow
// strokes better than the share form and than none, with a play at 1 A in
// the range read off the loops. On those records, the chosen form's floors
// (record_floor_gaps) lie below its gaps.
TEST(CalibrateLab, ViscousLostMotionCarriesToTheSlowStrokes) {
  ASSERT_TRUE(fs::exists(lab_dir())) << lab_dir() << " not found: the shared data folder belongs beside the clone";
  const std::vector<MeasuredData> fit = lab_families("2mm_5Hz", "5mm_3Hz");
  const std::vector<MeasuredData> held = lab_family("25mm_0p25Hz");
  CalibrateOptions opt;
  opt.current_exponent = opt.viscous_exponent = opt.stiffness = false;  // LawShape below
  opt.series_compliance = false;  // SeriesComplianceTakesTheLagThatGrowsWithTheForce
  opt.law = BaseLaw::bingham;
  opt.transition = TransitionShape::tanh;
  const CalibrationResult r = calibrate(fit, opt, held);
  // tanh, with a transition time, with that and either lost motion.
  ASSERT_EQ(r.fits.size(), 4u);
  ASSERT_EQ(baseline_form_name(r.fits[3].baseline), "bingham_tanh+transition_time+viscous_lost_motion");
  ASSERT_TRUE(r.best().baseline.has_viscous_lost_motion()) << r.choice_reason;
  const auto rms_held = [&](const LawFit& f) { return rms_over_records(baseline_gaps(f.baseline, held)); };
  EXPECT_LT(rms_held(r.fits[3]), rms_held(r.fits[2])) << "against the share form";
  EXPECT_LT(rms_held(r.fits[3]), rms_held(r.fits[1])) << "against none";
  const Baseline& b = r.best().baseline;
  const double play_m = b.lost_motion_m_per_n * b.yield_n.at(1.0);
  EXPECT_GT(play_m, 0.1e-3);
  EXPECT_LT(play_m, 0.6e-3);
  // The band: within the loops' 20–70 mm/s or below it (the transition time
  // and the force lag take part of the build-up the plateau shows), not
  // above it; and not under 5 mm/s, where the 25 mm plateau, crossed at
  // about 5 mm/s, would hold more than tanh 1 = 0.76 of the full force
  // against the 0.15–0.25 read off its loop (v_p → 0 is a step).
  EXPECT_GT(b.lost_motion_band_m_s, 0.005);
  EXPECT_LT(b.lost_motion_band_m_s, 0.07);

  // The 25 mm records' floors: the chosen form fitted to each alone, from the
  // calibrated baseline. From that start a fit ends no worse on the record
  // (1e-3: judged at full rate, fitted on a thinned record). On the 1 A record
  // the form alone must fit at least as well as the field's standard model
  // fitted to that record alone: Spencer et al. (1997)'s modified Bouc–Wen
  // (α, c0, c1, k0, k1, the yield displacement and a force lag; n = 2,
  // β = γ), integrated at 2 kHz and fitted by Nelder–Mead outside this code,
  // left 8.79 % (README, discrepancy section).
  const std::vector<double> floors = record_floor_gaps(b, held, opt);
  const std::vector<double> gaps = baseline_gaps(b, held);
  ASSERT_EQ(floors.size(), held.size());
  for (std::size_t i = 0; i < held.size(); ++i) EXPECT_LE(floors[i], gaps[i] + 1e-3) << held[i].source;
  EXPECT_LT(floors.back(), 0.0879) << held.back().source;
}

TEST(CalibrateLab, LostMotionKeptWhenItGeneralizes) {
  ASSERT_TRUE(fs::exists(lab_dir())) << lab_dir() << " not found: the shared data folder belongs beside the clone";
  // Calibrated on the 2 mm / 5 Hz and 5 mm / 3 Hz records, whose loops show
  // the plateau after each reversal; judged on the 25 mm / 0.25 Hz records.
  const std::vector<MeasuredData> fit = lab_families("2mm_5Hz", "5mm_3Hz");
  const std::vector<MeasuredData> held = lab_family("25mm_0p25Hz");
  // The lost motion alone on the plain law: with the transition time kept
  // first (RMS 0.188 against 0.224 on the 25 mm records), the lost motion on
  // top no longer carries to them (0.191 against 0.188).
  CalibrateOptions opt;
  opt.current_exponent = opt.viscous_exponent = opt.stiffness = false;  // LawShape below
  opt.series_compliance = false;  // SeriesComplianceTakesTheLagThatGrowsWithTheForce
  opt.law = BaseLaw::bingham;
  opt.transition = TransitionShape::linear;
  opt.transition_time = false;
  opt.lost_motion_form = LostMotionForm::share;
  const CalibrationResult r = calibrate(fit, opt, held);
  ASSERT_EQ(r.fits.size(), 2u);
  ASSERT_TRUE(r.best().baseline.has_lost_motion()) << r.choice_reason;
  // The plateau read off the 2 mm / 1 A loop (force–displacement, docs/
  // discrepancy/lab_calibration_2mm_5Hz_1A_loops.png): about 0.5 of 1.3 kN,
  // so a held-up share near 0.6, for about 0.3 mm, at Y(1 A) ≈ 0.84 kN of the
  // plain fit, λ ≈ 3.6e-7 m/N. The fit must land in the same range: share
  // 0.3–0.8, play at 1 A 0.1–0.6 mm.
  const Baseline& b = r.best().baseline;
  EXPECT_GT(b.lost_motion_share, 0.3);
  EXPECT_LT(b.lost_motion_share, 0.8);
  const double play_m = b.lost_motion_m_per_n * b.yield_n.at(1.0);
  EXPECT_GT(play_m, 0.1e-3);
  EXPECT_LT(play_m, 0.6e-3);
  // On every held-out record with current (the 0 A one is friction-like, no
  // plateau) the gap is lower with the lost motion than without (measured:
  // 18.7 → 14.8, 16.4 → 12.8, 18.1 → 14.7, 19.9 → 16.6 %).
  const std::vector<double> with = baseline_gaps(r.fits[1].baseline, held);
  const std::vector<double> without = baseline_gaps(r.fits[0].baseline, held);
  for (std::size_t i = 1; i < held.size(); ++i) EXPECT_LT(with[i], without[i]) << held[i].source;
}

/// Where in the stroke the residual of `b` on `d` sits: by the distance
/// the actuator has gone since its last reversal, the share of the squared
/// residual and the mean of (F_model − F_meas) sgn v over the RMS force
/// (> 0: the model too strong in the direction of motion).
void print_residual_by_stroke(const Baseline& b, const MeasuredData& d) {
  const DamperModel m(model_input(d), b);
  ModelWorkspace ws;
  std::vector<double> f;
  m.simulate(EffectSet{}, {}, ws, f);
  const ModelInput& in = m.input();
  constexpr std::array<double, 7> edges_mm{0.0, 0.1, 0.2, 0.3, 0.5, 1.0, 1e9};
  std::array<double, 6> sq{}, signed_sum{}, count{};
  double total = 0.0, ff = 0.0, n = 0.0;
  // Over the samples where the actuator moves, as the gap (baseline_gaps).
  const SampleRange moving = moving_span(in.vel_m_s);
  double x_rev = in.disp_m[moving.begin];
  int dir = 0;
  for (std::size_t k = moving.begin; k < moving.end; ++k) {
    const int s = in.vel_m_s[k] > 0.0 ? 1 : -1;
    if (s != dir) {
      dir = s;
      x_rev = in.disp_m[k];
    }
    const double e = f[k] - d.force_n[k];
    const double mm = std::fabs(in.disp_m[k] - x_rev) * 1e3;
    std::size_t bin = 0;
    while (bin + 1 < sq.size() && mm >= edges_mm[bin + 1]) ++bin;
    sq[bin] += e * e;
    signed_sum[bin] += e * s;
    count[bin] += 1.0;
    total += e * e;
    ff += d.force_n[k] * d.force_n[k];
    n += 1.0;
  }
  const double rms_f = std::sqrt(ff / n);
  std::string line = "    since reversal (mm: share of residual^2, mean signed error/RMS F, share of time):";
  for (std::size_t i = 0; i < sq.size(); ++i) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " [%g,%g) %.2f %+.3f %.2f", edges_mm[i], edges_mm[i + 1] > 1e8 ? 99.0 : edges_mm[i + 1],
                  sq[i] / total, count[i] > 0.0 ? signed_sum[i] / count[i] / rms_f : 0.0, count[i] / n);
    line += buf;
  }
  std::printf("%s\n", line.c_str());
}

/// The lag (s, 1 ms steps up to 20 ms) at which a least-squares fit of the
/// measured force on tanh(v/5 mm/s) and v, v lagged, leaves the least
/// residual over the moving span less 0.2 s at either end; and the ratio of
/// the force's RMS to the velocity's there (N·s/m). v is the central
/// difference of the displacement.
std::pair<double, double> force_lag_and_ratio(const MeasuredData& d) {
  const std::size_t n = d.time_s.size();
  const double dt = d.time_s[1] - d.time_s[0];
  std::vector<double> v(n, 0.0);
  for (std::size_t k = 1; k + 1 < n; ++k) v[k] = (d.displacement_m[k + 1] - d.displacement_m[k - 1]) / (2.0 * dt);
  const SampleRange moving = moving_span(v);
  const std::size_t skip = static_cast<std::size_t>(std::lround(0.2 / dt));
  const std::size_t a = moving.begin + skip, b = moving.end - skip;
  double best = HUGE_VAL, best_lag = 0.0;
  for (std::size_t lag = 0; lag <= static_cast<std::size_t>(std::lround(0.02 / dt)); ++lag) {
    // Normal equations of F ≈ p tanh(v/v_b) + q v on the lagged v.
    double s11 = 0.0, s12 = 0.0, s22 = 0.0, r1 = 0.0, r2 = 0.0, ff = 0.0;
    for (std::size_t k = a; k < b; ++k) {
      const double x1 = std::tanh(v[k - lag] / 0.005), x2 = v[k - lag], f = d.force_n[k];
      s11 += x1 * x1;
      s12 += x1 * x2;
      s22 += x2 * x2;
      r1 += x1 * f;
      r2 += x2 * f;
      ff += f * f;
    }
    const double det = s11 * s22 - s12 * s12;
    const double p = (r1 * s22 - r2 * s12) / det, q = (s11 * r2 - s12 * r1) / det;
    const double res = ff - p * r1 - q * r2;
    if (res < best) {
      best = res;
      best_lag = static_cast<double>(lag) * dt;
    }
  }
  double ff = 0.0, vv = 0.0;
  for (std::size_t k = a; k < b; ++k) {
    ff += d.force_n[k] * d.force_n[k];
    vv += v[k] * v[k];
  }
  return {best_lag, std::sqrt(ff / vv)};
}

// The force's lag behind the motion grows with the current on the
// laboratory damper: on the 5 mm / 3 Hz records (1 kHz) the best lag is 2 ms
// at 0 A and 9 ms at 1 A, while the force per velocity (RMS over RMS) grows
// from about 2.6 to 22 kN·s/m. A compliance in series with the law delays
// the force by (F/v)/k_s, so the two lags read k_s ≈ Δ(F/v)/Δlag ≈ 2.8 MN/m
// off the records, with no model. Calibrated on the other two families and
// checked on these, the series compliance must be kept, the force channel's
// own lag must fall to under a millisecond (the compliance is the lag) and
// k_s must lie within 35 % of the records' reading (the lags are read to
// 1 ms of 7; F/v by RMS stands for the slope of a law that is not linear).
TEST(CalibrateLab, SeriesComplianceTakesTheLagThatGrowsWithTheForce) {
  ASSERT_TRUE(fs::exists(lab_dir())) << lab_dir() << " not found: the shared data folder belongs beside the clone";
  const std::vector<MeasuredData> held = lab_family("5mm_3Hz");
  const auto [lag0_s, ratio0] = force_lag_and_ratio(held.front());
  const auto [lag1_s, ratio1] = force_lag_and_ratio(held.back());
  ASSERT_GT(lag1_s, lag0_s + 3e-3);
  const double k_read_n_m = (ratio1 - ratio0) / (lag1_s - lag0_s);
  CalibrateOptions opt;
  opt.current_exponent = opt.viscous_exponent = opt.stiffness = false;
  opt.lost_motion = false;
  opt.law = BaseLaw::bingham;
  opt.transition = TransitionShape::tanh;
  const CalibrationResult r = calibrate(lab_families("2mm_5Hz", "25mm_0p25Hz"), opt, held);
  const Baseline& b = r.best().baseline;
  std::string notes;
  for (const std::string& n : r.notes) notes += n + "\n";
  ASSERT_TRUE(b.has_series_compliance()) << r.choice_reason << "\n" << notes;
  std::printf("lags %.0f and %.0f ms, F/v %.0f and %.0f N s/m: k_s read %.3g N/m, calibrated %.3g N/m\n",
              1e3 * lag0_s, 1e3 * lag1_s, ratio0, ratio1, k_read_n_m, 1.0 / b.series_compliance_m_per_n);
  EXPECT_NEAR(1.0 / b.series_compliance_m_per_n, k_read_n_m, 0.35 * k_read_n_m);
  EXPECT_LT(b.force_delay_s, 1e-3);
}

// The held-out study of the README (discrepancy section): each law
// calibrated on two families with the third as its --check records, judged
// on that third; the median gap over the fifteen held-out records. Minutes
// per law, so not in CTest (LongStudy, cmake/MrdTesting.cmake): run it with
// --gtest_filter=*LongStudy*; MRD_LAB_HELD_OUT_LAWS narrows the laws (a
// comma-separated list of bingham, bouc_wen, spencer; default all three).
TEST(CalibrateLab, LongStudyHeldOutFamily) {
  const char* laws_set = std::getenv("MRD_LAB_HELD_OUT_LAWS");
  const char* laws_env = laws_set != nullptr ? laws_set : "bingham,bouc_wen,spencer";
  ASSERT_TRUE(fs::exists(lab_dir())) << lab_dir() << " not found: the shared data folder belongs beside the clone";
  const std::array<const char*, 3> families{"2mm_5Hz", "5mm_3Hz", "25mm_0p25Hz"};
  std::string list(laws_env);
  std::size_t at = 0;
  while (at <= list.size()) {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    const std::string name = list.substr(at, comma - at);
    at = comma + 1;
    if (name.empty()) continue;
    CalibrateOptions opt;
    // MRD_LAB_HELD_OUT_NO_SHAPE=1: the Bingham law without the shape terms
    // (current and viscous exponents, spring), as before them.
    if (std::getenv("MRD_LAB_HELD_OUT_NO_SHAPE") != nullptr)
      opt.current_exponent = opt.viscous_exponent = opt.stiffness = false;
    // MRD_LAB_HELD_OUT_VERDICTS=1: each held-out record also through `mrd
    // discrepancy` with the baseline calibrated without it (seconds each).
    const bool verdicts = std::getenv("MRD_LAB_HELD_OUT_VERDICTS") != nullptr;
    std::array<int, 4> verdict_count{};
    // MRD_LAB_HELD_OUT_WHERE=1: where in the stroke each held-out record's residual sits.
    const bool where = std::getenv("MRD_LAB_HELD_OUT_WHERE") != nullptr;
    opt.law = name == "spencer" ? BaseLaw::spencer : (name == "bouc_wen" ? BaseLaw::bouc_wen : BaseLaw::bingham);
    std::vector<double> all;
    std::string per_family;
    for (std::size_t h = 0; h < families.size(); ++h) {
      const std::vector<MeasuredData> fit = lab_families(families[(h + 1) % 3], families[(h + 2) % 3]);
      const std::vector<MeasuredData> held = lab_family(families[h]);
      // MRD_LAB_HELD_OUT_NO_CHECK=1: calibrated on the two families alone,
      // as a user without check records (the extras judged by leaving out
      // each family in turn; MRD_LAB_NO_CROSS_VALIDATION=1: not judged).
      if (std::getenv("MRD_LAB_NO_CROSS_VALIDATION") != nullptr) opt.cross_validate = false;
      const bool no_check = std::getenv("MRD_LAB_HELD_OUT_NO_CHECK") != nullptr;
      const CalibrationResult r = no_check ? calibrate(fit, opt) : calibrate(fit, opt, held);
      std::vector<double> g = baseline_gaps(r.best().baseline, held);
      for (std::size_t i = 0; i < held.size(); ++i) {
        std::string line = "  " + fs::path(held[i].source).filename().string() + " gap " + std::to_string(g[i]);
        if (verdicts) {
          DiscrepancyOptions dopt;
          dopt.baseline = r.best().baseline;
          const DiscrepancyResult v = run_discrepancy(held[i], dopt);
          ++verdict_count[static_cast<std::size_t>(v.verdict)];
          line += std::string(" verdict ") + verdict_name(v.verdict) + " (expected gap " +
                  std::to_string(dopt.baseline.expected_gap) + ")";
        }
        std::printf("%s\n", line.c_str());
        if (where) print_residual_by_stroke(r.best().baseline, held[i]);
      }
      std::vector<double> sorted = g;
      std::sort(sorted.begin(), sorted.end());
      per_family += std::string(" ") + families[h] + " " + std::to_string(sorted[sorted.size() / 2]) + " (" +
                    baseline_form_name(r.best().baseline) + ")";
      std::printf("  %s held out: %s\n", families[h], r.choice_reason.substr(0, 300).c_str());
      for (const std::string& n : r.notes)
        if (n.find("kept") != std::string::npos) std::printf("    %s\n", n.c_str());
      all.insert(all.end(), g.begin(), g.end());
    }
    std::sort(all.begin(), all.end());
    std::printf("held-out %s: median %.4f over %zu records;%s\n", name.c_str(), all[all.size() / 2], all.size(),
                per_family.c_str());
    if (verdicts)
      for (std::size_t k = 0; k < verdict_count.size(); ++k)
        std::printf("  verdict %s: %d\n", verdict_name(static_cast<Verdict>(k)), verdict_count[k]);
  }
}

}  // namespace
}  // namespace mrd::discrepancy
