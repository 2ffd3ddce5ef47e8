// Hostile or careless input to `mrd calibrate` and `mrd discrepancy --baseline`,
// run as a user runs them: a baseline file that is a FIFO, a device or too
// large is refused at once; one record in two roles is refused naming both
// options and the file; a damper.toml number outside its physical range is
// refused naming file, line, field and range; records probably in another
// unit or of another damper are warned about on stderr and in summary.json.
#include <sys/stat.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/plausibility.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

/// `mrd ARGS` run in `cwd`, killed after 60 s: a reader that blocks or reads
/// without end fails the test instead of hanging it.
RunResult run_in(const std::string& args, const fs::path& cwd, const fs::path& scratch) {
  return run_mrd(args, scratch, cwd, 60);
}

/// Options that keep a calibration of two or three small records well under a second.
constexpr const char* kQuick = " --law bingham --transition tanh --no-lost-motion --no-transition-time --no-plots";

class HostileCalibrate : public ::testing::Test {
 protected:
  TempDir scratch_;  // the records, and the working folder of every run
  TempDir logs_;     // stdout and stderr of the runs

  RunResult run(const std::string& args) { return run_in(args, scratch_.path(), logs_.path()); }

  /// A 2 s sine record at 200 Hz (5 mm at 1 Hz) of a damper with
  /// F = (200 + 800 I) tanh(v / 5 mm/s) + (1000 + 3000 I) v, times `force_scale`;
  /// the displacement written times `disp_scale` and the current times
  /// `current_scale` (1000: millimetres or milliamperes in an SI column).
  fs::path record(const std::string& name, double current_a, double force_scale = 1.0, double disp_scale = 1.0,
                  double current_scale = 1.0) {
    const auto p = scratch_.path() / name;
    std::ofstream f(p);
    f << "time_s,displacement_m,current_cmd_A,force_N\n";
    const double w = 2.0 * kPi;
    for (int k = 0; k <= 400; ++k) {
      const double t = k * 0.005;
      const double x = 0.005 * std::sin(w * t);
      const double v = 0.005 * w * std::cos(w * t);
      const double force = (200.0 + 800.0 * current_a) * std::tanh(v / 0.005) + (1000.0 + 3000.0 * current_a) * v;
      f << t << ',' << disp_scale * x << ',' << current_scale * current_a << ',' << force_scale * force << '\n';
    }
    return p;
  }

  /// A damper.toml calibrated from three records of the damper above (0, 0.5, 1 A).
  fs::path calibrated_toml() {
    record("c0.csv", 0.0);
    record("c1.csv", 0.5);
    record("c2.csv", 1.0);
    const auto r = run(std::string("calibrate --measured c0.csv c1.csv c2.csv") + kQuick + " --out cal");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return scratch_.path() / "cal" / "damper.toml";
  }
};

void expect_one_line_error(const RunResult& r, const std::vector<std::string>& mentions) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  for (const auto& m : mentions) EXPECT_NE(r.err.find(m), std::string::npos) << m << " in: " << r.err;
}

// ---- the --baseline reader --------------------------------------------------------

// A FIFO with no writer blocked the reader forever, /dev/zero was read until
// memory ran out: both are refused before any read, and a regular file larger
// than the stated limit (16 MiB: a damper.toml is a few kB) is refused naming it.
TEST_F(HostileCalibrate, BaselineThatIsNotARegularFileOrTooLargeIsRefusedAtOnce) {
  record("m.csv", 1.0);
  const auto fifo = scratch_.path() / "fifo.toml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_one_line_error(run("discrepancy --measured m.csv --baseline fifo.toml --out d"), {"fifo.toml"});
  expect_one_line_error(run("discrepancy --measured m.csv --baseline /dev/zero --out d"), {"/dev/zero"});
  expect_one_line_error(run("discrepancy --measured m.csv --baseline " + scratch_.path().string() + " --out d"),
                        {scratch_.path().string()});
  const auto big = scratch_.path() / "big.toml";
  std::ofstream(big) << "[model]\n";
  fs::resize_file(big, (std::size_t{16} << 20) + 1);
  expect_one_line_error(run("discrepancy --measured m.csv --baseline big.toml --out d"), {"big.toml", "limit"});
  EXPECT_FALSE(fs::exists(scratch_.path() / "d"));
}

// ---- the range rule of damper.toml ----------------------------------------------------

/// `text` with the first line starting with `key = ` replaced by `key = value`;
/// `line_no` receives its 1-based number.
std::string with_value(const std::string& text, const std::string& key, const std::string& value, int& line_no) {
  std::size_t pos = 0;
  line_no = 1;
  while (text.compare(pos, key.size() + 3, key + " = ") != 0) {
    pos = text.find('\n', pos);
    if (pos == std::string::npos) return text;
    ++pos;
    ++line_no;
  }
  const std::size_t end = text.find('\n', pos);
  return text.substr(0, pos) + key + " = " + value + text.substr(end);
}

// The values the probes found accepted, each refused with file:line:field and
// the range: a participant ratio is a share of the particles, [0, 1] (§5.3); a
// yield force lies between 1 mN and 1e9 N; a time constant between 1 µs and
// 1000 s. The file as calibrated is accepted.
TEST_F(HostileCalibrate, BaselineNumbersOutsideTheirPhysicalRangeAreRefused) {
  const auto toml = calibrated_toml();
  const std::string text = slurp(toml);
  record("m.csv", 1.0);
  const auto good = run("discrepancy --measured m.csv --effects force_offset --no-plots --baseline " + toml.string() +
                        " --out ok");
  ASSERT_EQ(good.exit_code, 0) << good.err;
  struct Case {
    const char* key;
    const char* value;
    const char* message;
  };
  for (const Case& c : {Case{"a_initial", "5", "participant_ratio.a_initial: expected a participant ratio in [0, 1], "
                                                "got 5.0"},
                        Case{"at_zero", "1e308", "yield_n.at_zero: expected a force in [0.001, 1e+09] N, got 1e+308"},
                        Case{"at_zero", "1e-300", "yield_n.at_zero: expected a force in [0.001, 1e+09] N, got 1e-300"},
                        Case{"tau_slow_s", "-0.7",
                             "coil.tau_slow_s: expected a time constant in [1e-06, 1000] s, got -0.7"}}) {
    int line = 0;
    const auto bad = scratch_.path() / "bad.toml";
    std::ofstream(bad) << with_value(text, c.key, c.value, line);
    const auto r = run("discrepancy --measured m.csv --baseline bad.toml --out d");
    EXPECT_EQ(r.exit_code, 2) << c.key;
    EXPECT_EQ(r.err, "mrd: error: bad.toml:" + std::to_string(line) + ": " + c.message + "\n");
    EXPECT_FALSE(fs::exists(scratch_.path() / "d"));
  }
}

// ---- calibration roles ------------------------------------------------------------------

// One file in two roles (or twice in one) was calibrated and reported as "test
// records (seen by no choice)": refused before any record is read, naming both
// options and the file, whatever path names it (./, a link, dir/..).
TEST_F(HostileCalibrate, OneRecordInTwoRolesIsRefused) {
  record("a.csv", 0.0);
  record("b.csv", 1.0);
  fs::create_directory(scratch_.path() / "dir");
  fs::create_symlink("a.csv", scratch_.path() / "link.csv");
  const std::string tail = " are one file: a record takes one role, once";
  expect_one_line_error(run(std::string("calibrate --measured a.csv b.csv --test ./a.csv") + kQuick + " --out o"),
                        {"--measured 'a.csv' and --test './a.csv'" + tail});
  expect_one_line_error(run(std::string("calibrate --measured b.csv --check a.csv --test link.csv") + kQuick +
                            " --out o"),
                        {"--check 'a.csv' and --test 'link.csv'" + tail});
  expect_one_line_error(run(std::string("calibrate --measured a.csv b.csv --check dir/../a.csv") + kQuick + " --out o"),
                        {"--measured 'a.csv' and --check 'dir/../a.csv'" + tail});
  expect_one_line_error(run(std::string("calibrate --measured a.csv b.csv ") + (scratch_.path() / "a.csv").string() +
                            kQuick + " --out o"),
                        {"--measured 'a.csv' and --measured '" + (scratch_.path() / "a.csv").string() + "'" + tail});
  EXPECT_FALSE(fs::exists(scratch_.path() / "o"));
  // Two records of the same name in two folders are two files.
  fs::create_directory(scratch_.path() / "other");
  fs::copy_file(scratch_.path() / "a.csv", scratch_.path() / "other" / "a.csv");
  const auto r = run(std::string("calibrate --measured a.csv b.csv --test other/a.csv") + kQuick + " --out o");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// ---- plausibility warnings ----------------------------------------------------------------

/// The lines of `err` that are warnings of `command`.
std::vector<std::string> warning_lines(const std::string& err, const std::string& command) {
  std::vector<std::string> lines;
  std::size_t pos = 0;
  const std::string prefix = "mrd " + command + ": warning: ";
  while (pos < err.size()) {
    const std::size_t end = err.find('\n', pos);
    const std::string line = err.substr(pos, end - pos);
    if (line.rfind(prefix, 0) == 0) lines.push_back(line.substr(prefix.size()));
    pos = end == std::string::npos ? err.size() : end + 1;
  }
  return lines;
}

// Millimetres in a _m column (a 5 mm test at 5 m of half range, above the 1 m
// no damper's half stroke reaches), milliamperes in an _A column (0.5 A at
// 500 A, above the 20 A of any MR coil), and two dampers 250 times apart at
// the same current and velocity (peak forces more than 10 times beyond what
// one damper allows): each warned on stderr and in summary.json's warnings.
// The same damper's records at 0, 0.5 and 1 A are not.
TEST_F(HostileCalibrate, RecordsProbablyInAnotherUnitOrOfAnotherDamperAreWarned) {
  record("a.csv", 0.0);
  record("b.csv", 0.5);
  record("c.csv", 1.0);
  record("mm.csv", 1.0, 1.0, 1000.0);
  record("ma.csv", 0.5, 1.0, 1.0, 1000.0);
  record("big.csv", 1.0, 250.0);
  const auto clean = run(std::string("calibrate --measured a.csv b.csv --check c.csv") + kQuick + " --out clean");
  ASSERT_EQ(clean.exit_code, 0) << clean.err;
  EXPECT_TRUE(warning_lines(clean.err, "calibrate").empty()) << clean.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(scratch_.path() / "clean" / "summary.json"))["warnings"],
            nlohmann::json::array());

  const auto r = run(std::string("calibrate --measured c.csv mm.csv --check ma.csv") + kQuick + " --out units");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lines = warning_lines(r.err, "calibrate");
  ASSERT_EQ(lines.size(), 2u) << r.err;
  EXPECT_EQ(lines[0].rfind("mm.csv: displacement half range 5 m, beyond any damper's half stroke", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind("ma.csv: commanded current up to 500 A, beyond any MR damper's coil", 0), 0u) << lines[1];
  EXPECT_EQ(nlohmann::json::parse(slurp(scratch_.path() / "units" / "summary.json"))["warnings"],
            nlohmann::json(lines));

  // big.csv against c.csv: the same 1 A and 31.4 mm/s, peak forces 250 times apart.
  const auto two = run(std::string("calibrate --measured c.csv --test big.csv") + kQuick + " --out two");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const auto tl = warning_lines(two.err, "calibrate");
  ASSERT_EQ(tl.size(), 1u) << two.err;
  EXPECT_EQ(tl[0].rfind("records big.csv and c.csv: peak forces", 0), 0u) << tl[0];
  EXPECT_NE(tl[0].find("250 times apart"), std::string::npos) << tl[0];
  EXPECT_EQ(nlohmann::json::parse(slurp(scratch_.path() / "two" / "summary.json"))["warnings"], nlohmann::json(tl));

  // discrepancy on the record with milliamperes in its current column.
  const auto d = run("discrepancy --measured ma.csv --effects force_offset --no-plots --out disc");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const auto dl = warning_lines(d.err, "discrepancy");
  ASSERT_EQ(dl.size(), 1u) << d.err;
  EXPECT_EQ(dl[0].rfind("ma.csv: commanded current up to 500 A", 0), 0u) << dl[0];
  EXPECT_EQ(nlohmann::json::parse(slurp(scratch_.path() / "disc" / "summary.json"))["warnings"],
            nlohmann::json(dl));
}

// The laboratory damper's fifteen records (../shared/lab_data: 0-1 A, 2-25 mm,
// 0.25-5 Hz, one damper) raise no warning together.
TEST(HostileCalibrateLab, TheLaboratoryRecordsRaiseNoWarning) {
  const fs::path dir = fs::path(MRD_SHARED_DIR) / "lab_data" / "quiroz_utfsm";
  ASSERT_TRUE(fs::exists(dir)) << dir;
  std::vector<discrepancy::MeasuredData> records;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".csv") records.push_back(discrepancy::read_measured(e.path()));
  ASSERT_EQ(records.size(), 15u);
  const auto w = discrepancy::plausibility_warnings(records);
  EXPECT_TRUE(w.empty()) << w.front();
}

}  // namespace
}  // namespace mrd::test
