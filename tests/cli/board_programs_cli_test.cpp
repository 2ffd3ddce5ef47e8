// The board programs run as a user runs them: bad input gets one line naming
// file, line and field with exit status 2; an unusable interface exit 1; the
// sim board's summary equals `mrd sim`'s summary.json.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <utility>

namespace {

namespace fs = std::filesystem;

struct Result {
  int exit_code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

class Programs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("mrd-board-cli-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  Result run(const std::string& cmd) {
    const std::string full = cmd + " >" + (dir_ / "out").string() + " 2>" + (dir_ / "err").string();
    const int status = std::system(full.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir_ / "out"), slurp(dir_ / "err")};
  }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  fs::path dir_;
};

int lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

/// `cmd` stopped after 10 s (exit 124), so that a program that blocks fails the test instead of hanging it.
std::string within_10_s(const std::string& cmd) { return "timeout 10 " + cmd; }

/// A board file without GPIO whose [state] path (line 9) is `state_path`.
std::string board_with_state_path(const std::string& state_path) {
  return "[board]\nname = \"x\"\n[control]\n[can]\ninterface = \"can0\"\n[gpio]\nfitted = false\n[state]\npath = \"" +
         state_path + "\"\n";
}

TEST_F(Programs, FirmwareRefusesABadBoardFileNamingLineAndField) {
  const auto board = write("b.toml", "[board]\nname = \"x\"\n[control]\nmode = \"fast\"\n[can]\ninterface = \"can0\"\n");
  const Result r = run(std::string(MRD_FIRMWARE) + " --board " + board.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines(r.err), 1);
  EXPECT_NE(r.err.find(board.string() + ":4: control.mode: expected passive-off"), std::string::npos) << r.err;
}

// A plain open() of a FIFO waits for a writer: --print-state hung for ever.
TEST_F(Programs, FirmwarePrintStateOnAFifoReturnsAtOnceWithExit2) {
  const fs::path fifo = dir_ / "state.bin";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const Result r = run(within_10_s(std::string(MRD_FIRMWARE) + " --board " + MRD_BOARDS_DIR +
                                   "/emulated-arm64/board.toml --state " + fifo.string() + " --print-state"));
  EXPECT_EQ(r.exit_code, 2) << "124: it blocked\n" << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--state: " + fifo.string() + ": is a pipe (FIFO), expected a regular file"),
            std::string::npos) << r.err;
}

TEST_F(Programs, FirmwareRefusesABoardFileWhoseStatePathIsAFifoAFolderADeviceOrHoldsANul) {
  const fs::path fifo = dir_ / "state.bin";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const fs::path folder = dir_ / "state";
  fs::create_directory(folder);
  const std::pair<std::string, std::string> cases[] = {
      {fifo.string(), fifo.string() + ": is a pipe (FIFO), expected a regular file"},
      {folder.string(), folder.string() + ": is a folder, expected a regular file"},
      {"/dev/null", "/dev/null: is a device, expected a regular file"},
      {"/data/a\\u0000b.bin", "expected a file path without a NUL character"},
  };
  for (const auto& [state_path, problem] : cases) {
    const fs::path board = write("b.toml", board_with_state_path(state_path));
    const Result r = run(within_10_s(std::string(MRD_FIRMWARE) + " --board " + board.string() + " --print-state"));
    EXPECT_EQ(r.exit_code, 2) << state_path << "\n" << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(board.string() + ":9: state.path: " + problem), std::string::npos) << r.err;
  }
}

// Each program reads its board file under the reader policy: a FIFO, a
// folder or /dev/zero is refused unread, at once, naming the file.
TEST_F(Programs, BoardProgramsRefuseABoardFileThatIsAFifoAFolderOrADevice) {
  const fs::path fifo = dir_ / "board.toml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::pair<std::string, std::string> boards[] = {
      {fifo.string(), "is a pipe (FIFO), expected a regular file"},
      {dir_.string(), "is a folder, expected a regular file"},
      {"/dev/zero", "is a device, expected a regular file"},
  };
  const std::string programs[] = {std::string(MRD_FIRMWARE) + " --print-state --board ",
                                  std::string(MRD_PLANT_SIM) + " --record r.csv --board ",
                                  std::string(MRD_SIM_BOARD) + " --record r.csv --board "};
  for (const std::string& program : programs) {
    for (const auto& [board, problem] : boards) {
      const Result r = run(within_10_s(program + board));
      EXPECT_EQ(r.exit_code, 2) << program << board << "\n" << r.err;
      EXPECT_EQ(lines(r.err), 1) << r.err;
      EXPECT_NE(r.err.find(board + ": " + problem), std::string::npos) << program << board << "\n" << r.err;
    }
  }
}

// An empty value was taken as "not given": --state '' printed the board's
// state file, --can '' opened the board's interface.
TEST_F(Programs, AnEmptyOptionValueIsAnErrorNamingTheOption) {
  const std::string firmware = std::string(MRD_FIRMWARE) + " --board " + MRD_BOARDS_DIR +
                               "/emulated-arm64/board.toml --print-state";
  const std::pair<std::string, std::string> cases[] = {
      {firmware + " --state ''", "mrd-firmware: error: --state: expected a value, got an empty one"},
      {firmware + " --state " + (dir_ / "state.bin").string() + " --can ''",
       "mrd-firmware: error: --can: expected a value, got an empty one"},
      {firmware + " --state " + (dir_ / "state.bin").string() + " --mode ''",
       "mrd-firmware: error: --mode: expected a value, got an empty one"},
      {std::string(MRD_PLANT_SIM) + " --record r.csv --can ''",
       "mrd-plant-sim: error: --can: expected a value, got an empty one"},
      {std::string(MRD_PLANT_SIM) + " --record r.csv --board ''",
       "mrd-plant-sim: error: --board: expected a value, got an empty one"},
      {std::string(MRD_SIM_BOARD) + " --board " + MRD_BOARDS_DIR + "/sim/board.toml --record r.csv --mode ''",
       "mrd-sim-board: error: --mode: expected a value, got an empty one"},
  };
  for (const auto& [cmd, message] : cases) {
    const Result r = run(within_10_s(cmd));
    EXPECT_EQ(r.exit_code, 2) << cmd << "\n" << r.err;
    EXPECT_EQ(r.err, message + "\n") << cmd;
  }
}

TEST_F(Programs, FirmwareNamesTheCanInterfaceItCannotOpen) {
  const Result r = run(std::string(MRD_FIRMWARE) + " --board " + MRD_BOARDS_DIR + "/emulated-arm64/board.toml --can mrdnone0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(lines(r.err), 1);
  EXPECT_NE(r.err.find("CAN interface 'mrdnone0'"), std::string::npos) << r.err;
}

TEST_F(Programs, PlantSimulatorNamesABadRecord) {
  const auto rec = write("rec.csv", "time_s,accel_m_s2\n0.00,0\n0.01,abc\n");
  const Result r = run(std::string(MRD_PLANT_SIM) + " --record " + rec.string() + " --lockstep");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("rec.csv"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(":3"), std::string::npos) << "names the line: " << r.err;
}

TEST_F(Programs, SimBoardSummaryEqualsMrdSim) {
  const fs::path rec = fs::path(MRD_SHARED_DIR) / "ground_motions" / "hachinohe_ns.csv";
  ASSERT_TRUE(fs::exists(rec)) << "shared Hachinohe record not found at " << rec << " (../shared beside the checkout)";
  const std::string common = " --record " + rec.string() + " --duration-s 10 --idle-years 0.25";
  const Result board = run(std::string(MRD_SIM_BOARD) + " --board " + MRD_BOARDS_DIR + "/sim/board.toml --mode passive-on" + common);
  ASSERT_EQ(board.exit_code, 0) << board.err;
  const Result sim = run(std::string(MRD_BINARY) + " sim --control passive-on --out " + (dir_ / "sim").string() + common);
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto j = nlohmann::json::parse(slurp(dir_ / "sim" / "summary.json"));
  auto value = [&](const std::string& key) {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(board.out, m, std::regex(key + "=([-0-9.eE+]+)"))) << key;
    return m.empty() ? -1.0 : std::stod(m[1]);
  };
  // Both print every double to 17 significant digits: equal text, equal value.
  EXPECT_EQ(value("peak_base_displacement_m"), j.at("peak_base_displacement_m").get<double>());
  EXPECT_EQ(value("peak_damper_force_n") / 1e3, j.at("peak_damper_force_kn").get<double>());
  EXPECT_EQ(value("peak_current_a"), j.at("peak_current_a").get<double>());
  EXPECT_EQ(value("final_participant_ratio"), j.at("final_participant_ratio").get<double>());
}

}  // namespace
