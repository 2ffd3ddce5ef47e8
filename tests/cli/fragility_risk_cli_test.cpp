// `mrd fragility` and `mrd risk` as a user runs them: files and fields, and
// bad input (exit status 2, a one-line error naming the file, line and field,
// nothing written).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
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
  // 1 control × 2 idle times × 3 limit states (story_drift only with --drift-m).
  EXPECT_EQ(count_lines(slurp(dir / "fragility.csv")), 1 + 6);
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  EXPECT_EQ(j["runs"], 18);
  EXPECT_EQ(j["runs_computed"], 18);
  EXPECT_EQ(j["runs_resumed"], 0);
  std::set<std::string> states;
  for (const auto& s : j["limit_states"]) states.insert(s["name"].get<std::string>());
  EXPECT_EQ(states, (std::set<std::string>{"stroke", "isolation_gap", "floor_accel"}));
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
    for (const char* ls : {"stroke", "isolation_gap", "floor_accel"}) {
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

// A tiny study: one 4-s stochastic record at one level, one idle time and
// one control mode, one thread, no bootstrap.
std::string tiny_study(const std::string& pga_g) {
  return "fragility --synthetic 1 --duration-s 4 --pga-g " + pga_g +
         " --idle-years 0 --control passive-on --bootstrap 0 --threads 1";
}

TEST_F(FragilityRiskCli, EstimateSaysRunsTimeAndDiskAndWritesNothing) {
  const fs::path dir = out_.path() / "frag";
  const auto r = run_mrd(tiny_study("0.1,0.2") + " --out " + dir.string() + " --estimate", scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("= 2 runs"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("of wall time"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("on disk: runs.csv"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("journal 128 B (64 B per run"), std::string::npos) << r.out;  // 2 runs x 64 bytes
  EXPECT_NE(r.out.find("free on the file system of --out"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir));
  EXPECT_FALSE(fs::exists(out_.path() / "frag.journal"));
  EXPECT_TRUE(fs::is_empty(out_.path()));
  // The same figures are printed before a study that runs.
  const auto run = run_mrd(tiny_study("0.1,0.2") + " --out " + dir.string(), scratch_.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("of wall time"), std::string::npos) << run.out;
  EXPECT_LT(run.out.find("of wall time"), run.out.find("runs computed")) << run.out;
}

// /proc holds no free block: any study is more than its file system can take.
TEST_F(FragilityRiskCli, StudyBeyondTheFreeSpaceOfOutIsRefused) {
  const auto r = run_mrd(tiny_study("0.1") + " --out /proc/mrd-no-space/frag", scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--out: the study would write about"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("which has 0 B free"), std::string::npos) << r.err;
}

// 1000 records of 600 s at 1e-5 s: 1000 x 6e7 samples x 8 bytes = 480 GB of
// records in every process, refused before any is made.
TEST_F(FragilityRiskCli, StudyBeyondTheMachinesMemoryIsRefused) {
  const fs::path dir = out_.path() / "frag";
  const auto r = run_mrd("fragility --synthetic 1000 --duration-s 600 --step-s 1e-5 --pga-g 0.2 --idle-years 0 "
                         "--control passive-on --bootstrap 0 --threads 1 --out " + dir.string(),
                         scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("would take about 480 GB of memory"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
}

// 50 g: far beyond the damper's stroke and force; 0.01 g: within both.
TEST_F(FragilityRiskCli, RunsBeyondTheModelAreWarnedAndListed) {
  const fs::path dir = out_.path() / "frag";
  auto r = run_mrd(tiny_study("50") + " --out " + dir.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("mrd fragility: warning: in 1 of 1 runs: peak stroke"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("mrd fragility: warning: in 1 of 1 runs: peak damper force"), std::string::npos) << r.err;
  auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  ASSERT_EQ(j["warnings"].size(), 2u);
  EXPECT_NE(j["warnings"][0].get<std::string>().find("peak stroke"), std::string::npos);

  r = run_mrd(tiny_study("0.01") + " --out " + dir.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  j = nlohmann::json::parse(slurp(dir / "summary.json"));
  EXPECT_TRUE(j["warnings"].empty());
}

/// A 2-s record in the shared CSV format: 1 m/s² at 1 Hz, 0.01 s apart.
void write_record(const fs::path& path) {
  std::ofstream f(path);
  f << "time_s,accel_m_s2\n";
  for (int k = 0; k <= 200; ++k) f << k * 0.01 << "," << std::sin(2.0 * 3.141592653589793 * k * 0.01) << "\n";
}

// Hidden names are skipped even when they are junk; a record name that is a
// FIFO is an error naming it (it used to be skipped without a word).
TEST_F(FragilityRiskCli, RecordsFolderSkipsHiddenNamesAndRefusesNonFileRecords) {
  const fs::path records = scratch_.path() / "records";
  fs::create_directory(records);
  write_record(records / "quake.csv");
  std::ofstream(records / ".quake.csv.swp") << "junk";
  std::ofstream(records / ".junk.csv") << "not a record at all";
  const fs::path dir = out_.path() / "frag";
  const std::string study = "fragility --records " + records.string() +
                            " --pga-g 0.1 --idle-years 0 --control passive-on --bootstrap 0 --threads 1 --out " +
                            dir.string();
  auto r = run_mrd(study, scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "summary.json"))["records"].size(), 1u);

  ASSERT_EQ(::mkfifo((records / "aftershock.CSV").c_str(), 0600), 0);
  r = run_mrd(study, scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("aftershock.CSV' is a FIFO"), std::string::npos) << r.err;
}

// Curves fitted over 0.2-1.5 g against a hazard of 0.001-0.01 g: all of the
// result is extrapolated, and said so.
TEST_F(FragilityRiskCli, RiskWarnsWhenTheHazardLiesOutsideTheFittedLevels) {
  const fs::path frag = scratch_.path() / "fragility.csv";
  std::ofstream(frag) << "control,limit_state,threshold,idle_years,status,median_pga_g,beta,median_pga_g_p05,"
                         "median_pga_g_p95,beta_p05,beta_p95,runs,exceedances,pga_g_min,pga_g_max\n"
                         "passive-on,stroke,0.2921,0,fitted,0.9,0.5,,,,,10,3,0.2,1.5\n"
                         "passive-on,stroke,0.2921,1,fitted,0.5,0.5,,,,,10,4,0.2,1.5\n";
  const fs::path hazard = scratch_.path() / "site.csv";
  std::ofstream(hazard) << "pga_g,annual_frequency\n0.001,1\n0.01,0.1\n";
  const fs::path out = out_.path() / "risk";
  const auto r = run_mrd("risk --fragility " + frag.string() + " --hazard " + hazard.string() +
                             " --years 2 --out " + out.string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("mrd risk: warning: the hazard curve (0.001-0.01 g) reaches beyond the fragility's fitted PGA "
                       "levels (0.2-1.5 g): 100 % of the annual exceedance of stroke"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("mrd risk: warning: the ratios to always-fully-mixed for stroke rest mainly on extrapolated"),
            std::string::npos)
      << r.err;
  const auto s = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_GE(s["warnings"].size(), 2u);
  EXPECT_EQ(s["extrapolated_fraction_at_idle"]["stroke"][0], 1.0);
  EXPECT_NE(slurp(out / "report.md").find("rest mainly on extrapolated curves"), std::string::npos);
}

}  // namespace
}  // namespace mrd::test
