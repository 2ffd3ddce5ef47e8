// `mrd calibrate` run as a user runs it: a damper.toml that reads back,
// summary.json and the per-record lines; `mrd discrepancy --baseline` using
// it; missing or bad input (exit 2, one line).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "host_sim/discrepancy/baseline_file.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

class CalibrateCli : public ::testing::Test {
 protected:
  TempDir scratch_;
  TempDir out_;

  /// A sine record at 500 Hz (by default 4 s, 5 mm at 1 Hz) of a damper with
  /// F = (200 + 800 I) tanh(v / 5 mm/s) + (1000 + 3000 I) v (N, I in A),
  /// times `force_scale` (another damper when not 1).
  fs::path record(const std::string& name, double current_a, double amplitude_m = 0.005, double freq_hz = 1.0,
                  double duration_s = 4.0, double force_scale = 1.0) {
    const auto p = scratch_.path() / name;
    std::ofstream f(p);
    f << "time_s,displacement_m,current_cmd_A,force_N\n";
    const double w = 2.0 * kPi * freq_hz;
    for (int k = 0; k <= static_cast<int>(std::lround(duration_s / 0.002)); ++k) {
      const double t = k * 0.002;
      const double x = amplitude_m * std::sin(w * t);
      const double v = amplitude_m * w * std::cos(w * t);
      const double force = (200.0 + 800.0 * current_a) * std::tanh(v / 0.005) + (1000.0 + 3000.0 * current_a) * v;
      f << t << ',' << x << ',' << current_a << ',' << force_scale * force << '\n';
    }
    return p;
  }
};

TEST_F(CalibrateCli, WritesAReadableBaselineThatDiscrepancyUses) {
  const auto a = record("a.csv", 0.0);
  const auto b = record("b.csv", 0.5);
  const auto c = record("c.csv", 1.0);
  const auto r = run_mrd("calibrate --measured " + a.string() + " " + b.string() + " " + c.string() +
                             " --law bingham --lost-motion-form viscous --no-series-compliance --no-plots --out " +
                             out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"a.csv", "b.csv", "c.csv", "chosen: law given: bingham"})
    EXPECT_NE(r.out.find(name), std::string::npos) << name << "\n" << r.out;
  const auto toml = out_.path() / "damper.toml";
  const discrepancy::BaselineFile f = discrepancy::read_baseline_file(toml);
  EXPECT_EQ(f.baseline.law, discrepancy::BaseLaw::bingham);
  EXPECT_EQ(f.source_records.size(), 3u);
  EXPECT_FALSE(f.baseline.coil_identified);  // constant-current records
  // The yield force at 1 A of the generating law is 1000 N (tanh close to 1 at speed).
  EXPECT_NEAR(f.baseline.yield_n.at(1.0), 1000.0, 150.0);
  EXPECT_DOUBLE_EQ(f.baseline.range.current_max_a, 1.0);
  // The generating transition is a tanh of v / 5 mm/s: the BIC must prefer
  // it to Eq. 4.4's and find its velocity.
  EXPECT_TRUE(f.baseline.has_tanh_transition());
  EXPECT_NEAR(f.baseline.v_tf_m_s, 0.005, 0.0005);
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  // The law given with either transition, then each with a transition time
  // and with the lost motion in the form asked for: no --check records and
  // one motion (5 mm at 1 Hz) to leave out, so none is kept.
  EXPECT_TRUE(j["cross_validation"].is_null()) << j["cross_validation"].dump();
  EXPECT_EQ(j["chosen_law"], "bingham_tanh");
  ASSERT_EQ(j["fits"].size(), 6u);
  EXPECT_EQ(j["fits"][0]["law"], "bingham");
  EXPECT_EQ(j["fits"][1]["law"], "bingham_tanh");
  EXPECT_EQ(j["fits"][2]["law"], "bingham+transition_time");
  EXPECT_EQ(j["fits"][3]["law"], "bingham+viscous_lost_motion");  // on the law kept, not on the time refused
  EXPECT_EQ(j["fits"][4]["law"], "bingham_tanh+transition_time");
  EXPECT_EQ(j["fits"][5]["law"], "bingham_tanh+viscous_lost_motion");
  EXPECT_TRUE(fs::exists(out_.path() / "report.md"));
  EXPECT_FALSE(fs::exists(out_.path() / "loops_1.png"));

  // Against the calibrated baseline the record is close; against the
  // thesis's 200 kN damper it is about 100 times off.
  TempDir d1, d2;
  const auto with = run_mrd("discrepancy --measured " + c.string() + " --effects force_offset --baseline " +
                                toml.string() + " --out " + d1.path().string(),
                            scratch_.path());
  ASSERT_EQ(with.exit_code, 0) << with.err;
  const auto without = run_mrd(
      "discrepancy --measured " + c.string() + " --effects force_offset --out " + d2.path().string(), scratch_.path());
  ASSERT_EQ(without.exit_code, 0) << without.err;
  const double gap_with = nlohmann::json::parse(slurp(d1.path() / "summary.json"))["gap_before"].get<double>();
  const double gap_without = nlohmann::json::parse(slurp(d2.path() / "summary.json"))["gap_before"].get<double>();
  EXPECT_LT(gap_with, 0.15);
  EXPECT_GT(gap_without, 10.0);
  const auto inside = nlohmann::json::parse(slurp(d1.path() / "summary.json"))["baseline"];
  EXPECT_TRUE(inside["outside_coverage"].empty()) << inside.dump();
  EXPECT_NEAR(inside["record_frequency_hz"].get<double>(), 1.0, 0.05);

  // The same damper at 25 mm and 0.2 Hz (the same peak velocity, 31 mm/s): 5 times the calibrated half range
  // and a fifth of its frequency, both beyond the margin of 1.25. Judged, and named outside the coverage.
  const auto slow = record("slow.csv", 1.0, 0.025, 0.2, 20.0);
  TempDir d3;
  const auto far = run_mrd("discrepancy --measured " + slow.string() + " --effects force_offset --baseline " +
                               toml.string() + " --no-plots --out " + d3.path().string(),
                           scratch_.path());
  ASSERT_EQ(far.exit_code, 0) << far.err;
  const auto js = nlohmann::json::parse(slurp(d3.path() / "summary.json"));
  EXPECT_NE(js["verdict"], "baseline_mismatch") << js["findings"].dump();
  const auto notes = js["baseline"]["outside_coverage"];
  ASSERT_EQ(notes.size(), 2u) << notes.dump();
  const std::string amplitude = notes[0].get<std::string>();
  const std::string frequency = notes[1].get<std::string>();
  EXPECT_NE(amplitude.find("half range is 25 mm, above the 5 mm the baseline"), std::string::npos) << amplitude;
  EXPECT_NE(frequency.find("frequency is 0.2 Hz, below the 1 Hz the baseline"), std::string::npos) << frequency;
  EXPECT_NE(far.out.find("outside the calibrated coverage"), std::string::npos) << far.out;
}

// --test records are judged after the calibration and choose nothing: the
// same fits and the same choice with or without them. The gaps expected:
// a record of the same damper is described as well as the fitted ones; a
// record of a damper twice as strong has gap |F - 2F| / |2F| = 0.5 against
// a baseline that describes the first damper exactly.
TEST_F(CalibrateCli, TestRecordsAreJudgedButChooseNothing) {
  const auto a = record("a.csv", 0.0);
  const auto b = record("b.csv", 0.5);
  const auto c = record("c.csv", 1.0);
  const auto check = record("check.csv", 0.25, 0.003, 2.0);
  const auto same = record("same.csv", 0.75, 0.008, 0.5, 8.0);
  const auto twice = record("twice.csv", 1.0, 0.005, 1.0, 4.0, 2.0);
  const std::string common = "calibrate --measured " + a.string() + " " + b.string() + " " + c.string() +
                             " --check " + check.string() +
                             " --law bingham --transition tanh --no-lost-motion --no-series-compliance --no-plots --out ";
  TempDir plain;
  const auto r0 = run_mrd(common + plain.path().string(), scratch_.path());
  ASSERT_EQ(r0.exit_code, 0) << r0.err;
  const auto r1 = run_mrd(common + out_.path().string() + " --test " + same.string() + " " + twice.string() +
                              " --floors",
                          scratch_.path());
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  EXPECT_EQ(slurp(plain.path() / "damper.toml"), slurp(out_.path() / "damper.toml"));
  const auto j0 = nlohmann::json::parse(slurp(plain.path() / "summary.json"));
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_EQ(j0["fits"], j["fits"]);
  EXPECT_EQ(j0["choice_reason"], j["choice_reason"]);
  EXPECT_TRUE(j0["test"].empty());
  EXPECT_TRUE(j0["test_gap_rms"].is_null());

  const std::string chosen = j["chosen_law"];
  ASSERT_EQ(j["test"].size(), 2u);
  EXPECT_NE(j["test"][0]["file"].get<std::string>().find("same.csv"), std::string::npos);
  const double g_same = j["test"][0]["gap"][chosen].get<double>();
  const double g_twice = j["test"][1]["gap"][chosen].get<double>();
  EXPECT_LT(g_same, 0.02);
  EXPECT_NEAR(g_twice, 0.5, 0.01);
  EXPECT_NEAR(j["test_gap_rms"].get<double>(), std::sqrt(0.5 * (g_same * g_same + g_twice * g_twice)), 1e-12);
  EXPECT_NE(r1.out.find("twice.csv (test)"), std::string::npos) << r1.out;
  EXPECT_NE(r1.out.find("test records (seen by no choice): RMS gap of the chosen form"), std::string::npos) << r1.out;
  EXPECT_NE(slurp(out_.path() / "report.md").find("twice.csv (test)"), std::string::npos);

  // --floors: the chosen form fitted to each record alone. The twice-as-strong
  // damper's force is the same form with Y and C doubled, so alone it is
  // described as well as a fitted record (below 0.02), where the one
  // calibrated model misses it by 0.5: the floor tells a damper (or a test
  // session) unlike the others from a force the form cannot take.
  EXPECT_TRUE(j0["floors"].is_null());
  const auto& fl = j["floors"];
  ASSERT_EQ(fl["measured"].size(), 3u);
  ASSERT_EQ(fl["check"].size(), 1u);
  ASSERT_EQ(fl["test"].size(), 2u);
  for (const char* set : {"measured", "check", "test"})
    for (const auto& g : fl[set]) EXPECT_LT(g.get<double>(), 0.02) << set;
  // From the calibrated model as its start, a fit to the record alone ends no
  // worse on it (judged at full rate, where the fit saw a thinned record: 1e-3).
  EXPECT_LE(fl["test"][0].get<double>(), g_same + 1e-3);
  EXPECT_NE(r1.out.find("floor:"), std::string::npos) << r1.out;
  EXPECT_EQ(r0.out.find("floor:"), std::string::npos) << r0.out;
  EXPECT_NE(slurp(out_.path() / "report.md").find("the chosen form fitted to the record alone"), std::string::npos);
}

// Without --check, two motions (5 mm at 1 Hz, 2 mm at 3 Hz) judge each
// other: summary.json names the records of each, the notes say so; with
// --no-cross-validation the extras are only reported, as with one motion.
TEST_F(CalibrateCli, TwoMotionsJudgeEachOtherWithoutCheckRecords) {
  const auto a = record("a.csv", 0.0), b = record("b.csv", 1.0);
  const auto c = record("c.csv", 0.0, 0.002, 3.0), d = record("d.csv", 1.0, 0.002, 3.0);
  const std::string common = "calibrate --measured " + a.string() + " " + c.string() + " " + b.string() + " " +
                             d.string() + " --law bingham --transition tanh --no-lost-motion --no-series-compliance --no-plots";
  const auto r = run_mrd(common + " --out " + out_.path().string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  using nlohmann::json;
  const json want = json::array({json::array({a.string(), b.string()}), json::array({c.string(), d.string()})});
  EXPECT_EQ(j["cross_validation"], want) << j["cross_validation"].dump();
  EXPECT_NE(r.out.find("leaving out each of the records' 2 motions"), std::string::npos) << r.out;
  EXPECT_NE(j["choice_reason"].get<std::string>().find("left-out motions"), std::string::npos) << j["choice_reason"];
  // Each record's gap when its motion was left out is reported; with two
  // motions (each fold one motion's fit) the expected gap is the fitted
  // records' largest.
  EXPECT_EQ(j["validity"]["expected_gap_basis"], "calibration_records");
  const auto chosen = std::find_if(j["fits"].begin(), j["fits"].end(),
                                   [&](const json& f) { return f["law"] == j["chosen_law"]; });
  ASSERT_NE(chosen, j["fits"].end()) << j.dump();
  const json& held = (*chosen)["held_out_gaps"];
  ASSERT_EQ(held.size(), 4u) << held.dump();
  double largest = 0.0;
  for (const json& g : (*chosen)["record_gaps"]) largest = std::max(largest, g["gap"].get<double>());
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(held[i]["file"], want[i / 2][i % 2]) << held.dump();
    EXPECT_GT(held[i]["gap"].get<double>(), 0.0) << held.dump();
  }
  EXPECT_EQ(j["validity"]["expected_gap"].get<double>(), largest);
  EXPECT_NE(slurp(out_.path() / "damper.toml").find("expected_gap_basis = \"calibration_records\""),
            std::string::npos);
  TempDir plain;
  const auto n = run_mrd(common + " --no-cross-validation --threads 1 --out " + plain.path().string(), scratch_.path());
  ASSERT_EQ(n.exit_code, 0) << n.err;
  const auto k = nlohmann::json::parse(slurp(plain.path() / "summary.json"));
  EXPECT_TRUE(k["cross_validation"].is_null());
  EXPECT_NE(k["choice_reason"].get<std::string>().find("lowest BIC"), std::string::npos) << k["choice_reason"];
  EXPECT_EQ(k["validity"]["expected_gap_basis"], "calibration_records");
}

TEST_F(CalibrateCli, MissingMeasuredIsAUsageError) {
  const auto r = run_mrd("calibrate --out " + out_.path().string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--measured"), std::string::npos) << r.err;
}

TEST_F(CalibrateCli, BadLawAndBadBaselineFileAreOneLineErrors) {
  const auto a = record("a.csv", 1.0);
  const auto law = run_mrd("calibrate --measured " + a.string() + " --law spring", scratch_.path());
  EXPECT_EQ(law.exit_code, 2);
  EXPECT_NE(law.err.find("--law"), std::string::npos) << law.err;
  const auto shape = run_mrd("calibrate --measured " + a.string() + " --transition cubic", scratch_.path());
  EXPECT_EQ(shape.exit_code, 2);
  EXPECT_NE(shape.err.find("--transition: expected linear, tanh or auto, got 'cubic'"), std::string::npos)
      << shape.err;
  const auto form = run_mrd("calibrate --measured " + a.string() + " --lost-motion-form plastic", scratch_.path());
  EXPECT_EQ(form.exit_code, 2);
  EXPECT_NE(form.err.find("--lost-motion-form: plastic not in {both,share,viscous}"), std::string::npos) << form.err;

  const auto bad = scratch_.path() / "damper.toml";
  std::ofstream(bad) << "[model]\nlaw = \"spring\"\n";
  const auto r = run_mrd("discrepancy --measured " + a.string() + " --baseline " + bad.string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "mrd: error: " + bad.string() + ":2: model.law: expected \"bingham\", \"bouc_wen\" or \"spencer\", got \"spring\"\n");
}

}  // namespace
}  // namespace mrd::test
