// `mrd synth` and `mrd discrepancy` run as a user runs them: outputs, a
// hidden effect named from a generated record (CSV and .mat), and bad input
// (exit 2, one line naming file, line and column, nothing written).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "host_sim/discrepancy/effects.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

class DiscrepancyCli : public ::testing::Test {
 protected:
  TempDir scratch_;
  TempDir out_;
  fs::path write(const std::string& name, const std::string& content) {
    const auto p = scratch_.path() / name;
    std::ofstream(p) << content;
    return p;
  }
};

TEST_F(DiscrepancyCli, SynthThenDiscrepancyNamesTheHiddenEffect) {
  const auto gen = scratch_.path() / "gen";
  const auto s = run_mrd("synth --effects time_delay --params 0.015 --seed 3 --duration-s 12 --out " + gen.string(),
                         scratch_.path());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const auto truth = nlohmann::json::parse(slurp(gen / "summary.json"));
  EXPECT_EQ(truth["effects"], nlohmann::json::array({"time_delay"}));
  EXPECT_DOUBLE_EQ(truth["parameters"]["time_delay"]["delay_s"].get<double>(), 0.015);
  // 12 s at 1 kHz: 12001 rows and the header.
  EXPECT_EQ(count_lines(slurp(gen / "measured.csv")), 12002);

  const auto r = run_mrd("discrepancy --measured " + (gen / "measured.csv").string() + " --out " + out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_EQ(j["effects"], nlohmann::json::array({"time_delay"}));
  EXPECT_NEAR(j["parameters"]["time_delay"]["delay_s"].get<double>(), 0.015, 0.001);
  EXPECT_LT(j["gap_after"].get<double>(), 0.5 * j["gap_before"].get<double>());
  EXPECT_EQ(j["verdict"], "explained");
  EXPECT_LT(j["gap_validation_after"].get<double>(), 0.5 * j["gap_validation_before"].get<double>());
  ASSERT_EQ(j["candidates"].size(), discrepancy::kEffectCount);
  for (const auto& c : j["candidates"]) {
    EXPECT_TRUE(c.contains("name"));
    EXPECT_TRUE(c.contains("score"));
    EXPECT_TRUE(c["parameters"].is_object());
  }
  ASSERT_FALSE(j["regions"].empty());
  EXPECT_TRUE(j["regions"][0].contains("share_of_gap_before"));
  for (const char* f : {"fit.csv", "report.md", "force_time.png", "residual.png", "loops.png"}) {
    EXPECT_TRUE(fs::exists(out_.path() / f)) << f;
  }
  EXPECT_EQ(count_lines(slurp(out_.path() / "fit.csv")), 12002);
}

TEST_F(DiscrepancyCli, MatInputAndNoneOnTheBaseline) {
  const auto gen = scratch_.path() / "gen";
  const auto s =
      run_mrd("synth --effects none --seed 4 --duration-s 8 --format mat --out " + gen.string(), scratch_.path());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  ASSERT_TRUE(fs::exists(gen / "measured.mat"));
  const auto r = run_mrd("discrepancy --no-plots --measured " + (gen / "measured.mat").string() + " --out " +
                             out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_TRUE(j["effects"].empty());
  EXPECT_EQ(j["verdict"], "none");
  EXPECT_EQ(j["rounds"][0]["chosen"], "none");
  EXPECT_DOUBLE_EQ(j["gap_after"].get<double>(), j["gap_before"].get<double>());
}

// The laboratory damper of ../shared/lab_data (about 1.5-1.9 kN at 1 A, its README) against the
// thesis's 200 kN damper: a hundredfold force scale is no effect of the catalogue.
TEST_F(DiscrepancyCli, ThesisBaselineOnTheLabDamperIsAMismatch) {
  const auto rec = fs::path(MRD_SHARED_DIR) / "lab_data" / "quiroz_utfsm" / "5mm_3Hz_1p00A.csv";
  ASSERT_TRUE(fs::exists(rec)) << rec;
  const auto r = run_mrd("discrepancy --no-plots --measured " + rec.string() + " --out " + out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_EQ(j["verdict"], "baseline_mismatch");
  EXPECT_TRUE(j["effects"].empty());
  EXPECT_TRUE(j["rounds"].empty());  // nothing fitted to hide the mismatch
  const double ratio = j["baseline"]["force_ratio"].get<double>();
  EXPECT_GT(ratio, 0.005);
  EXPECT_LT(ratio, 0.02);
  EXPECT_NE(r.out.find("force scale"), std::string::npos) << r.out;
}

std::string record(int rows, const std::string& header = "time_s,displacement_m,current_cmd_A,force_N") {
  std::string s = header + "\n";
  for (int k = 0; k < rows; ++k) {
    s += std::to_string(k * 1e-3) + "," + std::to_string(0.01 * std::sin(k * 6.283e-3)) + ",2," +
         std::to_string(1e5 * std::cos(k * 6.283e-3)) + "\n";
  }
  return s;
}

struct BadInput {
  const char* name;
  std::string content;
  const char* must_mention;
};

class DiscrepancyCliBad : public DiscrepancyCli, public ::testing::WithParamInterface<BadInput> {};

TEST_P(DiscrepancyCliBad, ExitTwoWithOneLineNamingFileLineAndColumn) {
  const auto& c = GetParam();
  const auto f = write("lab.csv", c.content);
  const auto r = run_mrd("discrepancy --measured " + f.string() + " --out " + (out_.path() / "o").string(),
                         scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("lab.csv"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(c.must_mention), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out_.path() / "o"));
}

std::string replace_line(std::string text, int line_no, const std::string& repl) {
  std::size_t pos = 0;
  for (int l = 1; l < line_no; ++l) pos = text.find('\n', pos) + 1;
  return text.replace(pos, text.find('\n', pos) - pos, repl);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, DiscrepancyCliBad,
    ::testing::Values(BadInput{"MissingColumn", "time_s,displacement_m,force_N\n0,0,0\n", "lab.csv:1: missing column"},
                      BadInput{"NonMonotonicTime", replace_line(record(1500), 200, "0.1,0,2,0"), "lab.csv:200: column 'time_s'"},
                      BadInput{"NaN", replace_line(record(1500), 33, "0.031,nan,2,0"), "lab.csv:33: column 'displacement_m'"},
                      BadInput{"TooShort", record(100), "lab.csv:101: column 'time_s'"},
                      BadInput{"UnknownUnit", record(1500, "time_s,displacement_m,current_cmd_A,force_lb"),
                               "column 4 'force_lb'"}),
    [](const auto& p) { return std::string(p.param.name); });

TEST_F(DiscrepancyCli, MissingFile) {
  const auto r = run_mrd("discrepancy --measured " + (scratch_.path() / "nope.csv").string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nope.csv"), std::string::npos);
}

TEST_F(DiscrepancyCli, UnknownEffectInCatalogue) {
  const auto f = write("lab.csv", record(1500));
  const auto r = run_mrd("discrepancy --effects backlash,warp_drive --measured " + f.string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("warp_drive"), std::string::npos) << r.err;
}

TEST_F(DiscrepancyCli, SynthRejectsParamsOutsideBounds) {
  const auto r = run_mrd("synth --effects coil_lag --params 20 --out " + out_.path().string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("tau_scale"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out_.path() / "summary.json"));
}

}  // namespace
}  // namespace mrd::test
