// Months between boots (label emulated-board): the state on a persistent ext4
// disk and the guest's clock from QEMU's `-rtc base=`
// (scripts/emulated-board/months.sh, board file maintenance-test.toml).
//  boot 1, 2027-01-01: no state → the firmware's documented worst case → a
//    mixing request over CAN → mrd-actuator-sim strokes the damper, its DAQ
//    frames show the stroke → the estimator confirms the cycle and saves;
//    SIGTERM, clean power-off;
//  boot 2, half a Julian year later (182.625 days): the boot line's equivalent
//    idle time grew by the time the board was off (the clock difference
//    between boot 2's start and boot 1's last save) within 1 %, the capacity
//    is below the board's threshold, a mixing request goes out, the cycle is
//    confirmed and saved;
//  boot 3, a minute later: --print-state shows what boot 2 saved.
// Fails when QEMU, the cross compiler, the kernel or mke2fs cannot be had;
// registered in the release build only (tests/integration/CMakeLists.txt).
#include <gtest/gtest.h>

#include "emulated_board_support.hpp"

namespace mrd {
namespace {

using testing::find_line;
using testing::find_lines;
using testing::key_values;
using testing::key_words;

/// `mrd-firmware --print-state` of one boot, before or after the firmware ran.
std::string print_state(const std::string& serial, int boot, const char* when) {
  return find_line(serial, "[boot-" + std::to_string(boot) + "-state-" + when + "] mrd-firmware: state ");
}

/// The guest's Unix time printed by boot N before the firmware started.
double boot_clock_s(const std::string& serial, int boot) {
  const std::string line = find_line(serial, "EMU: boot " + std::to_string(boot) + ": clock ");
  return line.empty() ? -1.0 : std::stod(line.substr(line.find("clock ") + 6));
}

/// `capacity_threshold` of the board file's [mixing] table (-1 when absent).
double capacity_threshold(const testing::fs::path& board) {
  const std::string text = testing::read_text(board);
  std::smatch m;
  if (std::regex_search(text, m, std::regex(R"((^|\n)capacity_threshold\s*=\s*([0-9.eE+-]+))"))) return std::stod(m[2]);
  return -1.0;
}

TEST(EmulatedBoard, MonthsBetweenBootsCountAsIdleTimeAndBringAMixingCycle) {
  const auto out = testing::emulated_out_dir("months");
  ASSERT_TRUE(testing::run_emulated_script("", "months.sh", {out.string()}))
      << "months.sh failed (reason above), see " << out;
  const std::string serial = testing::read_text(out / "serial.txt");

  // Boot 1: no state, the worst case, a mixing cycle confirmed and saved.
  EXPECT_NE(print_state(serial, 1, "before").find(": missing"), std::string::npos) << "a fresh disk";
  const std::string boot1 = find_line(serial, "[boot-1-firmware] mrd-firmware: boot: ");
  ASSERT_FALSE(boot1.empty()) << "no boot line in boot 1";
  std::printf("boot 1: %s\n", boot1.c_str());
  EXPECT_EQ(key_words(boot1)["rtc"], "valid");
  EXPECT_TRUE(std::regex_search(boot1, std::regex(R"(boot: state [^ ]*: missing )"))) << "no state at the first boot";
  EXPECT_FALSE(find_line(serial, "[boot-1-firmware] mrd-firmware: boot: no usable state or clock").empty())
      << "the documented worst case (a fully settled damper)";
  EXPECT_FALSE(testing::find_line_with(serial, "[boot-1-firmware] ", "mixing requested: ").empty());
  const auto saved1 = key_values(print_state(serial, 1, "after"));
  ASSERT_TRUE(saved1.count("seq") && saved1.count("cycles") && saved1.count("idle_years") && saved1.count("rtc_ms"))
      << "boot 1 saved no state: " << print_state(serial, 1, "after");
  EXPECT_GE(saved1.at("cycles"), 1.0) << "the cycle was confirmed";

  // Boot 2: the six months off count as idle time.
  const std::string boot2 = find_line(serial, "[boot-2-firmware] mrd-firmware: boot: ");
  ASSERT_FALSE(boot2.empty()) << "no boot line in boot 2";
  std::printf("boot 2: %s\n", boot2.c_str());
  EXPECT_TRUE(std::regex_search(boot2, std::regex(R"(boot: state [^ ]*: ok ok )"))) << "boot 1's state read back";
  EXPECT_EQ(key_words(boot2)["rtc"], "valid");
  const auto b2 = key_values(boot2);
  ASSERT_TRUE(b2.count("equivalent_idle_years") && b2.count("capacity"));
  // Off time: boot 2's clock before the firmware started minus boot 1's last
  // save (rtc_ms); QEMU's -rtc base= puts them 0.5 Julian years apart, less
  // the seconds boot 1 ran after its start. The firmware reads its clock a
  // moment later than the shell did: well inside 1 %.
  const double off_years = units::s_to_years(boot_clock_s(serial, 2) - saved1.at("rtc_ms") * 1e-3);
  const double gained_years = b2.at("equivalent_idle_years") - saved1.at("idle_years");
  std::printf("boot 2: equivalent idle %.6f years = saved %.6f + %.6f (board off %.6f years by the clocks, "
              "relative %+.2e)\n",
              b2.at("equivalent_idle_years"), saved1.at("idle_years"), gained_years, off_years,
              gained_years / off_years - 1.0);
  EXPECT_NEAR(off_years, 0.5, 0.5 * 0.01) << "the clocks are half a year apart";
  EXPECT_NEAR(gained_years, off_years, 0.01 * off_years);
  const double threshold = capacity_threshold(testing::fs::path(MRD_SOURCE_DIR) / "boards" / "emulated-arm64" /
                                              "maintenance-test.toml");
  ASSERT_GT(threshold, 0.0) << "no capacity threshold in maintenance-test.toml";
  EXPECT_LT(b2.at("capacity"), threshold);
  const std::string request = testing::find_line_with(serial, "[boot-2-firmware] ", "mixing requested: ");
  ASSERT_FALSE(request.empty()) << "no mixing request in boot 2";
  std::printf("boot 2: %s\n", request.c_str());
  const auto saved2 = key_values(print_state(serial, 2, "after"));
  ASSERT_TRUE(saved2.count("seq") && saved2.count("cycles")) << print_state(serial, 2, "after");
  EXPECT_GT(saved2.at("cycles"), saved1.at("cycles")) << "boot 2 confirmed a cycle";
  EXPECT_GT(saved2.at("seq"), saved1.at("seq"));
  EXPECT_FALSE(find_lines(serial, "[boot-2-firmware] mrd-firmware: state saved").empty());
  // The actuator stroked the damper by the requested amplitude; its DAQ
  // frames carry that position (the estimator confirmed the cycle from them).
  double peak_stroke_m = 0.0;
  const std::regex peak_re(R"(peak stroke so far ([0-9.]+) m)");
  for (const auto& line : find_lines(serial, "[boot-2-actuator] ")) {
    std::smatch m;
    if (std::regex_search(line, m, peak_re)) peak_stroke_m = std::max(peak_stroke_m, std::stod(m[1]));
  }
  const double amplitude_m = key_values(request.substr(request.find("mixing requested:"))).at("amplitude_m");
  std::printf("boot 2: actuator peak stroke %.4f m for a requested amplitude of %.4f m\n", peak_stroke_m, amplitude_m);
  EXPECT_GT(amplitude_m, 0.0);
  EXPECT_NEAR(peak_stroke_m, amplitude_m, 0.05 * amplitude_m);

  // Boot 3: the state boot 2 saved.
  const std::string state3 = print_state(serial, 3, "before");
  std::printf("boot 3: %s\n", state3.c_str());
  const auto s3 = key_values(state3);
  ASSERT_TRUE(s3.count("seq") && s3.count("cycles")) << state3;
  EXPECT_EQ(s3.at("seq"), saved2.at("seq"));
  EXPECT_EQ(s3.at("cycles"), saved2.at("cycles"));
}

}  // namespace
}  // namespace mrd
