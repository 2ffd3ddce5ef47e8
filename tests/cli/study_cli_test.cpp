// `mrd study`: the report and summary of the chapter-6 study (without the
// sweep, which `mrd sweep` tests cover), and bad input (exit 2, nothing written).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

class StudyCli : public ::testing::Test {
 protected:
  TempDir scratch_;
  TempDir out_;
};

TEST_F(StudyCli, WritesReportSummaryAndOnePlotPerRecordAndMode) {
  const auto r = run_mrd("study --no-sweep --out " + out_.path().string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_EQ(j["report"], "report.md");
  EXPECT_TRUE(j["sweep"].is_null());
  EXPECT_NEAR(j["max_settling_time_years"].get<double>(), 0.8531, 0.005 * 0.8531);  // Eq. 5.4
  ASSERT_TRUE(j["runs"].is_array());
  ASSERT_FALSE(j["runs"].empty());
  EXPECT_EQ(j["runs"].size() % 4, 0u);  // four records (or four synthetic motions) x the modes
  const std::string report = slurp(out_.path() / "report.md");
  for (const auto& run : j["runs"]) {
    for (const char* phase : {"fully_mixed", "idle"}) {
      for (const char* key : {"peak_base_displacement_m", "peak_damper_force_kn", "peak_superstructure_accel_m_s2",
                              "sq"}) {
        ASSERT_TRUE(run[phase][key].is_number()) << phase << " " << key;
      }
    }
    // Fully mixed at the start of the record; 2.5 years idle is past T_max (Eq. 5.5).
    EXPECT_EQ(run["fully_mixed"]["sq"].get<double>(), 0.0);
    EXPECT_EQ(run["idle"]["sq"].get<double>(), 1.0);
    const std::string png = run["plot"];
    const bool drawn = fs::exists(out_.path() / png);
    EXPECT_TRUE(drawn || r.err.find("plot not written") != std::string::npos) << png;
    if (drawn) {
      EXPECT_NE(report.find("![" + png + "](" + png + ")"), std::string::npos) << png;
    }
  }
  for (const char* section : {"## Structure (Table 6.1, Fig. 6.2)", "## Damper after idle time (§5.3)",
                              "## Earthquakes at 0.1127 g: fully mixed against 2.5 years idle", "## Model"}) {
    EXPECT_NE(report.find(section), std::string::npos) << section;
  }
  EXPECT_EQ(report.find("## Idle-time sweep"), std::string::npos);
  EXPECT_FALSE(fs::exists(out_.path() / "sweep"));
  EXPECT_NE(r.out.find("wrote " + out_.path().string() + "/report.md\n"), std::string::npos) << r.out;
}

TEST_F(StudyCli, BadPgaIsAOneLineErrorAndWritesNothing) {
  const fs::path out = out_.path() / "study";
  const auto r = run_mrd("study --pga-g 0 --out " + out.string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--pga-g"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace mrd::test
