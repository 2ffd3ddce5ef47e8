// Closed loop on a real Linux kernel (label emulated-board): the cross-built
// mrd-firmware, mrd-drive-sim and mrd-plant-sim run in Debian's arm64 kernel
// under QEMU, over SocketCAN (vcan0) and the PL061 GPIO chip, in lockstep for
// 10 s of the Hachinohe record (scripts/emulated-board/run.sh). Checked here:
//  1. the peaks equal the in-process simulation's (with the frames'
//     quantization applied, run::WireQuantizedController) to the last-bit differences
//     between aarch64 and x86-64 libm and Eigen (the cross build contracts no
//     multiply-add: cmake/toolchain-aarch64.cmake): passive-on (idle 0.25
//     years, coil and mixing dynamics active) and semi-active (idle 0.5 years)
//     within relative 1e-9. A last-bit difference that moved a sensor value
//     across a float or 0.1 µm rounding boundary, so that the switching law
//     (ODBDCO) took another branch for a tick, would fail here: a difference
//     to explain, not to tolerate. Measured on Hachinohe, 10 s: at most
//     1.9e-12 (passive-on) and 1.4e-12 (semi-active);
//  2. the drive-enable line was driven: the kernel's own view
//     (/sys/kernel/debug/gpio) shows line 0 held high by mrd-firmware;
//  3. after `kill -9` of the free-running firmware the drive applies its safe
//     current at its first tick past the 20 ms timeout.
// Fails when QEMU, the cross compiler or the kernel cannot be had; registered
// in the release build only (tests/integration/CMakeLists.txt).
#include <gtest/gtest.h>

#include "emulated_board_support.hpp"

namespace mrd {
namespace {

using testing::find_line;
using testing::kGuestDurationS;
using testing::kGuestRuns;
using testing::key_values;

TEST(EmulatedBoard, ClosedLoopOverSocketCanEqualsTheInProcessSimulation) {
  const auto record = testing::hachinohe_record();
  ASSERT_TRUE(testing::fs::exists(record)) << "shared Hachinohe record not found at " << record;
  const auto out = testing::emulated_out_dir("vcan");
  ASSERT_TRUE(testing::run_emulated_script("MRD_EMU_RUNS='" + testing::runs_argument(kGuestRuns) +
                                               "' MRD_EMU_DURATION_S=" +
                                               std::to_string(static_cast<int>(kGuestDurationS)),
                                           "run.sh", {record.string(), out.string()}))
      << "run.sh failed (reason above), see " << out;
  const std::string serial = testing::read_text(out / "serial.txt");

  // 1. Peaks against the in-process run with the same quantization.
  for (std::size_t i = 0; i < std::size(kGuestRuns); ++i)
    testing::expect_guest_run_equals_in_process(serial, static_cast<int>(i + 1), kGuestRuns[i], record, kGuestDurationS,
                                                "emulated board (vcan)");

  // 2. The kernel saw line 0 of the PL061 driven high by mrd-firmware.
  const std::smatch chip = [&] {
    std::smatch m;
    std::regex_search(serial, m, std::regex(R"(\[run-1-gpio\] gpiochip0: GPIOs (\d+)-(\d+))"));
    return m;
  }();
  ASSERT_FALSE(chip.empty()) << "no /sys/kernel/debug/gpio snapshot";
  const int base = std::stoi(chip[1]);
  const std::regex enable_line("\\[run-1-gpio\\] +gpio-" + std::to_string(base) +
                               R"( \([^|]*\|mrd-firmware *\) out hi)");
  EXPECT_TRUE(std::regex_search(serial, enable_line)) << "drive-enable (line 0) not held high by mrd-firmware";

  // 3. Command stream cut: fallback at the drive's first tick past the timeout.
  const auto cut = key_values(find_line(serial, "[cut-drive] mrd-drive-sim: summary"));
  ASSERT_FALSE(cut.empty()) << "no drive summary from the cut phase";
  EXPECT_NE(find_line(serial, "[cut-drive] mrd-drive-sim: summary").find("final_state=safe"), std::string::npos);
  EXPECT_GT(cut.at("accepted"), 100.0) << "the drive followed the firmware before the cut";
  const double latency = cut.at("last_fallback_latency_ms"), gap = cut.at("last_fallback_tick_gap_ms");
  const double timeout = cut.at("timeout_ms");
  std::printf("command cut: safe current %.3f ms after the last valid command (timeout %.1f ms, drive tick gap "
              "%.3f ms; documented bound on hardware: timeout + 1 ms)\n", latency, timeout, gap);
  EXPECT_GT(latency, timeout);
  EXPECT_LE(latency, timeout + gap + 1e-3);
}

}  // namespace
}  // namespace mrd
