// `mrd fragility --drift-m`: the story_drift limit state is opt-in. Without
// the option the study is the thesis's three limit states; with it the
// story_drift curves are added and every other curve, bootstrap band
// included, is what it was without it. `mrd risk` reads both shapes, and a
// journal kept without the option resumes with it.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

class FragilityDriftCli : public ::testing::Test {
 protected:
  TempDir scratch_;
  TempDir out_;
};

// 3 records x 3 PGAs x 2 idle times x 1 control mode = 18 runs, with
// bootstrap bands. Under a seed numbering that counted story_drift's curves
// among the others, the idle-1 curves of stroke, isolation_gap and
// floor_accel would take other seeds than without it.
constexpr const char* kStudy =
    "fragility --synthetic 3 --duration-s 8 --pga-g 0.2,0.6,1.5 --idle-years 0,1 --control passive-on "
    "--bootstrap 20 --seed 3 --threads 2";

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> v;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) v.push_back(l);
  return v;
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> v;
  std::istringstream in(line);
  for (std::string c; std::getline(in, c, ',');) v.push_back(c);
  return v;
}

/// The header and the rows of a fragility.csv or fragility_curves.csv
/// (limit_state in the second column) whose limit state is not story_drift.
std::vector<std::string> without_story_drift(const std::string& text) {
  std::vector<std::string> kept;
  for (const auto& l : lines(text)) {
    if (cells(l).at(1) != "story_drift") kept.push_back(l);
  }
  return kept;
}

std::set<std::string> limit_states_of(const std::string& fragility_csv) {
  std::set<std::string> states;
  const auto rows = lines(fragility_csv);
  for (std::size_t i = 1; i < rows.size(); ++i) states.insert(cells(rows[i]).at(1));
  return states;
}

const std::set<std::string> kThesisStates{"stroke", "isolation_gap", "floor_accel"};

TEST_F(FragilityDriftCli, WithoutDriftMOnlyTheThesisLimitStates) {
  const fs::path dir = out_.path() / "frag";
  const auto r = run_mrd(std::string(kStudy) + " --out " + dir.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = slurp(dir / "fragility.csv");
  EXPECT_EQ(limit_states_of(csv), kThesisStates);
  EXPECT_EQ(count_lines(csv), 1 + 2 * 3);  // 2 idle times x 3 limit states
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  std::set<std::string> listed;
  for (const auto& s : j.at("limit_states")) listed.insert(s.at("name").get<std::string>());
  EXPECT_EQ(listed, kThesisStates);
  for (const auto& name : entries(dir)) EXPECT_EQ(name.find("story_drift"), std::string::npos) << name;
}

TEST_F(FragilityDriftCli, DriftMAddsStoryDriftAndMovesNoOtherCurve) {
  const fs::path plain = out_.path() / "plain", drift = out_.path() / "drift";
  auto r = run_mrd(std::string(kStudy) + " --out " + plain.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_mrd(std::string(kStudy) + " --drift-m 0.0005 --out " + drift.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const std::string plain_csv = slurp(plain / "fragility.csv"), drift_csv = slurp(drift / "fragility.csv");
  std::set<std::string> with_drift = kThesisStates;
  with_drift.insert("story_drift");
  EXPECT_EQ(limit_states_of(drift_csv), with_drift);
  EXPECT_EQ(count_lines(drift_csv), 1 + 2 * 4);
  // The three states' rows, bootstrap percentiles included, are the same bytes.
  EXPECT_EQ(without_story_drift(drift_csv), lines(plain_csv));
  EXPECT_EQ(without_story_drift(slurp(drift / "fragility_curves.csv")), lines(slurp(plain / "fragility_curves.csv")));
  EXPECT_EQ(slurp(drift / "runs.csv"), slurp(plain / "runs.csv"));
  for (const auto& l : lines(drift_csv)) {
    const auto c = cells(l);
    if (c.at(1) == "story_drift") {
      EXPECT_EQ(std::stod(c.at(2)), 0.0005) << l;
    }
  }

  // The comparison bites only if some band of an idle-1 curve (whose seed
  // an interleaved numbering would move) is not a single point.
  bool spread = false;
  const auto header = cells(lines(plain_csv).at(0));
  ASSERT_EQ(header.at(3), "idle_years");
  ASSERT_EQ(header.at(7), "median_pga_g_p05");
  ASSERT_EQ(header.at(8), "median_pga_g_p95");
  for (const auto& l : lines(plain_csv)) {
    const auto c = cells(l);
    if (c.at(3) == "1" && c.at(7) != c.at(8)) spread = true;
  }
  EXPECT_TRUE(spread) << plain_csv;

  // The other files but summary.json (runs.csv, the plots) are the same; the plots added are story_drift's.
  for (const auto& name : entries(plain)) {
    if (name == "summary.json" || name == "fragility.csv" || name == "fragility_curves.csv") continue;
    EXPECT_EQ(slurp(drift / name), slurp(plain / name)) << name;
  }
  for (const auto& name : entries(drift)) {
    if (!entries(plain).count(name)) {
      EXPECT_NE(name.find("story_drift"), std::string::npos) << name;
    }
  }
  const auto pj = nlohmann::json::parse(slurp(plain / "summary.json"));
  const auto dj = nlohmann::json::parse(slurp(drift / "summary.json"));
  nlohmann::json kept = nlohmann::json::array();
  for (const auto& c : dj.at("curves")) {
    if (c.at("limit_state") != "story_drift") kept.push_back(c);
  }
  EXPECT_EQ(kept, pj.at("curves"));
  EXPECT_EQ(dj.at("limit_states").size(), 4u);
  EXPECT_EQ(dj.at("limit_states")[3].at("name"), "story_drift");

  // mrd risk reads both: the three states' annual rates are equal, story_drift's added.
  const fs::path plain_risk = out_.path() / "plain-risk", drift_risk = out_.path() / "drift-risk";
  r = run_mrd("risk --fragility " + plain.string() + " --years 5 --out " + plain_risk.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_mrd("risk --fragility " + drift.string() + " --years 5 --out " + drift_risk.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto pr = nlohmann::json::parse(slurp(plain_risk / "summary.json"));
  const auto dr = nlohmann::json::parse(slurp(drift_risk / "summary.json"));
  ASSERT_EQ(pr.at("policies").size(), dr.at("policies").size());
  for (std::size_t i = 0; i < pr.at("policies").size(); ++i) {
    const auto& p = pr.at("policies")[i];
    const auto& d = dr.at("policies")[i];
    EXPECT_FALSE(p.at("annual_exceedance").contains("story_drift"));
    EXPECT_TRUE(d.at("annual_exceedance").contains("story_drift")) << d.at("name");
    for (const auto& ls : kThesisStates) {
      EXPECT_EQ(d.at("annual_exceedance").at(ls), p.at("annual_exceedance").at(ls)) << d.at("name") << " " << ls;
    }
  }
}

TEST_F(FragilityDriftCli, DriftMMustBePositive) {
  for (const char* bad : {"0", "-0.02"}) {
    const fs::path dir = out_.path() / "frag";
    const auto r =
        run_mrd(std::string(kStudy) + " --drift-m " + bad + " --out " + dir.string(), scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("--drift-m"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir)) << bad;
    EXPECT_FALSE(fs::exists(out_.path() / "frag.journal")) << bad;
  }
}

TEST_F(FragilityDriftCli, HelpSaysTheDriftLimitHasNoDefault) {
  const auto r = run_mrd("fragility --help", scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("only with --drift-m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no default"), std::string::npos) << r.out;
}

// A study killed (SIGKILL) once 16 runs are in its journal, then run again
// with --drift-m: the journal's runs are taken (the limit states are not part
// of the study's fingerprint) and the outputs are an uninterrupted
// --drift-m run's.
TEST_F(FragilityDriftCli, AJournalKeptWithoutDriftMResumesWithIt) {
  const std::string study =
      "fragility --synthetic 6 --duration-s 20 --pga-g 0.1,0.3,0.6,1.0 --idle-years 0,0.5,1 "
      "--control passive-on,semi-active --bootstrap 10 --seed 5 --threads 1";
  const int total = 6 * 4 * 3 * 2;
  const fs::path whole = out_.path() / "whole", killed = out_.path() / "killed";
  const fs::path journal = out_.path() / "killed.journal";
  auto r = run_mrd(study + " --drift-m 0.001 --out " + whole.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const fs::path script = scratch_.path() / "kill.sh";
  std::ofstream(script) << std::string(MRD_BINARY) << " " << study << " --out " << killed.string()
                        << " >/dev/null 2>&1 &\n"
                        << "pid=$!\n"
                        << "for _ in $(seq 1 3000); do\n"
                        << "  size=$( (cat " << journal.string() << "/part-*.journal 2>/dev/null || true) | wc -c)\n"
                        << "  [ \"$size\" -ge " << 16 * 64 << " ] && break\n"
                        << "  sleep 0.01\n"
                        << "done\n"
                        << "kill -9 $pid\n"
                        << "wait $pid\n"
                        << "exit 0\n";
  ASSERT_EQ(run_command("bash " + script.string(), scratch_.path()).exit_code, 0);
  ASSERT_FALSE(fs::exists(killed / "summary.json")) << "the study finished before it was killed";
  std::uintmax_t bytes = 0;
  for (const auto& e : fs::directory_iterator(journal)) {
    if (e.path().extension() == ".journal") bytes += fs::file_size(e.path());
  }
  const auto kept = static_cast<int>(bytes / 64);
  ASSERT_GE(kept, 16);
  ASSERT_LT(kept, total);

  r = run_mrd(study + " --drift-m 0.001 --out " + killed.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(killed / "summary.json"));
  EXPECT_GE(j.at("runs_resumed").get<int>(), kept - 1);  // a torn last record is run again
  EXPECT_LT(j.at("runs_resumed").get<int>(), total);
  for (const char* f : {"runs.csv", "fragility.csv", "fragility_curves.csv"}) {
    EXPECT_EQ(slurp(killed / f), slurp(whole / f)) << f;
  }
  EXPECT_EQ(limit_states_of(slurp(killed / "fragility.csv")).count("story_drift"), 1u);
  EXPECT_FALSE(fs::exists(journal));
}

}  // namespace
}  // namespace mrd::test
