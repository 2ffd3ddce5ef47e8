// `mrd settle`: output fields, help, and bad input (exit status 2, one-line
// error, nothing half-written).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

class SettleCli : public ::testing::Test {
 protected:
  TempDir scratch_;
  TempDir out_;
};

TEST_F(SettleCli, WritesAllFieldsWithThesisValues) {
  const auto r = run_mrd("settle --idle-years 0.25 --out " + out_.path().string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  for (const char* key : {"settling_velocity_m_s", "hindered_settling_velocity_m_s", "settled_layer_height_m",
                          "max_settling_time_years", "sq", "a_pr", "b_pr", "c_pr"}) {
    ASSERT_TRUE(j.contains(key)) << key;
    ASSERT_TRUE(j[key].is_number()) << key;
  }
  // Thesis: 0.8531 years (§6.5), layer 0.0831 m (Table 5.5).
  EXPECT_NEAR(j["max_settling_time_years"].get<double>(), 0.8531, 0.005 * 0.8531);
  EXPECT_NEAR(j["settled_layer_height_m"].get<double>(), 0.0831, 0.0005);
  // SQ = 0.25 / 0.8531 = 0.2930 (Eq. 5.5), within the 0.5 % of the max time.
  const double sq = j["sq"].get<double>();
  EXPECT_NEAR(sq, 0.25 / 0.8531, 0.005 * 0.2930);
  // Eq. 5.6 at that SQ.
  EXPECT_NEAR(j["a_pr"].get<double>(), 0.10 + 0.90 * std::exp(-7.0 * sq), 1e-12);
  // The table names its quantities.
  EXPECT_NE(r.out.find("maximum settling time"), std::string::npos);
}

TEST_F(SettleCli, SqSaturatesPastMaxSettlingTime) {
  const auto r = run_mrd("settle --idle-years 2.5 --out " + out_.path().string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_DOUBLE_EQ(j["sq"].get<double>(), 1.0);
  EXPECT_NEAR(j["a_pr"].get<double>(), 0.100821, 1e-6);  // Eq. 5.6 at SQ = 1, by hand
}

TEST_F(SettleCli, HelpExplainsFieldsAndUnits) {
  const auto top = run_mrd("--help", scratch_.path());
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_NE(top.out.find("settle"), std::string::npos);
  const auto r = run_mrd("settle --help", scratch_.path());
  EXPECT_EQ(r.exit_code, 0);
  for (const char* key : {"--idle-years", "--out", "max_settling_time_years", "m/s", "Eq. 5.5", "c_pr"}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  }
}

struct BadCase {
  const char* name;
  const char* args;
  const char* must_mention;
};

class SettleCliBadInput : public SettleCli, public ::testing::WithParamInterface<BadCase> {};

TEST_P(SettleCliBadInput, OneLineErrorExitTwoNothingWritten) {
  const auto& c = GetParam();
  // A summary from an earlier good run must survive a bad one untouched.
  const auto summary = out_.path() / "summary.json";
  { std::ofstream(summary) << "{\"earlier\": true}\n"; }
  { std::ofstream(out_.path() / ".mrd-result") << "an mrd result\n"; }
  const auto r = run_mrd(std::string("settle ") + c.args + " --out " + out_.path().string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(c.must_mention), std::string::npos) << r.err;
  EXPECT_EQ(slurp(summary), "{\"earlier\": true}\n");
  for (const auto& e : fs::directory_iterator(out_.path())) {
    EXPECT_TRUE(e.path().filename() == "summary.json" || e.path().filename() == ".mrd-result")
        << "left behind: " << e.path();
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, SettleCliBadInput,
                         ::testing::Values(BadCase{"Negative", "--idle-years -1", "--idle-years"},
                                           BadCase{"NaN", "--idle-years nan", "--idle-years"},
                                           BadCase{"Infinite", "--idle-years inf", "--idle-years"},
                                           BadCase{"NotANumber", "--idle-years abc", "abc"},
                                           BadCase{"UnknownOption", "--idle-years 1 --frobnicate", "frobnicate"},
                                           BadCase{"Missing", "", "--idle-years"}),
                         [](const auto& p) { return std::string(p.param.name); });

TEST_F(SettleCli, UnwritableOutIsAnError) {
  const auto file = out_.path() / "a-file";
  { std::ofstream(file) << "x"; }
  for (const std::string& dir : {(file / "sub").string(), file.string(), std::string("/proc/mrd-cannot-write")}) {
    const auto r = run_mrd("settle --idle-years 0.5 --out " + dir, scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << dir;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
  }
}

TEST_F(SettleCli, UnknownSubcommandIsAnError) {
  const auto r = run_mrd("frobnicate", scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
}

}  // namespace
}  // namespace mrd::test
