// The board programs of the thesis's set-up refuse bad input before they
// touch the bus: exit status 2 and a message naming the file or the option.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_runner.hpp"

namespace mrd::rths_board {
namespace {
namespace fs = std::filesystem;

const std::string kBoardFile = (fs::path(MRD_BOARDS_DIR) / "emulated-arm64" / "board.toml").string();
const std::string kRecordFile = (fs::path(MRD_SHARED_DIR) / "ground_motions" / "elcentro_ns.csv").string();

test::RunResult run_rths_program(const char* binary, const std::string& args, const test::TempDir& dir) {
  return test::run_command("timeout -s KILL 20 " + std::string(binary) + " " + args, dir.path());
}

TEST(RthsProgramsCli, RuntimeRefusesABuildingWithTwoDamperPlacements) {
  test::TempDir dir;
  const std::string building = (fs::path(MRD_SOURCE_DIR) / "buildings" / "fixed-base-8dof.toml").string();
  const auto r = run_rths_program(MRD_RTHS, "--board " + kBoardFile + " --specimen damper --record " + kRecordFile +
                                                " --building " + building + " --out " + (dir.path() / "o").string(),
                                  dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("fixed-base-8dof.toml has 2 damper placements"), std::string::npos) << r.err;
}

TEST(RthsProgramsCli, RuntimeRefusesARateOutsideTheStatusFrameWithEitherSpecimen) {
  test::TempDir dir;
  for (const char* specimen : {"damper", "benchmark"}) {
    const auto r = run_rths_program(MRD_RTHS, "--board " + kBoardFile + " --specimen " + specimen + " --record " +
                                                  kRecordFile + " --rate-hz 50 --out " + (dir.path() / "o").string(),
                                    dir);
    EXPECT_EQ(r.exit_code, 2) << specimen << ": " << r.err;
    EXPECT_NE(r.err.find("--rate-hz: expected a number from 100 to 65535 Hz, got '50'"), std::string::npos) << specimen << ": " << r.err;
  }
}

TEST(RthsProgramsCli, RuntimeRefusesADelayOfPartSteps) {
  test::TempDir dir;
  const auto r = run_rths_program(MRD_RTHS, "--board " + kBoardFile + " --specimen damper --record " + kRecordFile +
                                                " --delay-ms 15.5 --out " + (dir.path() / "o").string(),
                                  dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--delay-ms"), std::string::npos) << r.err;
}

TEST(RthsProgramsCli, LaboratoryRefusesADelayUnderOneStepAndANodeOfTheDamperLoop) {
  test::TempDir dir;
  auto r = run_rths_program(MRD_RTHS_LAB, "--board " + kBoardFile + " --specimen damper --delay-ms 0.5", dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--delay-ms"), std::string::npos) << r.err;
  r = run_rths_program(MRD_RTHS_LAB, "--board " + kBoardFile + " --specimen damper --lab-node 3", dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--lab-node"), std::string::npos) << r.err;
}

TEST(RthsProgramsCli, BothProgramsRefuseCanFdWithTheThesisSetUp) {
  test::TempDir dir;
  auto r = run_rths_program(MRD_RTHS, "--board " + kBoardFile + " --specimen damper --can-fd --record " + kRecordFile +
                                          " --out " + (dir.path() / "o").string(),
                            dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--can-fd"), std::string::npos) << r.err;
  r = run_rths_program(MRD_RTHS_LAB, "--board " + kBoardFile + " --specimen damper --can-fd", dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--can-fd"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace mrd::rths_board
