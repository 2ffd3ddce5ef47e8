// Hostile input to `mrd`: every class of bad option and bad file gives exit 2
// and one line on stderr naming the option or file, and the previous result in
// the --out folder stays byte for byte as it was, with nothing beside it. And
// a run killed while it rewrites a folder leaves the old result or a complete
// new one (SIGKILL), or the old one and no debris (SIGINT, SIGTERM).
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.hpp"

extern char** environ;

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

/// A ground-motion CSV of `n` samples every `dt_s`, acceleration `accel(i)`.
template <class F>
std::string record_csv(int n, double dt_s, F accel) {
  std::string s = "time_s,accel_m_s2\n";
  char line[96];
  for (int i = 0; i < n; ++i) {
    std::snprintf(line, sizeof line, "%.6f,%.17g\n", i * dt_s, accel(i));
    s += line;
  }
  return s;
}

/// A measured damper record (300 samples at 100 Hz) with force `force(i)`, N.
template <class F>
std::string measured_csv(F force) {
  std::string s = "time_s,displacement_m,current_cmd_A,force_N\n";
  char line[128];
  for (int i = 0; i < 300; ++i) {
    std::snprintf(line, sizeof line, "%.3f,%.17g,1,%.17g\n", i * 0.01, 0.01 * std::sin(i * 0.05), force(i));
    s += line;
  }
  return s;
}

class HostileInput : public ::testing::Test {
 protected:
  void SetUp() override {
    prev_ = scratch_.path() / "prev";
    const auto r = run_mrd("sim --duration-s 1 --out " + prev_.string(), scratch_.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    before_ = snapshot(prev_);
    ASSERT_GE(before_.size(), 2u);
    around_ = entries(scratch_.path());
  }

  fs::path write(const std::string& name, const std::string& content) {
    const auto p = scratch_.path() / name;
    std::ofstream(p, std::ios::binary) << content;
    return p;
  }

  /// Runs `args` with `--out prev` appended and checks the refusal: exit 2,
  /// one line on stderr containing `named`, the previous result unchanged
  /// and nothing new beside it.
  void expect_refused(const std::string& args, const std::string& named) {
    SCOPED_TRACE(args);
    const auto r = run_mrd(args + " --out " + prev_.string(), scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << r.err;
    EXPECT_TRUE(snapshot(prev_) == before_) << "the previous result changed";
    auto now = entries(scratch_.path());
    now.erase("stdout.txt");
    now.erase("stderr.txt");
    auto was = around_;
    was.erase("stdout.txt");
    was.erase("stderr.txt");
    for (const auto& n : now) EXPECT_TRUE(was.count(n) || n.find(".csv") != std::string::npos ||
                                          n.find(".mat") != std::string::npos || n.find(".AT2") != std::string::npos)
        << "left beside the folder: " << n;
  }

  TempDir scratch_;
  fs::path prev_;
  Snapshot before_;
  std::set<std::string> around_;
};

TEST_F(HostileInput, OptionsOutOfRangeEmptyOrNotANumber) {
  expect_refused("sim --pga-g 1e308", "--pga-g");
  expect_refused("sim --pga-g nan", "--pga-g");
  expect_refused("sim --idle-years ''", "--idle-years");
  expect_refused("sim --idle-years 1e308", "--idle-years");
  expect_refused("sim --duration-s 0", "--duration-s");
  expect_refused("sim --duration-s inf", "--duration-s");
  expect_refused("sim --step-s -1", "--step-s");
  expect_refused("sweep --idle-to 1e308", "--idle-to");
  expect_refused("sweep --idle-step 1e-9 --idle-to 1", "--idle-step");
  expect_refused("sweep --threads 100000", "--threads");
  expect_refused("sine --amplitude-mm 1e308", "--amplitude-mm");
  expect_refused("sine --freq-hz inf", "--freq-hz");
  expect_refused("sine --duration-s 0", "--duration-s");
  expect_refused("settle --idle-years -1", "--idle-years");
  expect_refused("study --pga-g 0", "--pga-g");
  expect_refused("schedule --years ''", "--years");
  expect_refused("synth --duration-s 1e308", "--duration-s");
}

TEST_F(HostileInput, GroundMotionFilesThatAreNotRecords) {
  expect_refused("sim --record /dev/zero", "/dev/zero");
  expect_refused("sim --record " + scratch_.path().string(), scratch_.path().string());
  const auto fifo = scratch_.path() / "fifo.csv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_refused("sim --record " + fifo.string(), "fifo.csv");
  fs::remove(fifo);
  expect_refused("sim --record " + write("empty.csv", "time_s,accel_m_s2\n").string(), "empty.csv");
  expect_refused("sim --record " + write("zero.csv", record_csv(300, 0.01, [](int) { return 0.0; })).string(),
                 "PGA");
  expect_refused("sim --record " + write("huge.csv", record_csv(300, 0.01, [](int i) { return i == 7 ? 1e308 : 0.1; }))
                                       .string(),
                 "huge.csv");
  // A step of 1e-9 s makes no run at 1 ms (the limit is 1 µs).
  expect_refused("sim --record " + write("tiny_step.csv", record_csv(300, 1e-9, [](int i) { return std::sin(i); }))
                                       .string(),
                 "tiny_step.csv");
  expect_refused("sim --record " + write("quake.AT2", "h\nh\nUNITS OF G\nNPTS=  5, DT= .01 SEC\n 1 2 3\n").string(),
                 "quake.AT2");
}

TEST_F(HostileInput, MeasuredRecordsThatCannotBeCompared) {
  expect_refused("discrepancy --measured /dev/zero", "/dev/zero");
  expect_refused("discrepancy --measured " + write("zero_force.csv", measured_csv([](int) { return 0.0; })).string(),
                 "zero_force.csv");
  expect_refused("discrepancy --measured " + write("const_force.csv", measured_csv([](int) { return 5e3; })).string(),
                 "constant");
  expect_refused("discrepancy --measured " +
                     write("huge_force.csv", measured_csv([](int i) { return i == 50 ? 1e308 : 1e3 * i; })).string(),
                 "huge_force.csv");
  expect_refused("discrepancy --measured " + write("no_rows.csv", "time_s,displacement_m,current_cmd_A,force_N\n").string(),
                 "no_rows.csv");
  const auto fifo = scratch_.path() / "fifo.csv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_refused("discrepancy --measured " + fifo.string(), "fifo.csv");
  fs::remove(fifo);
}

TEST_F(HostileInput, TruncatedMatFileIsRefusedNamingTheVariable) {
  const auto gen = scratch_.path() / "gen";
  const auto s = run_mrd("synth --effects none --seed 4 --duration-s 8 --format mat --out " + gen.string(),
                         scratch_.path());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const std::string full = slurp(gen / "measured.mat");
  ASSERT_GT(full.size(), 1000u);
  const auto cut = write("cut.mat", full.substr(0, full.size() * 9 / 10));
  fs::remove_all(gen);
  around_ = entries(scratch_.path());
  // Variables are written in the order time, displacement, current, force: a 10 % cut falls in force_N.
  expect_refused("discrepancy --measured " + cut.string(), "force_N");
  const auto r = run_mrd("discrepancy --measured " + cut.string(), scratch_.path());
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
}

TEST_F(HostileInput, OutputFolderThatIsNotAnMrdResultIsNeverReplaced) {
  const auto mine = scratch_.path() / "mine";
  fs::create_directories(mine);
  std::ofstream(mine / "thesis.tex") << "my work";
  const auto r = run_mrd("settle --idle-years 0.5 --out " + mine.string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(mine / "thesis.tex"), "my work");
  EXPECT_EQ(entries(mine), std::set<std::string>{"thesis.tex"});
  const auto file = write("a_file", "x");
  const auto f = run_mrd("settle --idle-years 0.5 --out " + file.string(), scratch_.path());
  EXPECT_EQ(f.exit_code, 2);
  EXPECT_EQ(slurp(file), "x");
}

TEST_F(HostileInput, ANewRunReplacesTheWholeFolder) {
  // sim wrote summary.json, timeseries.csv and plots; settle writes only summary.json.
  const auto r = run_mrd("settle --idle-years 0.5 --out " + prev_.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(entries(prev_), (std::set<std::string>{".mrd-result", "summary.json"}));
  EXPECT_TRUE(nlohmann::json::parse(slurp(prev_ / "summary.json")).contains("sq"));
}

TEST_F(HostileInput, AnErrorAfterTheFolderIsOpenedLeavesNoFolder) {
  // --record none without --duration-s is found inside the run, after --out is opened.
  const auto fresh = scratch_.path() / "a" / "b" / "fresh";
  const auto r = run_mrd("sim --record none --out " + fresh.string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(fs::exists(scratch_.path() / "a"));
}

TEST(HostileWarnings, AHundredGRunFinishesWithWarnings) {
  TempDir out, scratch;
  const auto r = run_mrd("sim --pga-g 100 --duration-s 10 --out " + out.path().string(), scratch.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out.path() / "summary.json"));
  ASSERT_TRUE(j["warnings"].is_array());
  // 100 g moves the base metres, far past the ±0.2921 m stroke of Table 3.1.
  EXPECT_GT(j["peak_base_displacement_m"].get<double>(), 0.2921);
  bool stroke = false;
  for (const auto& w : j["warnings"]) stroke = stroke || w.get<std::string>().find("stroke") != std::string::npos;
  EXPECT_TRUE(stroke) << j["warnings"].dump();
  EXPECT_NE(r.err.find("mrd sim: warning: peak stroke"), std::string::npos) << r.err;
}

TEST(HostileWarnings, ARunWithinTheModelHasNone) {
  TempDir out, scratch;
  // Passive-off (0 A) at a tenth of the thesis PGA: millimetres, well inside every limit.
  const auto r = run_mrd("sim --pga-g 0.01 --duration-s 10 --out " + out.path().string(), scratch.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out.path() / "summary.json"));
  EXPECT_TRUE(j["warnings"].empty()) << j["warnings"].dump();
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
}

// ------------------------------------------------------------ killed runs

pid_t spawn_mrd(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  std::string bin = MRD_BINARY;
  argv.push_back(bin.data());
  std::vector<std::string> copy = args;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, bin.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

int wait_exit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

/// A sweep result is consistent when its summary, CSV and plots describe the same runs.
void expect_consistent_sweep(const fs::path& dir) {
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  const std::size_t runs = j["runs"].get<std::size_t>();
  EXPECT_EQ(static_cast<std::size_t>(count_lines(slurp(dir / "sweep.csv"))), runs + 1);
  std::set<std::string> expected{".mrd-result", "summary.json", "sweep.csv"};
  for (const auto& p : j["plots"]) expected.insert(p.get<std::string>());
  EXPECT_EQ(entries(dir), expected);
}

class KilledSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    record_ = scratch_.path() / "short.csv";
    std::ofstream(record_) << record_csv(400, 0.01, [](int i) { return std::sin(0.2 * i); });
    out_ = scratch_.path() / "sweep";
  }
  std::vector<std::string> sweep_args(const std::string& idle_to) const {
    return {"sweep", "--record", record_.string(), "--control", "passive-on", "--idle-to", idle_to,
            "--idle-step", "0.05", "--threads", "1", "--out", out_.string()};
  }
  TempDir scratch_;
  fs::path record_;
  fs::path out_;
};

TEST_F(KilledSweep, SigkillAtRandomMomentsLeavesTheOldOrTheNewResultWhole) {
  ASSERT_EQ(wait_exit(spawn_mrd(sweep_args("0.5"))), 0);
  expect_consistent_sweep(out_);
  // How long a rewrite takes, to kill within it.
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(wait_exit(spawn_mrd(sweep_args("1"))), 0);
  const double run_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::mt19937 rng(11);
  std::uniform_real_distribution<double> when(0.0, run_s * 1.2);
  int old_seen = 0, new_seen = 0;
  for (int k = 0; k < 8; ++k) {
    const Snapshot old_result = snapshot(out_);
    const pid_t pid = spawn_mrd(sweep_args(k % 2 == 0 ? "1" : "0.5"));
    std::this_thread::sleep_for(std::chrono::duration<double>(when(rng)));
    ::kill(pid, SIGKILL);
    wait_exit(pid);
    ASSERT_TRUE(fs::exists(out_ / "summary.json")) << "kill " << k << ": the result is gone";
    expect_consistent_sweep(out_);
    const Snapshot now = snapshot(out_);
    (now == old_result ? old_seen : new_seen)++;
    for (const auto& n : entries(scratch_.path())) {
      EXPECT_TRUE(n == "short.csv" || n == "sweep" || n.rfind(".sweep.staging-", 0) == 0) << n;
    }
    // Whatever the kill left, the next run completes.
    ASSERT_EQ(wait_exit(spawn_mrd(sweep_args("0.5"))), 0);
    expect_consistent_sweep(out_);
  }
  // The next completed run removed the staging folders of the killed ones.
  EXPECT_EQ(entries(scratch_.path()), (std::set<std::string>{"short.csv", "sweep"}));
  std::printf("SIGKILL x8: old result %d times, the new one %d times\n", old_seen, new_seen);
}

TEST_F(KilledSweep, SigintAndSigtermLeaveTheOldResultAndNoDebris) {
  ASSERT_EQ(wait_exit(spawn_mrd(sweep_args("0.5"))), 0);
  for (const int sig : {SIGINT, SIGTERM}) {
    const Snapshot old_result = snapshot(out_);
    const pid_t pid = spawn_mrd(sweep_args("1"));
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    ::kill(pid, sig);
    const int status = wait_exit(pid);
    if (WIFSIGNALED(status)) {
      EXPECT_EQ(WTERMSIG(status), sig);
      EXPECT_TRUE(snapshot(out_) == old_result);
    } else {
      expect_consistent_sweep(out_);  // the run had finished before the signal
    }
    EXPECT_EQ(entries(scratch_.path()), (std::set<std::string>{"short.csv", "sweep"}));
    ASSERT_EQ(wait_exit(spawn_mrd(sweep_args("0.5"))), 0);
  }
}

}  // namespace
}  // namespace mrd::test
