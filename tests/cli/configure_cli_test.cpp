// `mrd configure` and `mrd sim --board` from the command line: the lab
// walkthrough (records → calibrate → a lab-scale building → configure → the
// in-process board and mrd sim on the same board file, peaks equal), and bad
// configurations refused with exit 2 before anything is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "cli_runner.hpp"
#include "firmware/core/state_store.hpp"
#include "firmware/platform/linux/file_state_store.hpp"

namespace mrd::test {
namespace {

namespace fs = std::filesystem;

class ConfigureCli : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = scratch_.path() / name;
    std::ofstream(p) << text;
    return p;
  }
  static std::string source(const std::string& rel) { return std::string(MRD_SOURCE_DIR) + "/" + rel; }
  TempDir scratch_;
};

/// key=value of a program's summary line, as a double (17 digits: exact).
double summary_value(const std::string& out, const std::string& key) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(out, m, std::regex(" " + key + "=([-0-9.eE+]+)"))) << key << " in " << out;
  return m.empty() ? -1.0 : std::stod(m[1]);
}

// README "From your lab records to your board", steps 1-5.
TEST_F(ConfigureCli, TheLabWalkthroughRunsTheSameConfigurationInMrdSimAndOnTheBoard) {
  const fs::path lab = fs::path(MRD_SHARED_DIR) / "lab_data" / "quiroz_utfsm";
  const fs::path rec = fs::path(MRD_SHARED_DIR) / "ground_motions" / "elcentro_ns.csv";
  ASSERT_TRUE(fs::exists(lab / "25mm_0p25Hz_1p00A.csv")) << "shared laboratory records not found at " << lab;
  ASSERT_TRUE(fs::exists(rec)) << "shared El Centro record not found at " << rec;
  const fs::path cal = scratch_.path() / "cal", cfg = scratch_.path() / "cfg", sim = scratch_.path() / "sim";
  // 1. Calibrate (the 25 mm family: the stroke the closed loop needs).
  const auto c = run_mrd("calibrate --law bingham --measured " + (lab / "25mm_0p25Hz_0p00A.csv").string() + " " +
                             (lab / "25mm_0p25Hz_0p50A.csv").string() + " " + (lab / "25mm_0p25Hz_1p00A.csv").string() +
                             " --out " + cal.string(),
                         scratch_.path());
  ASSERT_EQ(c.exit_code, 0) << c.err;
  // 2-3. Configure the sim board for the lab frame and the calibrated damper.
  const std::string building = source("buildings/lab-frame-2dof.toml");
  const auto k = run_mrd("configure --building " + building + " --damper " + (cal / "damper.toml").string() +
                             " --board " + source("boards/sim/board.toml") + " --out " + cfg.string(),
                         scratch_.path());
  ASSERT_EQ(k.exit_code, 0) << k.err;
  ASSERT_TRUE(fs::exists(cfg / "configure.md"));
  const std::string board = slurp(cfg / "board.toml");
  // The lab damper's own size reached the controller: its 1 A rating, 4 A forcing.
  EXPECT_NE(board.find("rated_current_a = 1.0\n"), std::string::npos) << board;
  EXPECT_NE(board.find("overdrive_current_a = 4.0\n"), std::string::npos) << board;
  // 4-5. mrd sim --board and the in-process board (firmware runtime, drive
  // and plant over an in-memory CAN bus) on the same file.
  const std::string common = " --building " + building + " --record " + rec.string() + " --pga-g 0.1 --duration-s 20";
  const auto s = run_mrd("sim --board " + (cfg / "board.toml").string() + " --control semi-active --out " +
                             sim.string() + common,
                         scratch_.path());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const auto b = run_command(std::string(MRD_SIM_BOARD) + " --board " + (cfg / "board.toml").string() +
                                 " --mode semi-active" + common,
                             scratch_.path());
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto j = nlohmann::json::parse(slurp(sim / "summary.json"));
  const std::pair<const char*, double> peaks[] = {
      {"peak_base_displacement_m", j.at("peak_base_displacement_m").get<double>()},
      {"peak_damper_force_n", 1e3 * j.at("peak_damper_force_kn").get<double>()},
      {"peak_superstructure_accel_m_s2", j.at("peak_superstructure_accel_m_s2").get<double>()},
      {"peak_current_a", j.at("peak_current_a").get<double>()},
      {"peak_story_drift_m", j.at("peak_story_drift_m").get<double>()},
  };
  for (const auto& [key, want] : peaks) EXPECT_NEAR(summary_value(b.out, key), want, 1e-9 * std::fabs(want)) << key;
  // The controller worked within the damper's rating, and it mattered:
  // the coil stayed near 1 A, and the base moved less than without current.
  EXPECT_LT(j.at("peak_current_a").get<double>(), 1.1);
  const auto off = run_mrd("sim --board " + (cfg / "board.toml").string() + " --control passive-off --out " +
                               (scratch_.path() / "off").string() + common,
                           scratch_.path());
  ASSERT_EQ(off.exit_code, 0) << off.err;
  const auto j_off = nlohmann::json::parse(slurp(scratch_.path() / "off" / "summary.json"));
  EXPECT_LT(j.at("peak_base_displacement_m").get<double>(), 0.9 * j_off.at("peak_base_displacement_m").get<double>());
}

TEST_F(ConfigureCli, ABoardFileIsRequiredAndABadOneIsNamedWithItsLine) {
  const auto none = run_mrd("configure --out " + (scratch_.path() / "o").string(), scratch_.path());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("--board"), std::string::npos) << none.err;
  const fs::path bad = write("bad.toml", "[board]\nname = \"x\"\n[control]\n[can]\n[gpio]\nfitted = false\n[controler]\n");
  const auto r = run_mrd("configure --board " + bad.string() + " --out " + (scratch_.path() / "o").string(),
                         scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.toml:7: controler: unknown table"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(scratch_.path() / "o" / "board.toml"));
}

TEST_F(ConfigureCli, ACoilTheFixedBuildCannotCarryOnThisDriveIsRefusedByName) {
  // A 0.5 A coil on the ±10 A drive: the command range is 20 times the
  // rating, whose square does not fit the I²t format at the coil's scale
  // (firmware/core/numeric_formats.hpp): the fixed build refuses it, naming it.
  std::string damper = slurp(source("dampers/thesis-200kn.toml"));
  damper.replace(damper.find("current_a = 2.5"), 15, "current_a = 0.5");
  const fs::path d = write("small-coil.toml", damper);
  std::string board = slurp(source("boards/sim/board.toml"));
  board.replace(board.find("numeric = \"float\""), 17, "numeric = \"fixed\"");
  const fs::path b = write("fixed.toml", board);
  const auto r = run_mrd("configure --damper " + d.string() + " --board " + b.string() + " --out " +
                             (scratch_.path() / "o").string(),
                         scratch_.path());
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.err.find("fixed build) refuses"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("command_limit_a"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--drive-command-limit-a"), std::string::npos) << r.err;  // what to do about it
  EXPECT_FALSE(fs::exists(scratch_.path() / "o" / "board.toml"));

  // On a ±5 A drive it fits: s_I = 2^−2 A (the power of two nearest 0.5/2.5), and
  // (5 A / 0.25 A)² = 400 is inside Square Q9.22's 512; forcing min(4 × 0.5 A, 5 A) = 2 A.
  const fs::path out = scratch_.path() / "o5";
  const auto ok = run_mrd("configure --damper " + d.string() + " --board " + b.string() +
                              " --drive-command-limit-a 5 --drive-continuous-limit-a 8 --drive-peak-limit-a 12 --out " +
                              out.string(),
                          scratch_.path());
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const std::string board_out = slurp(out / "board.toml");
  EXPECT_NE(board_out.find("command_limit_a = 5.0"), std::string::npos) << board_out;
  EXPECT_NE(board_out.find("drive_continuous_limit_a = 8.0"), std::string::npos) << board_out;
  EXPECT_NE(board_out.find("drive_peak_limit_a = 12.0"), std::string::npos) << board_out;
  EXPECT_NE(board_out.find("overdrive_current_a = 2.0"), std::string::npos) << board_out;
  EXPECT_NE(slurp(out / "configure.md").find("given; the thesis rig's: 10 A"), std::string::npos);
}

// The drive's limits in the core's order (command range <= continuous <= peak), each positive.
TEST_F(ConfigureCli, ADrivesLimitsOutOfOrderAreRefusedByOption) {
  const std::string board = source("boards/sim/board.toml");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--drive-command-limit-a 20", "--drive-command-limit-a: expected at most the continuous current"},
      {"--drive-continuous-limit-a 40", "--drive-continuous-limit-a: expected at most the peak current"},
      {"--drive-peak-limit-a 0", "--drive-peak-limit-a"}};
  for (const auto& [option, message] : cases) {
    const fs::path out = scratch_.path() / "bad-drive";
    const auto r = run_mrd("configure --board " + board + " " + option + " --out " + out.string(), scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << option;
    EXPECT_NE(r.err.find(message), std::string::npos) << option << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << option;
  }
}

TEST_F(ConfigureCli, SimWithABoardRefusesWhatTheBoardDecides) {
  for (const char* opt : {"--numeric fixed", "--step-s 0.002", "--damper x.toml", "--fluid y.toml"}) {
    const auto r = run_mrd(std::string("sim --board ") + source("boards/sim/board.toml") + " " + opt, scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << opt;
    EXPECT_NE(r.err.find("cannot be given with --board"), std::string::npos) << opt << ": " << r.err;
  }
}

// A fluid whose maximum settling time is 20 years (fluids/illustrative-20-year.toml)
// on a configured board: after a saved idle time of 1 year, mrd-firmware
// --print-state gives SQ = τ/T_max = 1/20 (Eq. 5.5) and a_PR = 0.10 + 0.90·e^{−7·0.05}
// = 0.734219 (Eq. 5.6, Table 5.6); the thesis's model fluid (T_max = 0.853 years,
// Eq. 5.4) is fully settled after the same year (SQ = 1, a_PR = 0.10 + 0.90·e^{−7} = 0.100821).
TEST_F(ConfigureCli, TheBoardsFluidSetsTheFirmwaresSettlingState) {
  fw::PersistedIdleState st;
  st.equivalent_idle_ms = 31557600000ull;  // one Julian year
  st.rtc_ms = 1700000000000;
  st.save_sequence = 3;
  const fs::path state = scratch_.path() / "state.bin";
  posix::FileStateStore store(state.string());
  ASSERT_EQ(store.save(fw::encode_state(st)), hal::StoreStatus::kOk);
  for (const auto& [fluid, expect] :
       {std::pair{std::string(" --fluid ") + source("fluids/illustrative-20-year.toml"),
                  std::string("t_max_years=20.000000 sq=0.050000 pr=0.734219")},
        std::pair{std::string(), std::string("t_max_years=0.853434 sq=1.000000 pr=0.100821")}}) {
    const fs::path cfg = scratch_.path() / (fluid.empty() ? "thesis" : "slow");
    const auto k = run_mrd("configure --board " + source("boards/emulated-arm64/board.toml") + fluid + " --out " + cfg.string(),
                           scratch_.path());
    ASSERT_EQ(k.exit_code, 0) << k.err;
    const auto p = run_command(std::string(MRD_FIRMWARE) + " --board " + (cfg / "board.toml").string() + " --state " +
                                   state.string() + " --print-state",
                               scratch_.path());
    ASSERT_EQ(p.exit_code, 0) << p.err;
    EXPECT_NE(p.out.find(expect), std::string::npos) << p.out;
  }
}

}  // namespace
}  // namespace mrd::test
