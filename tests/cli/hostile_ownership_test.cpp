// What `mrd` may replace or remove: only what it made. A journal that is a
// folder of the user's, the --out folder, a parent of it or an older result is
// refused before any work and left as it was; `--out D/` keeps its journal
// beside D, never inside it; an --out that is, contains or lies inside an
// input is refused; list options with empty or repeated items are refused.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <thread>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

/// A fragility study of one short stochastic motion: a few runs, well under a second.
const std::string kTinyStudy =
    "fragility --synthetic 1 --duration-s 2 --pga-g 0.1 --idle-years 0 --control passive-on --bootstrap 0 "
    "--threads 1";

class Ownership : public ::testing::Test {
 protected:
  void SetUp() override {
    result_ = scratch_.path() / "result";
    const auto r = run_mrd(kTinyStudy + " --out " + result_.string(), scratch_.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_TRUE(fs::exists(result_ / "summary.json"));
    result_before_ = snapshot(result_);
    mine_ = scratch_.path() / "mine";
    fs::create_directories(mine_ / "chapter");
    std::ofstream(mine_ / "thesis.tex") << "my work";
    std::ofstream(mine_ / "chapter" / "one.tex") << "chapter one";
    mine_before_ = snapshot(mine_);
  }

  /// Runs `args` in the scratch folder; expects exit 2, one line naming `named`, and `result` and `mine` unchanged.
  void expect_refused(const std::string& args, const std::string& named, const fs::path& cwd = {}) {
    SCOPED_TRACE(args);
    const auto r = run_mrd_in(args, cwd.empty() ? scratch_.path() : cwd);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << r.err;
    EXPECT_TRUE(snapshot(result_) == result_before_) << "the previous result changed";
    EXPECT_TRUE(snapshot(mine_) == mine_before_) << "the user's folder changed";
  }

  /// run_mrd with `cwd` as the working folder (the runner's captured output stays in the scratch folder).
  RunResult run_mrd_in(const std::string& args, const fs::path& cwd) { return run_mrd(args, scratch_.path(), cwd); }

  TempDir scratch_;
  fs::path result_, mine_;
  Snapshot result_before_, mine_before_;
};

TEST_F(Ownership, AJournalThatIsNotOneOfMrdsIsRefusedAndKept) {
  const std::string out = " --out " + (scratch_.path() / "new").string();
  // A folder of the user's, with files and a subfolder.
  expect_refused(kTinyStudy + " --journal " + mine_.string() + out, "--journal");
  // The --out folder itself, an older result given as the journal, a parent of --out.
  expect_refused(kTinyStudy + " --journal " + result_.string() + " --out " + result_.string(), "--journal");
  expect_refused(kTinyStudy + " --journal " + result_.string() + out, "--journal");
  expect_refused(kTinyStudy + " --journal " + mine_.string() + " --out " + (mine_ / "sub").string(), "--journal");
  // A relative path into the working folder (the scratch folder holds the user's files).
  expect_refused(kTinyStudy + " --journal . --out new", "--journal");
  expect_refused(kTinyStudy + " --journal chapter --out ../new", "--journal", mine_);
  // An empty folder of the user's that is --out's parent: the journal would hold the result.
  fs::create_directories(scratch_.path() / "empty");
  expect_refused(kTinyStudy + " --journal empty --out empty/res", "--journal");
  EXPECT_TRUE(fs::is_empty(scratch_.path() / "empty"));
  EXPECT_FALSE(fs::exists(scratch_.path() / "new"));
}

TEST_F(Ownership, AJournalIsRemovedOnlyWithItsOwnFiles) {
  const fs::path journal = scratch_.path() / "j";
  const auto r = run_mrd(kTinyStudy + " --journal " + journal.string() + " --out " +
                             (scratch_.path() / "new").string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(journal)) << "a journal mrd made is removed after the run";
  // A journal of mrd's into which the user put a file of their own: only the journal's files go.
  fs::create_directories(journal);
  std::ofstream(journal / ".mrd-journal") << "made by mrd\n";
  std::ofstream(journal / "notes.txt") << "keep me";
  const auto again = run_mrd(kTinyStudy + " --journal " + journal.string() + " --out " +
                                 (scratch_.path() / "new").string(),
                             scratch_.path());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(entries(journal), std::set<std::string>{"notes.txt"});
  EXPECT_EQ(slurp(journal / "notes.txt"), "keep me");
}

TEST_F(Ownership, ATrailingSlashKeepsTheJournalBesideTheResult) {
  // A study long enough to be killed while it runs: 64 runs of 20 s motions on one thread.
  const std::string study =
      "fragility --synthetic 4 --duration-s 20 --pga-g 0.1,0.2,0.3,0.4 --idle-years 0,1 --control "
      "passive-on,passive-off --bootstrap 0 --threads 1 --out " +
      result_.string() + "/";
  const std::string cmd = std::string(MRD_BINARY) + " " + study + " >/dev/null 2>&1 & echo $!";
  FILE* p = ::popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  long pid = 0;
  ASSERT_EQ(std::fscanf(p, "%ld", &pid), 1);
  ::pclose(p);
  const fs::path beside = scratch_.path() / "result.journal";
  bool seen = false;
  for (int i = 0; i < 6000 && !seen; ++i) {
    std::error_code ec;
    for (fs::directory_iterator it(beside, ec), end; !ec && it != end; it.increment(ec)) {
      seen = seen || (it->path().extension() == ".journal" && fs::file_size(it->path(), ec) >= 64);
    }
    if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(static_cast<pid_t>(pid), SIGKILL);
  for (int i = 0; i < 500 && ::kill(static_cast<pid_t>(pid), 0) == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(seen) << "no journal record appeared beside the result (" << beside << ")";
  EXPECT_FALSE(fs::exists(result_ / ".journal"));
  EXPECT_TRUE(snapshot(result_) == result_before_) << "the killed run changed the previous result";
}

TEST_F(Ownership, AnOutputNeverReplacesAnInput) {
  // mrd risk reads the fragility result: the result as --out, through its file, a link, a trailing slash and `..`.
  expect_refused("risk --fragility " + result_.string() + " --out " + result_.string(), "--fragility");
  expect_refused("risk --fragility " + (result_ / "fragility.csv").string() + " --out " + result_.string(),
                 "contains the input");
  fs::create_directory_symlink(result_, scratch_.path() / "link");
  expect_refused("risk --fragility " + result_.string() + " --out link/", "is the input");
  expect_refused("risk --fragility result --out ./nowhere/../result/", "is the input");
  // A baseline inside the folder discrepancy would replace.
  std::ofstream(result_ / "damper.toml") << "# a baseline\n";
  result_before_ = snapshot(result_);
  expect_refused("discrepancy --measured " + (result_ / "runs.csv").string() + " --baseline " +
                     (result_ / "damper.toml").string() + " --out " + result_.string(),
                 "contains the input");
  // An output inside a folder of records.
  std::ofstream(mine_ / "quake.csv") << "time_s,accel_m_s2\n0,0\n0.01,1\n0.02,0\n";
  mine_before_ = snapshot(mine_);
  expect_refused(kTinyStudy + " --records " + mine_.string() + " --out " + (mine_ / "res").string(),
                 "lies inside the input");
  expect_refused("sim --record " + (mine_ / "quake.csv").string() + " --out " + mine_.string(), "contains the input");
}

TEST_F(Ownership, ListItemsEmptyOrRepeatedAreRefused) {
  const std::string out = " --out " + result_.string();
  expect_refused("fragility --synthetic 1 --pga-g 0.1,,0.2" + out, "--pga-g");
  expect_refused("fragility --synthetic 1 --pga-g ,0.1" + out, "--pga-g");
  expect_refused("fragility --synthetic 1 --pga-g 0.1," + out, "--pga-g");
  expect_refused("fragility --synthetic 1 --pga-g=0.1,,0.2" + out, "--pga-g");
  expect_refused("fragility --synthetic 1 --idle-years 0,1,,2" + out, "--idle-years");
  expect_refused("fragility --synthetic 1 --pga-g 0.1,0.10" + out, "given twice");
  expect_refused("fragility --synthetic 1 --control passive-on,passive-on" + out, "--control");
  expect_refused("fragility --synthetic 1 --control passive-on --control passive-on" + out, "given twice");
}

}  // namespace
}  // namespace mrd::test
