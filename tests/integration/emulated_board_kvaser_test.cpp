// Closed loop over a real CAN controller driver (label emulated-board): QEMU's
// two Kvaser PCI cards (SJA1000) on one emulated bus, Debian's kvaser_pci and
// sja1000 modules, both brought up with the systemd unit's
// `ip link set canX type can bitrate 1000000 restart-ms 100`;
// mrd-firmware on can0, mrd-drive-sim and mrd-plant-sim on can1, in lockstep
// for 10 s of the Hachinohe record (scripts/emulated-board/kvaser.sh).
// Checked here:
//  1. the peaks equal the in-process simulation's with the same tolerances as
//     the vcan run (the frames are the same, only the driver differs);
//  2. `ip -details -statistics link show` reports both controllers
//     ERROR-ACTIVE at 1000000 bit/s with restart-ms 100, and after the runs
//     can0 received every frame can1 sent and the reverse, with no errors,
//     at least as many as the firmware counted (frames_rx; one command a
//     tick sent).
// QEMU models no physical layer (no ACK, no error counters, no bus-off): the
// error paths stay covered by fault injection in the firmware's tests.
// Fails when QEMU, the cross compiler, the kernel or iproute2 cannot be had;
// registered in the release build only (tests/integration/CMakeLists.txt).
#include <gtest/gtest.h>

#include "emulated_board_support.hpp"

namespace mrd {
namespace {

using testing::find_line;
using testing::kGuestDurationS;
using testing::kGuestRuns;
using testing::find_lines;
using testing::key_values;

/// The lines of `ip -details -statistics link show` for one controller.
struct LinkShow {
  std::string text;
  double rx_packets = -1, rx_errors = -1, tx_packets = -1, tx_errors = -1;
};

LinkShow link_show(const std::string& serial, const std::string& tag) {
  LinkShow l;
  const auto lines = find_lines(serial, "[" + tag + "] ");
  for (std::size_t i = 0; i < lines.size(); ++i) {
    l.text += lines[i] + "\n";
    const bool rx = lines[i].find("RX:  bytes packets errors") != std::string::npos;
    const bool tx = lines[i].find("TX:  bytes packets errors") != std::string::npos;
    if ((rx || tx) && i + 1 < lines.size()) {
      std::istringstream nums(lines[i + 1].substr(tag.size() + 2));
      double bytes = 0, packets = 0, errors = 0;
      nums >> bytes >> packets >> errors;
      (rx ? l.rx_packets : l.tx_packets) = packets;
      (rx ? l.rx_errors : l.tx_errors) = errors;
    }
  }
  return l;
}

TEST(EmulatedBoard, ClosedLoopOverKvaserPciSja1000EqualsTheInProcessSimulation) {
  const auto record = testing::hachinohe_record();
  ASSERT_TRUE(testing::fs::exists(record)) << "shared Hachinohe record not found at " << record;
  const auto out = testing::emulated_out_dir("kvaser");
  ASSERT_TRUE(testing::run_emulated_script("MRD_EMU_RUNS='" + testing::runs_argument(kGuestRuns) +
                                               "' MRD_EMU_DURATION_S=" +
                                               std::to_string(static_cast<int>(kGuestDurationS)),
                                           "kvaser.sh", {record.string(), out.string()}))
      << "kvaser.sh failed (reason above), see " << out;
  const std::string serial = testing::read_text(out / "serial.txt");

  // 1. Peaks against the in-process run.
  for (std::size_t i = 0; i < std::size(kGuestRuns); ++i)
    testing::expect_guest_run_equals_in_process(serial, static_cast<int>(i + 1), kGuestRuns[i], record, kGuestDurationS,
                                                "emulated board (Kvaser PCI)");

  // 2. The controllers as the kernel reports them.
  for (const char* tag : {"link-before-can0", "link-before-can1", "link-after-can0", "link-after-can1"}) {
    SCOPED_TRACE(tag);
    const LinkShow l = link_show(serial, tag);
    ASSERT_FALSE(l.text.empty()) << "no ip -details -statistics output";
    std::printf("%s", l.text.c_str());
    EXPECT_NE(l.text.find("can state ERROR-ACTIVE"), std::string::npos);
    EXPECT_NE(l.text.find("restart-ms 100"), std::string::npos);
    EXPECT_TRUE(std::regex_search(l.text, std::regex(R"(\n\[[a-z0-9-]+\] \s+bitrate 1000000 )")));
    EXPECT_NE(l.text.find("sja1000:"), std::string::npos) << "the SJA1000 driver runs the controller";
    EXPECT_EQ(l.rx_errors, 0.0);
    EXPECT_EQ(l.tx_errors, 0.0);
  }
  const LinkShow fw = link_show(serial, "link-after-can0"), peers = link_show(serial, "link-after-can1");
  double fw_ticks = 0, fw_frames_rx = 0;
  for (std::size_t i = 0; i < std::size(kGuestRuns); ++i) {
    const auto s = key_values(find_line(serial, "[run-" + std::to_string(i + 1) + "-firmware] mrd-firmware: summary"));
    ASSERT_FALSE(s.empty());
    fw_ticks += s.at("ticks");
    fw_frames_rx += s.at("frames_rx");
  }
  EXPECT_EQ(fw.rx_packets, peers.tx_packets) << "every frame can1 sent arrived at can0";
  EXPECT_EQ(peers.rx_packets, fw.tx_packets) << "every frame can0 sent arrived at can1";
  EXPECT_GE(fw.rx_packets, fw_frames_rx) << "the firmware received its frames through the controller";
  EXPECT_GE(fw.tx_packets, fw_ticks) << "one command a tick at least";
}

}  // namespace
}  // namespace mrd
