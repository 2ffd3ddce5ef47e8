// `mrd sim --control semi-active [--numeric float|fixed]`: the firmware core
// through the command line, and bad --numeric input.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

TEST(FirmwareCli, SimRunsTheSemiActiveCoreInBothBuilds) {
  for (const std::string numeric : {"float", "fixed"}) {
    TempDir scratch, out;
    const auto r = run_mrd("sim --duration-s 6 --control semi-active --numeric " + numeric + " --out " +
                               out.path().string(),
                           scratch.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("semi-active (" + numeric + " core)"), std::string::npos) << r.out;
    const auto j = nlohmann::json::parse(slurp(out.path() / "summary.json"));
    EXPECT_EQ(j["control"].get<std::string>(), "semi-active");
    EXPECT_EQ(j["numeric"].get<std::string>(), numeric);
    EXPECT_GT(j["peak_damper_force_kn"].get<double>(), 0.0);
    // ODBDCO over-drives past the nominal 2.5 A but never past the 10 A command range.
    EXPECT_LE(j["peak_current_a"].get<double>(), 10.0);
  }
}

TEST(FirmwareCli, BadNumericIsAOneLineUsageError) {
  TempDir scratch, out;
  const auto r = run_mrd("sim --duration-s 1 --control semi-active --numeric quad --out " + out.path().string(),
                         scratch.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--numeric"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("quad"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out.path() / "summary.json"));
}

TEST(FirmwareCli, DoubleIsTheReferenceBuild) {
  // --numeric double runs the control core in double precision and says so.
  TempDir scratch, out;
  const auto r = run_mrd("sim --duration-s 2 --control semi-active --numeric double --out " + out.path().string(),
                         scratch.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(std::ifstream(out.path() / "summary.json"));
  EXPECT_EQ(j["numeric"], "double");
}

}  // namespace
}  // namespace mrd::test
