// Board files: every board in boards/ parses; bad files get one line naming
// file, line and field; a board says whether it has GPIO lines; a state path
// that holds a NUL or names a folder, a FIFO or a device is refused.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "firmware/app/board_config.hpp"
#include "firmware/platform/linux/regular_file.hpp"

namespace mrd::app {
namespace {

std::string error_of(const std::string& text, StatePathCheck check = nullptr) {
  try {
    parse_board_config(text, "b.toml", check);
  } catch (const BoardConfigError& e) {
    return e.what();
  }
  return "";
}

/// A board file as the programs read it: under the reader policy, its state path checked.
BoardConfig load_board_file(const std::filesystem::path& path) {
  std::string text;
  const posix::FileCheck c = posix::read_regular_file(path.c_str(), kMaxBoardFileBytes, text);
  if (!c.ok()) throw BoardConfigError(path.string() + ": " + posix::problem_text(c, kMaxBoardFileBytes));
  return parse_board_config(text, path.string(), posix::non_regular_problem);
}

/// Everything but [gpio].
constexpr const char* kMinimal = R"([board]
name = "x"
[control]
[can]
interface = "can0"
)";
constexpr const char* kNoGpio = "[gpio]\nfitted = false\n";

TEST(BoardConfig, MinimalFileTakesTheDefaults) {
  const BoardConfig c = parse_board_config(std::string(kMinimal) + kNoGpio, "b.toml");
  EXPECT_EQ(c.name, "x");
  EXPECT_EQ(c.period_us, 1000u);
  EXPECT_EQ(c.mode, control::ControlMode::kSemiActive);
  EXPECT_EQ(c.nodes.controller, 1);
  EXPECT_EQ(c.nodes.drive, 2);
  EXPECT_FALSE(c.gpio_fitted);
  EXPECT_EQ(c.sched_fifo_priority, 0);
}

TEST(BoardConfig, EveryBoardInTheRepositoryParses) {
  int n = 0;
  for (const auto& d : std::filesystem::directory_iterator(MRD_BOARDS_DIR)) {
    const auto file = d.path() / "board.toml";
    if (!std::filesystem::exists(file)) continue;
    ++n;
    const BoardConfig c = load_board_file(file);
    EXPECT_EQ(c.name, d.path().filename().string()) << file;
  }
  EXPECT_GE(n, 3) << "sim, emulated-arm64 and at least one real board";
}

TEST(BoardConfig, EmulatedBoardUsesVcanAndThePl061) {
  const BoardConfig c = load_board_file(std::filesystem::path(MRD_BOARDS_DIR) / "emulated-arm64" / "board.toml");
  EXPECT_EQ(c.can_interface, "vcan0");
  EXPECT_TRUE(c.gpio_fitted);
  EXPECT_EQ(c.gpio_chip, "gpiochip0");
  EXPECT_EQ(c.drive_enable.offset, 0);
}

TEST(BoardConfig, StateAndMixingTakeTheirDefaultsWhenAbsent) {
  const BoardConfig c = parse_board_config(std::string(kMinimal) + kNoGpio, "b.toml");
  EXPECT_EQ(c.state_path, "/var/lib/mrd/state.bin");
  EXPECT_EQ(c.save_every_s, 3600.0);
  EXPECT_TRUE(c.mixing.actuator_fitted);
  EXPECT_EQ(c.mixing.max_amplitude_m, 0.0762) << "thesis §6.6: ±76.2 mm";
  EXPECT_EQ(c.mixing.preferred_frequency_hz, 0.2) << "thesis §6.6: 0.2 Hz";
}

TEST(BoardConfig, StateAndMixingTablesAreRead) {
  const BoardConfig c = parse_board_config(std::string(kMinimal) + kNoGpio +
                                               "[state]\npath = \"/data/mrd.bin\"\nsave_every_s = 0.5\n"
                                               "[mixing]\nactuator_fitted = false\nholdoff_s = 2\n"
                                               "max_amplitude_m = 0.03\nmax_cycles = 30\ndead_band_m = 2e-4\n",
                                           "b.toml");
  EXPECT_EQ(c.state_path, "/data/mrd.bin");
  EXPECT_EQ(c.save_every_s, 0.5);
  EXPECT_FALSE(c.mixing.actuator_fitted);
  EXPECT_EQ(c.mixing.holdoff_s, 2.0) << "an integer is a number too";
  EXPECT_EQ(c.mixing.max_amplitude_m, 0.03);
  EXPECT_EQ(c.mixing.max_cycles, 30u);
  const MixingTaskConfig t = c.mixing_task_config();
  EXPECT_EQ(t.estimator.period_s, 1e-3);
  EXPECT_EQ(t.estimator.save_interval_s, 0.5);
  EXPECT_EQ(t.estimator.dead_band_m, 2e-4);
  EXPECT_FALSE(t.scheduler.actuator_fitted);
}

TEST(BoardConfig, ARelativeStatePathIsRefused) {
  const std::string e = error_of(std::string(kMinimal) + kNoGpio + "[state]\npath = \"state.bin\"\n");
  EXPECT_EQ(e, "b.toml:9: state.path: expected an absolute file path, got 'state.bin'");
}

TEST(BoardConfig, AMixingSettingOutOfRangeNamesLineFieldAndUnit) {
  const std::string e = error_of(std::string(kMinimal) + kNoGpio + "[mixing]\nmax_amplitude_m = 0.5\n");
  EXPECT_EQ(e, "b.toml:9: mixing.max_amplitude_m: expected 0.001 … 0.2 m, got 0.5");
  const std::string t = error_of(std::string(kMinimal) + kNoGpio + "[mixing]\nholdoff_s = \"soon\"\n");
  EXPECT_EQ(t, "b.toml:9: mixing.holdoff_s: expected a number, s");
  const std::string k = error_of(std::string(kMinimal) + kNoGpio + "[mixing]\nhold_off_s = 2\n");
  EXPECT_EQ(k, "b.toml:9: mixing.hold_off_s: unknown key");
}

TEST(BoardConfig, TheMaintenanceTestBoardRunsItsMixingTask) {
  const BoardConfig c =
      load_board_file(std::filesystem::path(MRD_BOARDS_DIR) / "emulated-arm64" / "maintenance-test.toml");
  EXPECT_GT(c.mixing.confirm_hold_s, fw::IdleModelConfig{}.quiet_close_s) << "mixing_scheduler.hpp's rule";
  // 2π · 1 Hz · 0.03 m = 0.188 m/s, within the plan's 0.19 m/s velocity limit.
  EXPECT_LE(2.0 * 3.141592653589793 * c.mixing.preferred_frequency_hz * c.mixing.max_amplitude_m,
            c.mixing.max_velocity_m_s);
  BasicMixingTask<num::Float32Policy> task;
  EXPECT_TRUE(task.init(c.mixing_task_config()));
}

TEST(BoardConfig, SyntaxErrorNamesTheLine) {
  EXPECT_EQ(error_of("[board]\nname = \"x\"\n[control\n").rfind("b.toml:3: ", 0), 0u) << error_of("[board]\nname = \"x\"\n[control\n");
}

TEST(BoardConfig, WrongTypeNamesLineAndField) {
  const std::string e = error_of(std::string(kMinimal) + "[gpio]\nchip = \"gpiochip0\"\ndrive_enable = 1.5\n");
  EXPECT_EQ(e, "b.toml:8: gpio.drive_enable: expected a line offset (integer) or a line name (string)");
}

TEST(BoardConfig, OutOfRangeNamesLineAndField) {
  const std::string e = error_of("[board]\nname = \"x\"\n[control]\nperiod_us = 50\n[can]\n");
  EXPECT_EQ(e, "b.toml:4: control.period_us: expected 100 … 100000, got 50");
}

TEST(BoardConfig, AFloatWhereAnIntegerGoesIsRefusedWhateverItsSize) {
  // 1e300 is no integer, and beyond int64's range: refused by type, never converted.
  EXPECT_EQ(error_of("[board]\nname = \"x\"\n[control]\nperiod_us = 1e300\n[can]\n"),
            "b.toml:4: control.period_us: expected an integer");
  EXPECT_EQ(error_of("[board]\nname = \"x\"\n[control]\nperiod_us = 1000.0\n[can]\n"),
            "b.toml:4: control.period_us: expected an integer");
}

TEST(BoardConfig, UnknownKeyIsRefused) {
  const std::string e = error_of("[board]\nname = \"x\"\n[control]\nperoid_us = 1000\n[can]\n");
  EXPECT_EQ(e, "b.toml:4: control.peroid_us: unknown key");
}

TEST(BoardConfig, UnknownModeIsRefused) {
  const std::string e = error_of("[board]\nname = \"x\"\n[control]\nmode = \"active\"\n[can]\n");
  EXPECT_EQ(e, "b.toml:4: control.mode: expected passive-off, passive-on or semi-active, got 'active'");
}

TEST(BoardConfig, DuplicateNodeIdsAreRefused) {
  const std::string e = error_of("[board]\nname = \"x\"\n[control]\n[can]\ncontroller_node = 2\n");
  EXPECT_NE(e.find("b.toml:5: can: node ids must be four different numbers"), std::string::npos) << e;
}

TEST(BoardConfig, MissingTableIsNamed) {
  EXPECT_EQ(error_of("[board]\nname = \"x\"\n[can]\n"), "b.toml:1: [control]: missing table");
}

TEST(BoardConfig, AFileThatDoesNotSayWhetherGpioIsFittedIsRefused) {
  EXPECT_EQ(error_of(kMinimal),
            "b.toml:1: [gpio]: missing table (the chip and its lines, or fitted = false for a board without GPIO)");
}

TEST(BoardConfig, NotFittedTakesNoLines) {
  const std::string e = error_of(std::string(kMinimal) + "[gpio]\nfitted = false\nchip = \"gpiochip0\"\n");
  EXPECT_EQ(e, "b.toml:8: gpio.chip: not allowed with fitted = false (a board without GPIO has no lines)");
}

TEST(BoardConfig, FittedMustBeTrueOrFalse) {
  const std::string e = error_of(std::string(kMinimal) + "[gpio]\nfitted = \"no\"\n");
  EXPECT_EQ(e, "b.toml:7: gpio.fitted: expected true or false");
}

TEST(BoardConfig, FittedLinesNeedTheChip) {
  const std::string e = error_of(std::string(kMinimal) + "[gpio]\nfitted = true\ndrive_enable = 0\ndrive_fault = 1\n");
  EXPECT_EQ(e, "b.toml:6: gpio.chip: missing GPIO chip (e.g. \"gpiochip0\")");
}

TEST(BoardConfig, OnlyTheSimBoardHasNoGpio) {
  EXPECT_FALSE(load_board_file(std::filesystem::path(MRD_BOARDS_DIR) / "sim" / "board.toml").gpio_fitted);
  EXPECT_TRUE(load_board_file(std::filesystem::path(MRD_BOARDS_DIR) / "rpi-cm4-mcp2515" / "board.toml").gpio_fitted);
}

TEST(BoardConfig, MissingFileIsNamed) {
  try {
    load_board_file("/nonexistent/board.toml");
    FAIL();
  } catch (const BoardConfigError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/board.toml: file not found");
  }
}

TEST(BoardConfig, AnEmptyStatePathIsRefused) {
  EXPECT_EQ(error_of(std::string(kMinimal) + kNoGpio + "[state]\npath = \"\"\n"),
            "b.toml:9: state.path: expected an absolute file path, got ''");
}

// TOML's \u0000 puts a NUL in the string: the path the system would see ends there.
TEST(BoardConfig, AStatePathHoldingANulIsRefused) {
  EXPECT_EQ(error_of(std::string(kMinimal) + kNoGpio + "[state]\npath = \"/data/a\\u0000b.bin\"\n"),
            "b.toml:9: state.path: expected a file path without a NUL character");
}

class BoardStatePath : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (std::filesystem::temp_directory_path() / "mrd-board-state-XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  static std::string with_state_path(const std::string& path) {
    return std::string(kMinimal) + kNoGpio + "[state]\npath = \"" + path + "\"\n";
  }
  std::filesystem::path dir_;
};

TEST_F(BoardStatePath, AFolderAFifoOrADeviceIsRefusedWithLineAndField) {
  const std::string folder = dir_.string();
  EXPECT_EQ(error_of(with_state_path(folder), posix::non_regular_problem),
            "b.toml:9: state.path: " + folder + ": is a folder, expected a regular file");
  const std::string fifo = (dir_ / "state.bin").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(error_of(with_state_path(fifo), posix::non_regular_problem),
            "b.toml:9: state.path: " + fifo + ": is a pipe (FIFO), expected a regular file");
  EXPECT_EQ(error_of(with_state_path("/dev/null"), posix::non_regular_problem),
            "b.toml:9: state.path: /dev/null: is a device, expected a regular file");
}

TEST_F(BoardStatePath, AMissingOrRegularStateFileIsAccepted) {
  const std::string missing = (dir_ / "state.bin").string();
  EXPECT_EQ(parse_board_config(with_state_path(missing), "b.toml", posix::non_regular_problem).state_path, missing);
  const std::string regular = (dir_ / "old.bin").string();
  { std::ofstream(regular) << "a record"; }
  EXPECT_EQ(parse_board_config(with_state_path(regular), "b.toml", posix::non_regular_problem).state_path, regular);
}

TEST_F(BoardStatePath, ABoardFileThatIsAFifoAFolderOrADeviceIsRefusedUnread) {
  const std::filesystem::path fifo = dir_ / "board.toml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto error_loading = [](const std::filesystem::path& p) {
    try {
      load_board_file(p);
    } catch (const BoardConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_loading(fifo), fifo.string() + ": is a pipe (FIFO), expected a regular file");
  EXPECT_EQ(error_loading(dir_), dir_.string() + ": is a folder, expected a regular file");
  EXPECT_EQ(error_loading("/dev/zero"), "/dev/zero: is a device, expected a regular file");
}

}  // namespace
}  // namespace mrd::app
