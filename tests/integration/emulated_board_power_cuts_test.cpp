// Power cuts while the state is saved (label emulated-board):
// scripts/emulated-board/power-cuts.sh kills QEMU with SIGKILL at a random
// moment while mrd-firmware saves every 10 ms, 20 times, and reads the state
// back at the next boot. Every read-back must be the old or the new valid
// record: none lost, none corrupt. The seed is fixed so that a failure can be
// replayed (`power-cuts.sh --trials 20 --seed 12`).
// Fails when QEMU, the cross compiler, the kernel or mke2fs cannot be had;
// registered in the release build only (tests/integration/CMakeLists.txt).
#include <gtest/gtest.h>

#include "emulated_board_support.hpp"

namespace mrd {
namespace {

constexpr int kTrials = 20;

TEST(EmulatedBoard, PowerCutsWhileSavingLoseNoStateAndCorruptNone) {
  const auto out = testing::emulated_out_dir("power-cuts");
  testing::fs::create_directories(out.parent_path());
  const auto log = out.parent_path() / "power-cuts.log";  // the script empties `out` first
  const bool ok = testing::run_emulated_script(
      "", "power-cuts.sh",
      {"--trials", std::to_string(kTrials), "--seed", "12", "--out", out.string()}, log);
  const std::string text = testing::read_text(log);
  std::printf("%s", text.c_str());
  const auto lines = testing::find_lines(text, "power cuts: ");
  ASSERT_FALSE(lines.empty()) << "power-cuts.sh printed no result";
  EXPECT_EQ(lines.back(), "power cuts: " + std::to_string(kTrials) + " trials, 0 lost, 0 corrupt");
  EXPECT_EQ(static_cast<int>(testing::find_lines(text, "power cuts: trial ").size()), 2 * kTrials)
      << "every trial was cut and read back";
  EXPECT_TRUE(ok) << "power-cuts.sh failed, see " << log;
}

}  // namespace
}  // namespace mrd
