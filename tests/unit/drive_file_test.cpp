// The drive file of --drive: the shipped thesis drive reads to exactly the
// compiled-in drive and to the numbers of thesis §3.2 (a 72 V supply, 15 A
// continuous, 30 A peak, ±10 V at 1 V/A), which are also the controller's
// default limits; a drive read from a file drives the coil as a hand
// calculation says (a saturated bridge charging an R–L coil; a command range
// that clips the reference); a loop the coil makes ring is refused with its
// line; every kind of bad file is refused with "<file>:<line>: <field>: ...".

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "firmware/core/controller_config.hpp"
#include "file_text_helpers.hpp"
#include "host_sim/drive/drive_file.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/plant/pwm_drive.hpp"

namespace mrd::drive {
namespace {

using test::edited;
using test::file_text;
using test::line_of;

namespace fs = std::filesystem;

const fs::path kThesisDrive = fs::path(MRD_DRIVES_DIR) / "thesis-pwm.toml";

/// The error of parsing `text` (empty when it parses).
std::string error_of(const std::string& text) { return test::parse_error_of(&parse_drive_toml, text, "d.toml"); }

TEST(DriveFile, TheThesisFileIsTheCompiledInDriveAndSection32s) {
  const DriveFile f = read_drive_file(kThesisDrive);
  const DriveFile t = thesis_drive();
  EXPECT_EQ(f.name, t.name);
  EXPECT_EQ(f.source, t.source);
  const plant::PwmDriveParams &a = f.params, &b = t.params;
  EXPECT_EQ(a.bus_v, b.bus_v);
  EXPECT_EQ(a.command_limit_v, b.command_limit_v);
  EXPECT_EQ(a.volts_per_amp, b.volts_per_amp);
  EXPECT_EQ(a.continuous_current_a, b.continuous_current_a);
  EXPECT_EQ(a.peak_current_a, b.peak_current_a);
  EXPECT_EQ(a.peak_time_s, b.peak_time_s);
  EXPECT_EQ(a.loop_bandwidth_rad_s, b.loop_bandwidth_rad_s);
  EXPECT_EQ(a.substep_s, b.substep_s);
  // Thesis §3.2: "a 72V DC output to the 30A8 analog servo-drive, which has a
  // maximum continuous current of 15 A and a maximum peak output of 30 A ...
  // A command signal of ± 10 V ... with a ratio of 1 V / 1 A".
  EXPECT_EQ(a.bus_v, 72.0);
  EXPECT_EQ(a.continuous_current_a, 15.0);
  EXPECT_EQ(a.peak_current_a, 30.0);
  EXPECT_EQ(command_limit_a(a), 10.0);
  // The controller's default limits are this drive's.
  const fw::ControllerConfig c{};
  EXPECT_EQ(c.command_limit_a, command_limit_a(a));
  EXPECT_EQ(c.drive_continuous_limit_a, a.continuous_current_a);
  EXPECT_EQ(c.drive_peak_limit_a, a.peak_current_a);
}

// A 6 V bus on a 4.8 Ω coil of constant 2 H (L(1 A) = L(2 A)), commanded
// 2.5 A: K_p = 2 H · 200 rad/s = 400 V/A asks for hundreds of volts, so the
// bridge stays at +6 V and the coil charges as an R–L circuit,
// i(t) = (6/4.8)(1 − e^{−t·4.8/2}): 1.25 (1 − e^{−2.4}) = 1.136603 A at 1 s.
TEST(DriveFile, ASaturatedBusChargesTheCoilAsAnRLCircuit) {
  const std::string text = edited(file_text(kThesisDrive), "bus_v = 72.0", "bus_v = 6.0");
  const DriveFile d = parse_drive_toml(text, "low.toml");
  plant::PwmDrive drive(d.params, plant::CoilParams{4.8, 2.0, 2.0, 0.5});
  for (int k = 0; k < 1000; ++k) (void)drive.step(plant::CoilDrive{2.5, true}, 1e-3);
  EXPECT_NEAR(drive.current_a(), 1.25 * (1.0 - std::exp(-2.4)), 1e-6);
  EXPECT_EQ(drive.voltage_v(), 6.0);
}

// ±5 V at 2 V/A: a 4 A command is 8 V, clipped to 5 V, a reference of 2.5 A;
// with 72 V on the bus the loop settles there (5 ms lag; 10 s is 2000 of them
// and 7 coil time constants L(0)/R past the integrator's takeover).
TEST(DriveFile, TheCommandRangeClipsTheReference) {
  std::string text = file_text(kThesisDrive);
  text = edited(text, "command_range_v = 10.0", "command_range_v = 5.0");
  text = edited(text, "volts_per_amp = 1.0", "volts_per_amp = 2.0");
  const DriveFile d = parse_drive_toml(text, "scaled.toml");
  EXPECT_EQ(command_limit_a(d.params), 2.5);
  plant::PwmDrive drive(d.params, plant::CoilParams{});
  EXPECT_EQ(drive.reference_a(4.0), 2.5);
  EXPECT_EQ(drive.reference_a(-1.0), -1.0);
  for (int k = 0; k < 10000; ++k) (void)drive.step(plant::CoilDrive{4.0, true}, 1e-3);
  EXPECT_NEAR(drive.current_a(), 2.5, 1e-3);
}

// The sampled loop moves the current by K_p T / L_min = ω_c L(1 A) T / L_min of
// its error per period: 5 H · 200 rad/s · 0.1 ms / 0.5 H = 0.2 for the thesis
// drive on the thesis coil; at 5000 rad/s it is 5, and the largest bandwidth
// that keeps it at 1 is 0.5 / (5 · 1e-4) = 1000 rad/s.
TEST(DriveFile, ALoopTheCoilMakesRingIsRefusedWithItsLine) {
  EXPECT_TRUE(check_drive_fit(thesis_drive(), plant::CoilParams{}, 2.5, 1e-3).empty());
  const std::string text =
      edited(file_text(kThesisDrive), "loop_bandwidth_rad_s = 200.0", "loop_bandwidth_rad_s = 5000.0");
  const DriveFile d = parse_drive_toml(text, "fast.toml");
  std::string e;
  try {
    (void)check_drive_fit(d, plant::CoilParams{}, 2.5, 1e-3);
  } catch (const io::UsageError& x) {
    e = x.what();
  }
  const std::string at = "fast.toml:" + std::to_string(line_of(text, "loop_bandwidth_rad_s")) +
                         ": drive.loop_bandwidth_rad_s: expected at most 1000 rad/s";
  EXPECT_EQ(e.rfind(at, 0), 0u) << e;
  EXPECT_NE(e.find("K_p T / L = 5 "), std::string::npos) << e;
  // 1000 rad/s is the edge: accepted.
  const DriveFile edge = parse_drive_toml(
      edited(file_text(kThesisDrive), "loop_bandwidth_rad_s = 200.0", "loop_bandwidth_rad_s = 1000.0"), "edge.toml");
  EXPECT_NO_THROW((void)check_drive_fit(edge, plant::CoilParams{}, 2.5, 1e-3));
}

// 12 V over 12 Ω drives at most 1 A, below a 2 A rating; a 0.3 ms loop does
// not divide a 1 ms step and runs at 1/3 ms.
TEST(DriveFile, ABusShortOfTheRatingAndAnUnevenLoopAreSaid) {
  std::string text = file_text(kThesisDrive);
  text = edited(text, "bus_v = 72.0", "bus_v = 12.0");
  text = edited(text, "loop_period_s = 0.0001", "loop_period_s = 0.0003");
  const std::vector<std::string> w =
      check_drive_fit(parse_drive_toml(text, "d.toml"), plant::CoilParams{12.0, 1.0, 0.8, 0.5}, 2.0, 1e-3);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0], "drive: the 12 V bus drives at most 1 A through the coil's 12 ohm, below the damper's rated 2 A");
  EXPECT_EQ(w[1], "drive: loop_period_s 0.0003 s is not a whole fraction of the 0.001 s step: the current loop runs at "
                  "0.0003333 s");
}

TEST(DriveFile, AMissingFileIsNamed) {
  try {
    (void)read_drive_file("no-such-drive.toml");
    FAIL() << "read";
  } catch (const io::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-drive.toml"), std::string::npos) << e.what();
  }
}

TEST(DriveFile, RefusesBadFilesNamingFileLineAndField) {
  const std::string t = file_text(kThesisDrive);
  const std::vector<test::Refusal> cases = {
      {"syntax error", edited(t, "bus_v = 72.0", "bus_v = 72.0.0"), "bus_v", "", ""},
      {"unknown table", t + "\n[drives]\nname = \"x\"\n", "[drives]", "drives", "unknown table (expected drive)"},
      {"unknown key", edited(t, "bus_v = 72.0", "bus_v = 72.0\nsupply_v = 72.0"), "supply_v", "drive.supply_v",
       "unknown key"},
      {"missing key", edited(t, "peak_time_s = 2.0", ""), "[drive]", "drive.peak_time_s", "missing key"},
      {"wrong type", edited(t, "bus_v = 72.0", "bus_v = \"72 V\""), "bus_v", "drive.bus_v", "expected a number"},
      {"non-finite", edited(t, "volts_per_amp = 1.0", "volts_per_amp = nan"), "volts_per_amp", "drive.volts_per_amp",
       "expected a finite number"},
      {"bus of 0.5 V", edited(t, "bus_v = 72.0", "bus_v = 0.5"), "bus_v", "drive.bus_v",
       "expected a voltage in [1, 1000] V, got 0.5"},
      {"negative continuous current", edited(t, "continuous_current_a = 15.0", "continuous_current_a = -15.0"),
       "continuous_current_a", "drive.continuous_current_a", "expected a current in [0.001, 1000] A, got -15.0"},
      {"peak below continuous", edited(t, "peak_current_a = 30.0", "peak_current_a = 10.0"), "peak_current_a",
       "drive.peak_current_a", "expected at least continuous_current_a (15.0 A)"},
      {"loop period of 0.1 s", edited(t, "loop_period_s = 0.0001", "loop_period_s = 0.1"), "loop_period_s",
       "drive.loop_period_s", "expected a time in [1e-07, 0.01] s, got 0.1"},
      {"bandwidth 0", edited(t, "loop_bandwidth_rad_s = 200.0", "loop_bandwidth_rad_s = 0.0"), "loop_bandwidth_rad_s",
       "drive.loop_bandwidth_rad_s", "expected a bandwidth in [1, 1e+06] rad/s, got 0.0"},
  };
  test::expect_refusals(cases, error_of, "d.toml");
  EXPECT_EQ(error_of(""), "d.toml:1: [drive]: missing table");
}

}  // namespace
}  // namespace mrd::drive
