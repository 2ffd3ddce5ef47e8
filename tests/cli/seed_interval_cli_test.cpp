// One rule for every seed option (--seed of sim, schedule, risk, fragility
// and synth; --sensor-seed of sim): a decimal whole number from 0 to
// 2^64 - 1 = 18446744073709551615, anything else refused before any work with
// exit 2 and one line naming the option and the range. And a fixed interval of
// 0 days is refused by schedule and risk: the search is the option's absence.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

/// 2^64 - 1, written out: the largest seed, and the range every refusal names.
constexpr const char* kSeedRange = "from 0 to 18446744073709551615";

/// A command line with a seed option, `{out}` and `{frag}` standing for the
/// test's output folder and a small fragility.csv.
struct SeedCommand {
  const char* name;
  const char* args;
  const char* option;
};

constexpr SeedCommand kSeedCommands[] = {
    {"SimSeed", "sim --record none --duration-s 0.1 --out {out}", "--seed"},
    {"SimSensorSeed", "sim --plant hardware --record none --duration-s 0.1 --out {out}", "--sensor-seed"},
    {"ScheduleSeed", "schedule --years 0.1 --interval-days 5 --out {out}", "--seed"},
    {"RiskSeed", "risk --fragility {frag} --years 0.1 --interval-days 5 --out {out}", "--seed"},
    {"FragilitySeed", "fragility --out {out}", "--seed"},
    {"SynthSeed", "synth --duration-s 1 --out {out}", "--seed"},
};

/// Values that are no seed: negative (was wrapped to 2^64 - 1), a fraction,
/// 2^64 (one past the largest), hex, an exponent, a sign, empty.
constexpr const char* kNotSeeds[] = {"-1", "1.5", "18446744073709551616", "0x10", "1e3", "+5", "''"};

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (auto at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

class SeedRuleCli : public ::testing::Test {
 protected:
  TempDir scratch_;
  TempDir out_root_;

  /// Two fitted rows of one limit state, as mrd fragility writes them.
  fs::path fragility_csv() {
    const fs::path frag = scratch_.path() / "fragility.csv";
    std::ofstream(frag) << "control,limit_state,threshold,idle_years,status,median_pga_g,beta,median_pga_g_p05,"
                           "median_pga_g_p95,beta_p05,beta_p95,runs,exceedances\n"
                           "passive-on,stroke,0.2921,0,fitted,0.9,0.5,,,,,10,3\n"
                           "passive-on,stroke,0.2921,1,fitted,0.7,0.5,,,,,10,4\n";
    return frag;
  }

  std::string command_line(const SeedCommand& c, const fs::path& out) {
    return replace_all(replace_all(c.args, "{out}", out.string()), "{frag}", fragility_csv().string());
  }
};

TEST_F(SeedRuleCli, EveryNonSeedIsRefusedByEveryCommandBeforeAnyWork) {
  int n = 0;
  for (const SeedCommand& c : kSeedCommands) {
    for (const char* value : kNotSeeds) {
      const fs::path out = out_root_.path() / ("out" + std::to_string(n++));
      const auto r = run_mrd(command_line(c, out) + " " + c.option + " " + value, scratch_.path());
      const std::string what = std::string(c.name) + " " + value;
      EXPECT_EQ(r.exit_code, 2) << what << ": " << r.err;
      EXPECT_EQ(count_lines(r.err), 1) << what << ": " << r.err;
      EXPECT_NE(r.err.find(std::string(c.option) + ":"), std::string::npos) << what << ": " << r.err;
      EXPECT_NE(r.err.find(kSeedRange), std::string::npos) << what << ": " << r.err;
      EXPECT_FALSE(fs::exists(out)) << what;
    }
  }
}

// The largest seed is taken as it is (not wrapped, not refused) and recorded
// exactly; a leading zero is decimal (010 is ten, not octal eight).
TEST_F(SeedRuleCli, LargestSeedAndLeadingZeroAreDecimal) {
  const fs::path out = out_root_.path() / "max";
  auto r = run_mrd("schedule --years 0.1 --interval-days 5 --seed 18446744073709551615 --out " + out.string(),
                   scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(j["seed"].get<std::uint64_t>(), std::numeric_limits<std::uint64_t>::max());

  const fs::path ten = out_root_.path() / "ten";
  r = run_mrd("schedule --years 0.1 --interval-days 5 --seed 010 --out " + ten.string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = nlohmann::json::parse(slurp(ten / "summary.json"));
  EXPECT_EQ(j["seed"].get<std::uint64_t>(), 10u);
}

// sim's synthetic motion takes the whole 64-bit range like every other seed.
TEST_F(SeedRuleCli, SimTakesTheLargestSeed) {
  const auto r = run_mrd("sim --duration-s 1 --seed 18446744073709551615", scratch_.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("seed=18446744073709551615"), std::string::npos) << r.out;
}

TEST_F(SeedRuleCli, HelpShowsTheSeedsDefault) {
  for (const char* command : {"sim", "schedule", "risk", "fragility", "synth"}) {
    const auto r = run_mrd(std::string(command) + " --help", scratch_.path());
    EXPECT_EQ(r.exit_code, 0) << command;
    EXPECT_NE(r.out.find("--seed UINT64=1"), std::string::npos) << command << ": " << r.out;
  }
}

// 0 days used to mean "search": now the search is the option's absence and a
// zero, negative or sub-hour interval is refused with the way to ask for it.
TEST_F(SeedRuleCli, ZeroIntervalIsRefusedByScheduleAndRisk) {
  for (const char* command : {"schedule --years 0.1", "risk --fragility {frag} --years 0.1"}) {
    for (const char* days : {"0", "-0", "-1", "0.01", "nan"}) {
      const fs::path out = out_root_.path() / "interval";
      const SeedCommand c{"", command, ""};
      const auto r =
          run_mrd(command_line(c, out) + " --interval-days " + days + " --out " + out.string(), scratch_.path());
      const std::string what = std::string(command) + " --interval-days " + days;
      EXPECT_EQ(r.exit_code, 2) << what << ": " << r.err;
      EXPECT_EQ(count_lines(r.err), 1) << what << ": " << r.err;
      EXPECT_NE(r.err.find("--interval-days: expected a number of days >= 0.0417 (1 hour)"), std::string::npos)
          << what << ": " << r.err;
      EXPECT_NE(r.err.find("leave the option out to search"), std::string::npos) << what << ": " << r.err;
      EXPECT_FALSE(fs::exists(out)) << what;
    }
  }
}

}  // namespace
}  // namespace mrd::test
