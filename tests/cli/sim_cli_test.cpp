// `mrd sim`, `mrd sine`, `mrd sweep`: outputs, and bad input (exit 2, a
// one-line error naming file, line and field; nothing half-written).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

class SimCli : public ::testing::Test {
 protected:
  TempDir scratch_;
  TempDir out_;
  fs::path write(const std::string& name, const std::string& content) {
    const auto p = scratch_.path() / name;
    std::ofstream(p) << content;
    return p;
  }
};

std::string good_record() {
  std::string s = "time_s,accel_m_s2\n";
  for (int i = 0; i < 500; ++i) s += std::to_string(i * 0.01) + "," + std::to_string(std::sin(i * 0.1)) + "\n";
  return s;
}

TEST_F(SimCli, WritesSummaryTimeSeriesAndPlots) {
  const auto rec = write("quake.csv", good_record());
  const auto r = run_mrd("sim --record " + rec.string() + " --pga-g 0.1 --control passive-on --idle-years 0.3 --out " +
                             out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  for (const char* k : {"peak_base_displacement_m", "peak_damper_force_kn", "peak_superstructure_accel_m_s2"}) {
    ASSERT_TRUE(j.contains(k)) << k;
    EXPECT_GT(j[k].get<double>(), 0.0) << k;
  }
  // PGA scaled to 0.1 g exactly.
  EXPECT_NEAR(j["pga_m_s2"].get<double>(), 0.1 * 9.80665, 1e-9);
  EXPECT_TRUE(fs::exists(out_.path() / "timeseries.csv"));
  EXPECT_TRUE(fs::exists(out_.path() / "timeseries_response.png"));
  // 4.99 s of record at 1 kHz: 4991 rows + header.
  EXPECT_EQ(count_lines(slurp(out_.path() / "timeseries.csv")), 4992);
}

TEST_F(SimCli, WithoutRecordUsesASyntheticMotionAndSaysSo) {
  const auto r = run_mrd("sim --duration-s 5 --out " + out_.path().string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("synthetic"), std::string::npos);
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_TRUE(j["synthetic_motion"].get<bool>());
}

constexpr const char* kCoilFigures[] = {"peak_coil_current_a", "rms_coil_current_a", "time_above_rated_s",
                                        "command_changes_per_s", "peak_coil_temperature_rise_k"};

// Passive-off commands 0 A throughout: the hardware coil never carries current.
TEST_F(SimCli, HardwarePlantAtRestWritesTheCoilFigures) {
  const auto r = run_mrd("sim --plant hardware --record none --duration-s 2 --control passive-off --out " +
                             out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  for (const char* k : kCoilFigures) {
    ASSERT_TRUE(j.contains(k)) << k;
    EXPECT_EQ(j[k].get<double>(), 0.0) << k;
  }
  EXPECT_EQ(j["plant"], "hardware");
  EXPECT_DOUBLE_EQ(j["duration_s"].get<double>(), 2.0);
  EXPECT_EQ(j["peak_base_displacement_m"].get<double>(), 0.0);
  EXPECT_NE(r.out.find("peak coil temperature rise"), std::string::npos) << r.out;
}

// Passive-on: one command change (0 → 2.5 A) in 2 s = 0.5 per s; the drive
// does not overshoot the rated current; 2.5 A for 2 s heats the coil by less
// than 60 K (1 − e^(−2/1200)) = 0.0999 K.
TEST_F(SimCli, HardwarePlantPassiveOnCoilFigures) {
  const auto r = run_mrd("sim --plant hardware --record none --duration-s 2 --control passive-on --sensor-seed 3 "
                         "--offset-mm 5 --out " + out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_DOUBLE_EQ(j["command_changes_per_s"].get<double>(), 0.5);
  EXPECT_LE(j["peak_coil_current_a"].get<double>(), 2.5);
  EXPECT_GT(j["peak_coil_current_a"].get<double>(), 2.4);
  EXPECT_EQ(j["time_above_rated_s"].get<double>(), 0.0);
  EXPECT_GT(j["peak_coil_temperature_rise_k"].get<double>(), 0.0);
  EXPECT_LT(j["peak_coil_temperature_rise_k"].get<double>(), 60.0 * (1.0 - std::exp(-2.0 / 1200.0)));
}

// summary.json says which sensor noise and which parking offset the hardware
// plant ran with: --sensor-seed 18446744073709551615 (2^64 - 1, the largest
// seed, kept exactly) and --offset-mm -7.5 = -0.0075 m.
TEST_F(SimCli, HardwarePlantSummaryHasSensorSeedAndParkingOffset) {
  const auto r = run_mrd("sim --plant hardware --record none --duration-s 0.5 --sensor-seed 18446744073709551615 "
                         "--offset-mm -7.5 --out " + out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  ASSERT_TRUE(j.contains("sensor_seed"));
  ASSERT_TRUE(j.contains("parking_offset_m"));
  EXPECT_EQ(j["sensor_seed"].get<std::uint64_t>(), 18446744073709551615u);
  EXPECT_DOUBLE_EQ(j["parking_offset_m"].get<double>(), -0.0075);
  EXPECT_NE(r.out.find("sensor seed"), std::string::npos) << r.out;
}

// The thesis plant has ideal sensors and a centred damper: neither option
// acts on it, and summary.json says so with null rather than the defaults.
TEST_F(SimCli, ThesisPlantSummaryHasNoSensorSeedOrParkingOffset) {
  const auto r = run_mrd("sim --record none --duration-s 0.5 --sensor-seed 5 --offset-mm 4 --out " +
                             out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  ASSERT_TRUE(j.contains("sensor_seed"));
  ASSERT_TRUE(j.contains("parking_offset_m"));
  EXPECT_TRUE(j["sensor_seed"].is_null());
  EXPECT_TRUE(j["parking_offset_m"].is_null());
}

TEST_F(SimCli, ThesisPlantWritesTheCoilFiguresToo) {
  const auto r = run_mrd("sim --duration-s 2 --control passive-on --out " + out_.path().string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  for (const char* k : kCoilFigures) EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["plant"], "thesis");
  EXPECT_DOUBLE_EQ(j["peak_coil_current_a"].get<double>(), j["peak_current_a"].get<double>());
}

TEST_F(SimCli, BadPlantIsRefused) {
  const auto r = run_mrd("sim --plant bogus --record none --duration-s 2 --out " + out_.path().string(),
                         scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--plant"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out_.path() / "summary.json"));
}

TEST_F(SimCli, NoRecordNeedsADuration) {
  const auto r = run_mrd("sim --record none --out " + out_.path().string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--duration-s"), std::string::npos) << r.err;
}

struct BadRecord {
  const char* name;
  const char* content;
  const char* must_mention;
};

class SimCliBadRecord : public SimCli, public ::testing::WithParamInterface<BadRecord> {};

TEST_P(SimCliBadRecord, NamesFileLineAndField) {
  const auto& c = GetParam();
  const auto rec = write("bad.csv", c.content);
  const auto r = run_mrd("sim --record " + rec.string() + " --out " + out_.path().string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("bad.csv"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(c.must_mention), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out_.path() / "summary.json"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SimCliBadRecord,
    ::testing::Values(BadRecord{"NonNumeric", "time_s,accel_m_s2\n0,0\n0.01,abc\n0.02,0\n", "bad.csv:3"},
                      BadRecord{"NonUniformStep", "time_s,accel_m_s2\n0,0\n0.01,0.1\n0.03,0.2\n", "bad.csv:4"},
                      BadRecord{"Empty", "", "empty"},
                      BadRecord{"WrongHeader", "t,a\n0,0\n0.01,1\n", "header"}),
    [](const auto& p) { return std::string(p.param.name); });

TEST_F(SimCli, MissingRecordFile) {
  const auto r = run_mrd("sim --record " + (scratch_.path() / "nope.csv").string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nope.csv"), std::string::npos);
}

struct BadOption {
  const char* name;
  const char* args;
  const char* must_mention;
};

class SimCliBadOption : public SimCli, public ::testing::WithParamInterface<BadOption> {};

TEST_P(SimCliBadOption, OneLineErrorExitTwo) {
  const auto& c = GetParam();
  const auto r = run_mrd(c.args, scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(c.must_mention), std::string::npos) << r.err;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SimCliBadOption,
    ::testing::Values(BadOption{"NegativeDuration", "sim --duration-s -3", "--duration-s"},
                      BadOption{"UnknownControl", "sim --control turbo", "--control"},
                      BadOption{"NegativeIdle", "sim --idle-years -1", "--idle-years"},
                      BadOption{"ZeroPga", "sim --pga-g 0", "--pga-g"},
                      BadOption{"SineNegativeDuration", "sine --duration-s -1", "--duration-s"},
                      BadOption{"SineZeroFrequency", "sine --freq-hz 0", "--freq-hz"},
                      BadOption{"SineNanAmplitude", "sine --amplitude-mm nan", "--amplitude-mm"},
                      BadOption{"SweepUnknownControl", "sweep --control turbo --out /tmp/mrd-never", "--control"},
                      BadOption{"SweepBadIdleRange", "sweep --idle-from 1 --idle-to 0.5", "--idle-to"}),
    [](const auto& p) { return std::string(p.param.name); });

// Table 5.2 definitions, checked on Case 3 (2.5 years, 25.4 mm, 0.5 Hz):
// fully mixed force from Eq. 4.1 at the peak velocity 79.80 mm/s is
// 169.02 kN and the initial force at PR = a_PR(SQ = 1) is 18.02 kN (hand
// calculations in tests/unit/sine_rig_test.cpp).
TEST_F(SimCli, SineWritesTable52Metrics) {
  const auto r = run_mrd("sine --amplitude-mm 25.4 --freq-hz 0.5 --current-a 2.5 --idle-years 2.5 --duration-s 40 --out " +
                             out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_NEAR(j["fully_mixed_force_kn"].get<double>(), 169.02, 0.01);
  EXPECT_NEAR(j["initial_force_kn"].get<double>(), 18.02, 0.01);
  EXPECT_GT(j["max_force_kn"].get<double>(), j["initial_force_kn"].get<double>());
  EXPECT_GT(j["rise_time_95_s"].get<double>(), j["rise_time_90_s"].get<double>());
  for (const char* f : {"sine.csv", "force_time.png", "force_displacement.png"}) EXPECT_TRUE(fs::exists(out_.path() / f)) << f;
}

TEST_F(SimCli, SineThesisCasesPrintsModelAgainstMeasured) {
  const auto r = run_mrd("sine --thesis-cases --out " + out_.path().string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* s : {"Case 1", "Case 2", "Case 3", "163.61", "139.23", "25.97"}) EXPECT_NE(r.out.find(s), std::string::npos) << s;
  EXPECT_TRUE(fs::exists(out_.path() / "thesis_cases.md"));
}

TEST_F(SimCli, SweepWritesCsvAndPlots) {
  const auto rec = write("quake.csv", good_record());
  const auto r = run_mrd("sweep --record " + rec.string() + " --idle-from 0 --idle-to 1 --idle-step 0.5 --out " +
                             out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = slurp(out_.path() / "sweep.csv");
  EXPECT_EQ(count_lines(csv), 1 + 3 * 3);  // passive-off, passive-on, semi-active × 3 idle times
  EXPECT_TRUE(fs::exists(out_.path() / "passive-on_peak_base_displacement.png"));
}

}  // namespace
}  // namespace mrd::test
