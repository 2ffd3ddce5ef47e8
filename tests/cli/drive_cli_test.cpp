// `--drive FILE` (README "Your drive") run as a user runs it: the shipped
// thesis drive gives the same bytes as no file in `mrd sim --plant hardware`;
// a 6 V drive on a coil of constant inductance charges it in `mrd sim` as an
// R–L circuit does by hand and says that its bus is short of the rating;
// `mrd configure --drive` puts the file's limits into the board; and bad
// drives or combinations are refused with exit status 2, nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

const fs::path kSource = MRD_SOURCE_DIR;
const fs::path kThesisDrive = kSource / "drives" / "thesis-pwm.toml";
const fs::path kThesisDamper = kSource / "dampers" / "thesis-200kn.toml";
const fs::path kSimBoard = kSource / "boards" / "sim" / "board.toml";

class DriveCli : public ::testing::Test {
 protected:
  /// `base`'s text with each `from` replaced by its `to`, written to scratch/`name`.
  fs::path edited(const fs::path& base, const std::string& name,
                  const std::vector<std::pair<std::string, std::string>>& edits) {
    std::string text = slurp(base);
    for (const auto& [from, to] : edits) {
      const auto at = text.find(from);
      EXPECT_NE(at, std::string::npos) << from;
      if (at != std::string::npos) text.replace(at, from.size(), to);
    }
    const fs::path p = scratch_.path() / name;
    std::ofstream(p) << text;
    return p;
  }

  TempDir scratch_;
  TempDir out_;
};

TEST_F(DriveCli, TheThesisDriveFileGivesTheSameBytesAsNoFile) {
  const std::string run = "sim --plant hardware --record none --duration-s 3 --control semi-active --out ";
  const fs::path plain = out_.path() / "plain", file = out_.path() / "file";
  const auto a = run_mrd(run + plain.string(), scratch_.path());
  const auto b = run_mrd(run + file.string() + " --drive " + kThesisDrive.string(), scratch_.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(a.err, b.err);
  for (const char* name : {"summary.json", "timeseries.csv"}) EXPECT_EQ(slurp(plain / name), slurp(file / name)) << name;
  EXPECT_EQ(nlohmann::json::parse(slurp(plain / "summary.json")).at("drive"), "thesis-pwm");
}

// A 6 V bus on the thesis damper with a coil of constant 2 H (L(1 A) = L(2 A))
// and 4.8 Ω, passive-on (2.5 A commanded from the first tick): the PI loop's
// K_p = 2 H · 200 rad/s = 400 V/A asks for hundreds of volts, so the bridge
// holds +6 V and i(t) = (6 V / 4.8 Ω)(1 − e^{−t · 4.8/2}). The largest current
// the run reads is at the start of its last tick, t = 0.999 s:
// 1.25 (1 − e^{−2.3976}) = 1.136330 A. The bus reaches at most 1.25 A, short
// of the damper's 2.5 A rating: said once.
TEST_F(DriveCli, ASixVoltDriveChargesTheCoilAsAnRLCircuitInMrdSim) {
  const fs::path damper = edited(kThesisDamper, "flat-coil.toml",
                                 {{"inductance_1a_h = 5.0", "inductance_1a_h = 2.0"},
                                  {"inductance_2a_h = 3.0", "inductance_2a_h = 2.0"}});
  const fs::path drive =
      edited(kThesisDrive, "six-volt.toml", {{"name = \"thesis-pwm\"", "name = \"six-volt\""}, {"bus_v = 72.0", "bus_v = 6.0"}});
  const fs::path dir = out_.path() / "six";
  const auto r = run_mrd("sim --plant hardware --record none --duration-s 1 --control passive-on --damper " +
                             damper.string() + " --drive " + drive.string() + " --out " + dir.string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("six-volt.toml: drive: the 6 V bus drives at most 1.25 A through the coil's 4.8 ohm, below "
                       "the damper's rated 2.5 A"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("six-volt"), std::string::npos) << r.out;
  // Its limits are the thesis rig's, for which the thesis's controller was made: nothing else said.
  EXPECT_EQ(r.err.find("configured for"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  EXPECT_EQ(j.at("drive"), "six-volt");
  EXPECT_NEAR(j.at("peak_coil_current_a").get<double>(), 1.25 * (1.0 - std::exp(-2.4 * 0.999)), 2e-5);

  // The same damper and drive through a board configured for them: the board carries the coil's inductance
  // and the drive ([drive]), and its passive-on current is the damper's rated 2.5 A, so the same charge.
  const fs::path cfg = out_.path() / "cfg";
  const auto c = run_mrd("configure --board " + kSimBoard.string() + " --damper " + damper.string() + " --drive " +
                             drive.string() + " --out " + cfg.string(),
                         scratch_.path());
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const std::string board = slurp(cfg / "board.toml");
  EXPECT_NE(board.find("coil_inductance_1a_h = 2.0\n"), std::string::npos) << board;
  EXPECT_NE(board.find("coil_inductance_2a_h = 2.0\n"), std::string::npos) << board;
  const fs::path on_board = out_.path() / "on-board";
  EXPECT_NE(board.find("[drive]\nname = \"six-volt\"\nbus_v = 6.0\n"), std::string::npos) << board;
  const auto b = run_mrd("sim --board " + (cfg / "board.toml").string() +
                             " --plant hardware --record none --duration-s 1 --control passive-on --out " +
                             on_board.string(),
                         scratch_.path());
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto on = nlohmann::json::parse(slurp(on_board / "summary.json"));
  EXPECT_EQ(on.at("drive"), "six-volt");
  EXPECT_NEAR(on.at("peak_coil_current_a").get<double>(), 1.25 * (1.0 - std::exp(-2.4 * 0.999)), 2e-5);
  EXPECT_NE(b.err.find("board.toml [drive]: drive: the 6 V bus drives at most 1.25 A"), std::string::npos) << b.err;
  // The board's [drive] decides the drive: --drive beside it is refused.
  const auto twice = run_mrd("sim --board " + (cfg / "board.toml").string() + " --plant hardware --record none "
                                 "--duration-s 1 --drive " + drive.string(),
                             scratch_.path());
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_NE(twice.err.find("--drive cannot be given with --board"), std::string::npos) << twice.err;
}

TEST_F(DriveCli, BadDrivesAndCombinationsAreRefusedBeforeAnythingIsWritten) {
  const fs::path weak = edited(kThesisDrive, "weak.toml", {{"peak_current_a = 30.0", "peak_current_a = 10.0"}});
  const fs::path ringing =
      edited(kThesisDrive, "ringing.toml", {{"loop_bandwidth_rad_s = 200.0", "loop_bandwidth_rad_s = 5000.0"}});
  const std::string sim = "sim --record none --duration-s 1 --plant hardware";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"sim --record none --duration-s 1 --drive " + kThesisDrive.string(), "--drive: only --plant hardware"},
      {sim + " --drive " + weak.string(), "weak.toml:16: drive.peak_current_a: expected at least continuous_current_a"},
      {sim + " --drive " + ringing.string(), "ringing.toml:18: drive.loop_bandwidth_rad_s: expected at most 1000 rad/s"},
      {sim + " --drive missing.toml", "missing.toml"},
      {"configure --board " + kSimBoard.string() + " --drive " + kThesisDrive.string() + " --drive-peak-limit-a 20",
       "cannot be given with --drive"},
  };
  for (const auto& [args, message] : cases) {
    const fs::path dir = out_.path() / "refused";
    const auto r = run_mrd(args + " --out " + dir.string(), scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << args << ": one line: " << r.err;
    EXPECT_FALSE(fs::exists(dir)) << args;
  }
}

// ±5 V at 2 V/A is a ±2.5 A command range; 8 A continuous and 12 A peak. A
// drive whose command range passes its continuous current is refused, naming
// the file's field: the core commands within the continuous current.
TEST_F(DriveCli, ConfigurePutsTheDrivesLimitsIntoTheBoard) {
  const fs::path drive = edited(kThesisDrive, "small.toml",
                                {{"name = \"thesis-pwm\"", "name = \"small\""},
                                 {"command_range_v = 10.0", "command_range_v = 5.0"},
                                 {"volts_per_amp = 1.0", "volts_per_amp = 2.0"},
                                 {"continuous_current_a = 15.0", "continuous_current_a = 8.0"},
                                 {"peak_current_a = 30.0", "peak_current_a = 12.0"}});
  const fs::path out = out_.path() / "small";
  const auto r = run_mrd("configure --board " + kSimBoard.string() + " --drive " + drive.string() + " --out " +
                             out.string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string board = slurp(out / "board.toml");
  EXPECT_NE(board.find("command_limit_a = 2.5\n"), std::string::npos) << board;
  EXPECT_NE(board.find("drive_continuous_limit_a = 8.0\n"), std::string::npos) << board;
  EXPECT_NE(board.find("drive_peak_limit_a = 12.0\n"), std::string::npos) << board;
  // Forcing: min(4 × 2.5 A, the 2.5 A command range).
  EXPECT_NE(board.find("overdrive_current_a = 2.5\n"), std::string::npos) << board;
  EXPECT_NE(slurp(out / "configure.md").find("the drive file's, small; the thesis rig's: 10 A"), std::string::npos);
  // Configured again from that board, without --drive: its [drive] gives the limits.
  const fs::path again = out_.path() / "again";
  const auto a = run_mrd("configure --board " + (out / "board.toml").string() + " --out " + again.string(),
                         scratch_.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_NE(slurp(again / "board.toml").find("command_limit_a = 2.5\n"), std::string::npos);
  const auto options = run_mrd("configure --board " + (out / "board.toml").string() +
                                   " --drive-peak-limit-a 12 --out " + (out_.path() / "options").string(),
                               scratch_.path());
  EXPECT_EQ(options.exit_code, 2);
  EXPECT_NE(options.err.find("cannot be given with a board file that has a [drive] table"), std::string::npos)
      << options.err;

  // The board configured for the thesis drive, or the thesis's controller, simulated on this one: said; the
  // board configured for it: not.
  for (const auto& [controller, which] : {std::pair{std::string("--board ") + kSimBoard.string(), "board"},
                                          std::pair{std::string("--control semi-active"), "thesis's controller"}}) {
    const auto s = run_mrd("sim " + controller + " --plant hardware --record none --duration-s 1 --drive " +
                               drive.string(),
                           scratch_.path());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    EXPECT_NE(s.err.find(std::string("the ") + which + " was configured for a drive of +-10 A command, 15 A "
                         "continuous and 30 A peak; the simulated drive's are +-2.5, 8 and 12 A"),
              std::string::npos)
        << s.err;
  }
  // The board configured for it carries it ([drive]): simulated without --drive, nothing said.
  const fs::path fit_dir = out_.path() / "fit";
  const auto fit = run_mrd("sim --board " + (out / "board.toml").string() +
                               " --plant hardware --record none --duration-s 1 --out " + fit_dir.string(),
                           scratch_.path());
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_EQ(fit.err.find("configured for"), std::string::npos) << fit.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(fit_dir / "summary.json")).at("drive"), "small");

  const fs::path wide = edited(kThesisDrive, "wide.toml", {{"continuous_current_a = 15.0", "continuous_current_a = 8.0"}});
  const fs::path refused = out_.path() / "wide";
  const auto w = run_mrd("configure --board " + kSimBoard.string() + " --drive " + wide.string() + " --out " +
                             refused.string(),
                         scratch_.path());
  EXPECT_EQ(w.exit_code, 2);
  EXPECT_NE(w.err.find("wide.toml: drive.command_range_v: the command range ±10 A (command_range_v / volts_per_amp) "
                       "exceeds continuous_current_a (8 A)"),
            std::string::npos)
      << w.err;
  EXPECT_FALSE(fs::exists(refused));
}

}  // namespace
}  // namespace mrd::test
