// Power cuts while the state is saved (label emulated-board):
// scripts/emulated-board/power-cuts.sh kills QEMU with SIGKILL at a random
// moment while mrd-firmware saves every 10 ms, 20 times, and reads the state
// back at the next boot. Every read-back must be the old or the new valid
// record: none lost, none corrupt. The seed is fixed so that a failure can be
// replayed (`power-cuts.sh --trials 20 --seed 12`).
// Trial 7's first boot is made to hang before its read-back
// (MRD_EMU_HANG_TRIAL): the script boots it again on the same disk and the
// run still counts every trial; a boot that hangs again on the same disk
// fails the run.
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
  // 30 s: ten times a boot's read-back here (about 3 s).
  const bool ok = testing::run_emulated_script(
      "MRD_EMU_HANG_TRIAL=7 MRD_EMU_READBACK_LIMIT_S=30", "power-cuts.sh",
      {"--trials", std::to_string(kTrials), "--seed", "12", "--out", out.string()}, log);
  const std::string text = testing::read_text(log);
  std::printf("%s", text.c_str());
  const auto lines = testing::find_lines(text, "power cuts: ");
  ASSERT_FALSE(lines.empty()) << "power-cuts.sh printed no result";
  EXPECT_EQ(lines.back(), "power cuts: " + std::to_string(kTrials) + " trials, 0 lost, 0 corrupt");
  EXPECT_EQ(static_cast<int>(testing::find_lines(text, "power cuts: trial ").size()), 2 * kTrials)
      << "every trial was cut and read back";
  const auto hung = testing::find_lines(text, "power cuts: boot of trial ");
  ASSERT_EQ(hung.size(), 1u) << "the one hung boot was booted again";
  EXPECT_EQ(hung[0].rfind("power cuts: boot of trial 7 hung before its read-back", 0), 0u) << hung[0];
  EXPECT_EQ(testing::find_lines(text, "power cuts: 1 boot(s) hung before their read-back and were booted again").size(),
            1u);
  EXPECT_TRUE(ok) << "power-cuts.sh failed, see " << log;
}

// A boot that hangs again on the same disk is what a state that hangs the
// reader would do: the run fails and says so. Both boots are made to hang,
// so a 5 s limit never cuts a boot that would have read the state.
TEST(EmulatedBoard, PowerCutsFailWhenABootHangsTwiceOnTheSameDisk) {
  const auto out = testing::emulated_out_dir("power-cuts-hang");
  testing::fs::create_directories(out.parent_path());
  const auto log = out.parent_path() / "power-cuts-hang.log";
  const bool ok = testing::run_emulated_script("MRD_EMU_HANG_TRIAL=1:2 MRD_EMU_READBACK_LIMIT_S=5", "power-cuts.sh",
                                               {"--trials", "1", "--seed", "12", "--out", out.string()}, log);
  const std::string text = testing::read_text(log);
  std::printf("%s", text.c_str());
  EXPECT_FALSE(ok) << "a boot that hung twice on the same disk must fail the run";
  EXPECT_EQ(testing::find_lines(text, "power cuts: boot of trial 1 hung before its read-back").size(), 1u);
  EXPECT_NE(text.find("emulated-board: FAIL: trial 1: the boot hung before its read-back again"), std::string::npos)
      << text;
  EXPECT_TRUE(testing::find_lines(text, "power cuts: 1 trials, ").empty()) << "no result for a failed run";
}

}  // namespace
}  // namespace mrd
