// `mrd modal`: output fields and thesis values, help, and bad input (exit
// status 2, one-line error).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

class ModalCli : public ::testing::Test {
 protected:
  TempDir scratch_;
  TempDir out_;
};

TEST_F(ModalCli, WritesAllFieldsWithThesisValues) {
  const auto r = run_mrd("modal --out " + out_.path().string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  for (const char* key : {"frequencies_hz", "damping_ratios", "periods_s", "undamped_frequencies_hz"}) {
    ASSERT_TRUE(j.contains(key)) << key;
    ASSERT_TRUE(j[key].is_array()) << key;
    ASSERT_EQ(j[key].size(), 6u) << key;
    for (const auto& v : j[key]) ASSERT_TRUE(v.is_number()) << key;
  }
  const auto f = j["frequencies_hz"].get<std::vector<double>>();
  const auto zeta = j["damping_ratios"].get<std::vector<double>>();
  const auto period = j["periods_s"].get<std::vector<double>>();
  for (std::size_t k = 1; k < f.size(); ++k) EXPECT_GT(f[k], f[k - 1]) << k;
  for (std::size_t k = 0; k < f.size(); ++k) EXPECT_NEAR(period[k] * f[k], 1.0, 1e-12) << k;
  // Thesis §6.1: f1 = 0.25 Hz; ζ = 4.97 %, 3.17 %, 5.07 % (fractions in the file).
  EXPECT_NEAR(f[0], 0.25, 0.0025);
  EXPECT_NEAR(zeta[0], 0.0497, 0.00005);
  EXPECT_NEAR(zeta[1], 0.0317, 0.00005);
  EXPECT_NEAR(zeta[2], 0.0507, 0.00005);

  ASSERT_TRUE(j.contains("mode_shapes"));
  ASSERT_EQ(j["mode_shapes"].size(), 6u);
  for (const auto& shape : j["mode_shapes"]) ASSERT_EQ(shape.size(), 6u);
  ASSERT_EQ(j["dofs"].size(), 6u);
  EXPECT_EQ(j["dofs"][0], "base");

  // The table names its columns and shows the first frequency.
  EXPECT_NE(r.out.find("zeta (%)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0.25"), std::string::npos) << r.out;
}

TEST_F(ModalCli, PrintsWithoutOut) {
  const auto r = run_mrd("modal", scratch_.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("mode"), std::string::npos);
  EXPECT_EQ(r.out.find("wrote"), std::string::npos);
}

TEST_F(ModalCli, HelpExplainsFieldsAndUnits) {
  const auto top = run_mrd("--help", scratch_.path());
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_NE(top.out.find("modal"), std::string::npos);
  const auto r = run_mrd("modal --help", scratch_.path());
  EXPECT_EQ(r.exit_code, 0);
  for (const char* key : {"--out", "frequencies_hz", "damping_ratios", "periods_s", "undamped_frequencies_hz",
                          "mode_shapes", "Hz", "fraction", "Fig. 6.2"}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  }
}

TEST_F(ModalCli, UnwritableOutIsAnError) {
  const auto file = out_.path() / "a-file";
  { std::ofstream(file) << "x"; }
  for (const std::string& dir : {(file / "sub").string(), file.string(), std::string("/proc/mrd-cannot-write")}) {
    const auto r = run_mrd("modal --out " + dir, scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << dir;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST_F(ModalCli, UnknownOptionIsAnError) {
  const auto summary = out_.path() / "summary.json";
  { std::ofstream(summary) << "{\"earlier\": true}\n"; }
  { std::ofstream(out_.path() / ".mrd-result") << "an mrd result\n"; }
  const auto r = run_mrd("modal --frobnicate --out " + out_.path().string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("frobnicate"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(summary), "{\"earlier\": true}\n");
  for (const auto& e : fs::directory_iterator(out_.path())) {
    EXPECT_TRUE(e.path().filename() == "summary.json" || e.path().filename() == ".mrd-result")
        << "left behind: " << e.path();
  }
}

}  // namespace
}  // namespace mrd::test
