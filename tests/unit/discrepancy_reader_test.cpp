// Measured-data input of the discrepancy workflow: units in the header,
// conversion to SI, kept extra columns, .mat files, the derived velocity, and
// a one-line error naming file, line and column for every kind of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "host_sim/discrepancy/measured_data.hpp"
#include "mrd/units.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::discrepancy {
namespace {

/// A valid record: `rows` samples at 1 kHz of a 1 Hz, 10 mm sine.
std::string csv(const std::string& header, int rows) {
  std::string s = header + "\n";
  for (int k = 0; k < rows; ++k) {
    char line[160];
    const double t = k * 1e-3;
    std::snprintf(line, sizeof line, "%.6f,%.9f,2.5,%.3f\n", t, 0.01 * std::sin(2.0 * units::kPi * t),
                  1e5 * std::cos(2.0 * units::kPi * t));
    s += line;
  }
  return s;
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_measured_csv(text, "lab.csv");
  } catch (const io::UsageError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(MeasuredCsv, ReadsSiColumns) {
  const auto m = parse_measured_csv(csv("time_s,displacement_m,current_cmd_A,force_N", 1500), "lab.csv");
  ASSERT_EQ(m.size(), 1500u);
  EXPECT_DOUBLE_EQ(m.time_s[1], 0.001);
  EXPECT_DOUBLE_EQ(m.current_cmd_a[7], 2.5);
  EXPECT_NEAR(m.force_n[0], 1e5, 1e-9);
  EXPECT_TRUE(m.velocity_m_s.empty());
  EXPECT_TRUE(m.extra.empty());
  EXPECT_EQ(m.source, "lab.csv");
}

TEST(MeasuredCsv, ConvertsUnitsToSi) {
  // 1 in = 25.4 mm; 1 kip = 4448.2216152605 N (1000 lbf); 500 mA = 0.5 A; 2 ms steps.
  // Displacement and force alternate between two values (a constant one is refused).
  std::string s = "Time_ms,Displacement_in,Current_cmd_mA,Force_kip,velocity_mm_s\n";
  for (int k = 0; k < 600; ++k) {
    s += std::to_string(2 * k) + "," + std::to_string(1 + k % 2) + ",500," + std::to_string(2 + k % 2) + ",30\n";
  }
  const auto m = parse_measured_csv(s, "lab.csv");
  EXPECT_DOUBLE_EQ(m.time_s[3], 0.006);
  EXPECT_DOUBLE_EQ(m.displacement_m[0], 0.0254);
  EXPECT_DOUBLE_EQ(m.current_cmd_a[0], 0.5);
  EXPECT_NEAR(m.force_n[0], 2.0 * 4448.2216152605, 1e-9);
  ASSERT_EQ(m.velocity_m_s.size(), 600u);
  EXPECT_DOUBLE_EQ(m.velocity_m_s[0], 0.03);
}

TEST(MeasuredCsv, KeepsExtraColumnsAndAcceptsCurrentAsCommand) {
  std::string s = "# lab export\ntime_s,displacement_mm,current_A,force_kN,temp_top_degC\n";
  for (int k = 0; k < 1200; ++k) {
    s += std::to_string(k * 1e-3) + "," + std::to_string(3 + k % 2) + ",1.5," + std::to_string(120 + k % 2) + "," +
         std::to_string(20 + k) + "\n";
  }
  const auto m = parse_measured_csv(s, "lab.csv");
  EXPECT_DOUBLE_EQ(m.current_cmd_a[0], 1.5);
  EXPECT_TRUE(m.current_a.empty());  // the command, not a measured current
  EXPECT_DOUBLE_EQ(m.force_n[0], 120e3);
  ASSERT_EQ(m.extra.size(), 1u);
  EXPECT_EQ(m.extra[0].name, "temp_top_degC");
  EXPECT_DOUBLE_EQ(m.extra[0].values[5], 25.0);
}

TEST(MeasuredCsv, MeasuredCurrentNextToCommandIsTheCoilCurrent) {
  std::string s = "time_s,displacement_m,current_cmd_A,current_mA,force_N\n";
  for (int k = 0; k < 1200; ++k) {
    s += std::to_string(k * 1e-3) + "," + std::to_string(k % 2) + ",2,1900," + std::to_string(5 + k % 2) + "\n";
  }
  const auto m = parse_measured_csv(s, "lab.csv");
  EXPECT_DOUBLE_EQ(m.current_cmd_a[0], 2.0);
  ASSERT_EQ(m.current_a.size(), m.size());
  EXPECT_DOUBLE_EQ(m.current_a[0], 1.9);  // 1900 mA
  EXPECT_TRUE(m.extra.empty());
  // Written back with SI names, read back the same.
  const std::string csv = measured_to_csv(m);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "time_s,displacement_m,current_cmd_A,current_A,force_N");
  const auto again = parse_measured_csv(csv, "again.csv");
  ASSERT_EQ(again.current_a.size(), m.size());
  EXPECT_DOUBLE_EQ(again.current_a.back(), 1.9);
}

TEST(MeasuredCsv, AMeasuredCurrentBeyondAnyTestIsRefusedNamingItsLine) {
  std::string s = "time_s,displacement_m,current_cmd_A,current_A,force_N\n";
  for (int k = 0; k < 1200; ++k) {
    s += std::to_string(k * 1e-3) + "," + std::to_string(k % 2) + ",2," + (k == 7 ? "5e4" : "1.9") + "," +
         std::to_string(5 + k % 2) + "\n";
  }
  try {
    (void)parse_measured_csv(s, "lab.csv");
    FAIL() << "accepted";
  } catch (const mrd::io::UsageError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("lab.csv:9: column 'current_A'"), std::string::npos) << w;  // header line 1, sample 7 on line 9
    EXPECT_NE(w.find("beyond any damper test"), std::string::npos) << w;
  }
}

TEST(MeasuredCsv, AcceptsNonUniformTime) {
  std::string s = "time_s,displacement_m,current_cmd_A,force_N\n";
  double t = 0.0;
  for (int k = 0; k < 1500; ++k) {
    s += std::to_string(t) + "," + std::to_string(k % 2) + ",1," + std::to_string(k % 2) + "\n";
    t += k % 3 == 0 ? 0.0005 : 0.0012;
  }
  const auto m = parse_measured_csv(s, "lab.csv");
  EXPECT_EQ(m.size(), 1500u);
}

struct BadCase {
  const char* name;
  std::string text;
  std::vector<std::string> must_mention;
};

class MeasuredCsvBad : public ::testing::TestWithParam<BadCase> {};

TEST_P(MeasuredCsvBad, NamesFileLineAndColumn) {
  const auto& c = GetParam();
  const std::string e = error_of(c.text);
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  EXPECT_NE(e.find("lab.csv"), std::string::npos) << e;
  for (const auto& m : c.must_mention) EXPECT_NE(e.find(m), std::string::npos) << "missing '" << m << "' in: " << e;
}

/// A record whose force never changes (a disconnected load cell).
std::string constant_force_csv(double force_n) {
  std::string s = "time_s,displacement_m,current_cmd_A,force_N\n";
  for (int k = 0; k < 1500; ++k) {
    s += std::to_string(k * 1e-3) + "," + std::to_string(0.01 * std::sin(0.01 * k)) + ",2.5," +
         std::to_string(force_n) + "\n";
  }
  return s;
}

std::string with_line(std::string text, int line_no, const std::string& replacement) {
  std::size_t pos = 0;
  for (int l = 1; l < line_no; ++l) pos = text.find('\n', pos) + 1;
  const std::size_t end = text.find('\n', pos);
  return text.replace(pos, end - pos, replacement);
}

const std::string kHeader = "time_s,displacement_m,current_cmd_A,force_N";

INSTANTIATE_TEST_SUITE_P(
    Cases, MeasuredCsvBad,
    ::testing::Values(
        BadCase{"MissingForce", csv("time_s,displacement_m,current_cmd_A,load_N", 1500),
                {"lab.csv:1", "missing column", "force_N"}},
        BadCase{"MissingCurrent", csv("time_s,displacement_m,volts_V,force_N", 1500), {"lab.csv:1", "current_cmd_A"}},
        BadCase{"NonMonotonicTime", with_line(csv(kHeader, 1500), 101, "0.05,0,2.5,0"),
                {"lab.csv:101", "time_s", "does not increase"}},
        BadCase{"RepeatedTime", with_line(csv(kHeader, 1500), 3, "0.000,0,2.5,0"), {"lab.csv:3", "time_s"}},
        BadCase{"NaN", with_line(csv(kHeader, 1500), 57, "0.055,0,2.5,nan"), {"lab.csv:57", "force_N", "finite"}},
        BadCase{"Infinity", with_line(csv(kHeader, 1500), 9, "0.007,inf,2.5,0"), {"lab.csv:9", "displacement_m"}},
        BadCase{"NotANumber", with_line(csv(kHeader, 1500), 12, "0.010,0,2.5A,0"), {"lab.csv:12", "current_cmd_A"}},
        BadCase{"TooShort", csv(kHeader, 150), {"lab.csv:151", "time_s", "too short"}},
        BadCase{"TooShortInTime", csv(kHeader, 800), {"lab.csv:801", "too short"}},
        BadCase{"UnknownUnit", csv("time_s,displacement_m,current_cmd_A,force_lb", 1500),
                {"lab.csv:1", "column 4", "force_lb", "unknown unit 'lb'"}},
        BadCase{"UnknownUnitDisplacement", csv("time_s,displacement_furlong,current_cmd_A,force_N", 1500),
                {"lab.csv:1", "column 2", "displacement_furlong"}},
        BadCase{"NoUnit", csv("time_s,displacement,current_cmd_A,force_N", 1500),
                {"lab.csv:1", "column 2", "no unit"}},
        BadCase{"ExtraWithoutUnit", csv("time_s,displacement_m,current_cmd_A,force_N,comment", 1500),
                {"lab.csv:1", "column 5", "comment"}},
        BadCase{"RepeatedQuantity", csv("time_s,displacement_m,current_cmd_A,force_N,force_kN", 1500),
                {"lab.csv:1", "force_kN"}},
        BadCase{"WrongFieldCount", with_line(csv(kHeader, 1500), 40, "0.038,0,2.5"), {"lab.csv:40", "3"}},
        BadCase{"Empty", "", {"empty"}},
        BadCase{"HeaderIsData", csv("0,0,2.5,0", 1500), {"lab.csv:1", "header"}},
        // Limits of measured_data.hpp: |force| <= 1e8 N, |displacement| <= 10 m.
        BadCase{"AbsurdForce", with_line(csv(kHeader, 1500), 50, "0.048,0,2.5,1e12"),
                {"lab.csv:50", "force_N", "limit 1e+08 N"}},
        BadCase{"AbsurdDisplacement", with_line(csv(kHeader, 1500), 60, "0.058,20,2.5,0"),
                {"lab.csv:60", "displacement_m", "limit 10 m"}},
        BadCase{"AllZeroForce", constant_force_csv(0.0), {"lab.csv:1", "force_N", "constant 0 N"}},
        BadCase{"ConstantForce", constant_force_csv(5e3), {"lab.csv:1", "force_N", "constant 5000 N"}}),
    [](const auto& p) { return std::string(p.param.name); });

TEST(MeasuredCsv, TooCoarseSampling) {
  std::string s = kHeader + "\n";
  for (int k = 0; k < 300; ++k) s += std::to_string(k * 0.05) + ",0,1,0\n";
  const std::string e = error_of(s);
  EXPECT_NE(e.find("lab.csv:1"), std::string::npos) << e;
  EXPECT_NE(e.find("time_s"), std::string::npos) << e;
  EXPECT_NE(e.find("coarse"), std::string::npos) << e;
}

TEST(MeasuredFile, MissingFileIsAUsageError) {
  EXPECT_THROW((void)read_measured("/nonexistent/lab.csv"), io::UsageError);
}

class MeasuredMat : public ::testing::Test {
 protected:
  std::filesystem::path dir_ = std::filesystem::temp_directory_path() /
                               ("mrd-mat-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
                                ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void SetUp() override { std::filesystem::create_directories(dir_); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
};

TEST_F(MeasuredMat, RoundTripsThroughAMatFile) {
  auto m = parse_measured_csv(csv(kHeader, 1500), "lab.csv");
  m.extra.push_back({"temp_degC", std::vector<double>(m.size(), 21.5)});
  m.current_a.assign(m.size(), 0.87);  // a measured coil current travels as current_A
  const auto p = dir_ / "lab.mat";
  write_measured_mat(m, p);
  const auto back = read_measured(p);
  ASSERT_EQ(back.size(), m.size());
  EXPECT_EQ(back.time_s, m.time_s);
  EXPECT_EQ(back.force_n, m.force_n);
  EXPECT_EQ(back.displacement_m, m.displacement_m);
  EXPECT_EQ(back.current_cmd_a, m.current_cmd_a);
  EXPECT_EQ(back.current_a, m.current_a);
  ASSERT_EQ(back.extra.size(), 1u);
  EXPECT_EQ(back.extra[0].name, "temp_degC");
}

TEST_F(MeasuredMat, NamesVariableAndElement) {
  auto m = parse_measured_csv(csv(kHeader, 1500), "lab.csv");
  m.force_n[56] = std::nan("");
  const auto p = dir_ / "bad.mat";
  write_measured_mat(m, p);
  try {
    (void)read_measured(p);
    FAIL() << "no error";
  } catch (const io::UsageError& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("bad.mat"), std::string::npos) << s;
    EXPECT_NE(s.find("force_N"), std::string::npos) << s;
    EXPECT_NE(s.find("element 57"), std::string::npos) << s;
  }
}

TEST_F(MeasuredMat, NotAMatFile) {
  const auto p = dir_ / "text.mat";
  std::FILE* f = std::fopen(p.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs("time_s\n", f);
  std::fclose(f);
  EXPECT_THROW((void)read_measured(p), io::UsageError);
}

// A polynomial of degree ≤ 4 is reproduced exactly by the quartic fit, on
// uniform and on jittered time: x = 1 + 2t − 3t² + 0.5t³ + 0.25t⁴ has
// v = 2 − 6t + 1.5t² + t³ (by hand).
TEST(SmoothMotion, ExactOnAQuartic) {
  for (const bool jitter : {false, true}) {
    std::vector<double> t, x;
    for (int k = 0; k < 2000; ++k) {
      const double tk = k * 1e-3 + (jitter ? 0.0004 * std::sin(k * 1.7) : 0.0);
      t.push_back(tk);
      x.push_back(1 + 2 * tk - 3 * tk * tk + 0.5 * tk * tk * tk + 0.25 * tk * tk * tk * tk);
    }
    const auto s = smooth_motion(t, x);
    for (std::size_t k = 0; k < t.size(); k += 37) {
      const double tk = t[k];
      EXPECT_NEAR(s.velocity_m_s[k], 2 - 6 * tk + 1.5 * tk * tk + tk * tk * tk, 1e-7) << k;
      EXPECT_NEAR(s.displacement_m[k], x[k], 1e-9) << k;
    }
  }
}

// A 2 Hz, 20 mm sine: velocity A ω cos ω t within 0.3 % of its amplitude
// (the fit's gain at 2 Hz is above 0.998, from its weights).
TEST(SmoothMotion, SineVelocity) {
  const double a = 0.02, w = 2 * units::kPi * 2.0;
  std::vector<double> t, x;
  for (int k = 0; k < 4000; ++k) {
    t.push_back(k * 1e-3);
    x.push_back(a * std::sin(w * t.back()));
  }
  const auto s = smooth_motion(t, x);
  for (std::size_t k = 200; k < 3800; k += 11) EXPECT_NEAR(s.velocity_m_s[k], a * w * std::cos(w * t[k]), 0.003 * a * w);
}

}  // namespace
}  // namespace mrd::discrepancy
