// `mrd fragility` and `mrd risk` as a user runs them: files and fields, and
// bad input (exit status 2, a one-line error naming the file, line and field,
// nothing written).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

class FragilityRiskCli : public ::testing::Test {
 protected:
  TempDir scratch_;
  TempDir out_;
};

constexpr const char* kSmallStudy =
    "fragility --synthetic 3 --duration-s 8 --pga-g 0.2,0.6,1.5 --idle-years 0,1 --control passive-on "
    "--bootstrap 10 --threads 2";

TEST_F(FragilityRiskCli, FragilityWritesRunsCurvesAndSummary) {
  const fs::path dir = out_.path() / "frag";
  const auto r = run_mrd(std::string(kSmallStudy) + " --out " + dir.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("left"), std::string::npos) << "progress with the time left on stderr";
  const std::string runs = slurp(dir / "runs.csv");
  EXPECT_EQ(count_lines(runs), 1 + 3 * 3 * 2);
  EXPECT_EQ(runs.substr(0, runs.find('\n')),
            "run,record,control,idle_years,pga_g,peak_base_displacement_m,peak_damper_force_kn,"
            "peak_floor_accel_m_s2,peak_base_accel_m_s2,peak_story_drift_m");
  // 1 control × 2 idle times × 4 limit states.
  EXPECT_EQ(count_lines(slurp(dir / "fragility.csv")), 1 + 8);
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  EXPECT_EQ(j["runs"], 18);
  EXPECT_EQ(j["runs_computed"], 18);
  EXPECT_EQ(j["runs_resumed"], 0);
  std::set<std::string> states;
  for (const auto& s : j["limit_states"]) states.insert(s["name"].get<std::string>());
  EXPECT_EQ(states, (std::set<std::string>{"stroke", "isolation_gap", "floor_accel", "story_drift"}));
  EXPECT_DOUBLE_EQ(j["limit_states"][0]["threshold"].get<double>(), 0.2921);
  EXPECT_GT(j["runs_per_core_hour"].get<double>(), 0.0);
  EXPECT_FALSE(fs::exists(out_.path() / "frag.journal"));

  // mrd risk on those curves: the per-policy table.
  const fs::path risk = out_.path() / "risk";
  const auto rr = run_mrd("risk --fragility " + dir.string() + " --years 5 --out " + risk.string(), scratch_.path());
  ASSERT_EQ(rr.exit_code, 0) << rr.err;
  const auto s = nlohmann::json::parse(slurp(risk / "summary.json"));
  ASSERT_EQ(s["policies"].size(), 4u);
  std::set<std::string> names;
  for (const auto& p : s["policies"]) {
    names.insert(p["name"].get<std::string>());
    EXPECT_TRUE(p.contains("cycles_per_year"));
    for (const char* ls : {"stroke", "isolation_gap", "floor_accel", "story_drift"}) {
      EXPECT_TRUE(p["annual_exceedance"].contains(ls)) << p["name"] << " " << ls;
    }
  }
  EXPECT_EQ(names, (std::set<std::string>{"none", "fixed-interval", "estimator", "always-fully-mixed"}));
  EXPECT_TRUE(fs::exists(risk / "risk.csv"));
  EXPECT_NE(slurp(risk / "report.md").find("| always-fully-mixed |"), std::string::npos);
}

TEST_F(FragilityRiskCli, BadOptionsFailBeforeAnyWork) {
  const fs::path dir = out_.path() / "frag";
  auto r = run_mrd("fragility --synthetic 2 --pga-g 0.2,-1 --out " + dir.string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--pga-g"), std::string::npos) << r.err;
  r = run_mrd("fragility --synthetic 2 --records /nonexistent --out " + dir.string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  r = run_mrd("fragility --records /nonexistent --out " + dir.string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is not a folder"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
}

TEST_F(FragilityRiskCli, BadHazardAndFragilityFilesNameTheLine) {
  const fs::path frag = scratch_.path() / "fragility.csv";
  std::ofstream(frag) << "control,limit_state,threshold,idle_years,status,median_pga_g,beta,median_pga_g_p05,"
                         "median_pga_g_p95,beta_p05,beta_p95,runs,exceedances\n"
                         "passive-on,stroke,0.2921,0,fitted,0.9,0.5,,,,,10,3\n"
                         "passive-on,stroke,0.2921,1,fitted,0.7,0.5,,,,,10,4\n";
  const fs::path hazard = scratch_.path() / "site.csv";
  std::ofstream(hazard) << "pga_g,annual_frequency\n0.1,0.01\n0.2,zero\n";
  const fs::path out = out_.path() / "risk";
  auto r =
      run_mrd("risk --fragility " + frag.string() + " --hazard " + hazard.string() + " --years 2 --out " + out.string(),
              scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("site.csv:3: field 'annual_frequency': expected a number, got 'zero'"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));

  std::ofstream(hazard) << "pga_g,annual_frequency\n0.1,0.01\n0.5,0.0005\n";
  r = run_mrd("risk --fragility " + frag.string() + " --hazard " + hazard.string() + " --years 2 --out " + out.string(),
              scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(s["control"], "passive-on");
  EXPECT_NE(s["hazard"].get<std::string>().find("site.csv"), std::string::npos);

  std::ofstream(frag) << "control,limit_state,threshold,idle_years,status,median_pga_g,beta,median_pga_g_p05,"
                         "median_pga_g_p95,beta_p05,beta_p95,runs,exceedances\n"
                         "passive-on,stroke,0.2921,0,fitted,0.9,0.5,,,,,10,3\n"
                         "passive-on,stroke,0.2921,1,fitted,,0.5,,,,,10,4\n";
  r = run_mrd("risk --fragility " + frag.string() + " --years 2", scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("fragility.csv:3: field 'median_pga_g'"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace mrd::test
