// The example frames of common/protocol/CAN_PROTOCOL.md, asserted byte for
// byte. The expected bytes are read from the spec itself (they were computed
// with an independent bitwise CRC and struct packing, not with this codec),
// so the spec and the codec cannot drift apart.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "mrd/protocol/codec.hpp"

namespace mrd::protocol {
namespace {

struct SpecExample {
  std::uint32_t id = 0;
  std::array<std::uint8_t, 8> data{};
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" `");
  const auto e = s.find_last_not_of(" `");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

/// Rows "| n | message | values | 0xID | `B0 .. B7` |" of the "Example frames" section.
std::map<int, SpecExample> read_spec_examples() {
  std::ifstream in(std::string(MRD_PROTOCOL_DIR) + "/CAN_PROTOCOL.md");
  std::map<int, SpecExample> out;
  std::string line;
  bool in_section = false;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) in_section = line == "## Example frames";
    if (!in_section || line.size() < 2 || line[0] != '|') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line.substr(1));
    std::string cell;
    while (std::getline(ss, cell, '|')) cells.push_back(trim(cell));
    if (cells.size() < 5 || cells[0].empty() || !std::isdigit(static_cast<unsigned char>(cells[0][0]))) continue;
    SpecExample ex;
    ex.id = static_cast<std::uint32_t>(std::stoul(cells[3], nullptr, 16));
    std::stringstream bytes(cells[4]);
    for (auto& b : ex.data) {
      std::string hex;
      bytes >> hex;
      b = static_cast<std::uint8_t>(std::stoul(hex, nullptr, 16));
    }
    out[std::stoi(cells[0])] = ex;
  }
  return out;
}

class SpecExamples : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { examples_ = read_spec_examples(); }
  static std::map<int, SpecExample> examples_;

  void expect_frame(int n, const hal::CanFrame& f) {
    ASSERT_TRUE(examples_.count(n)) << "example " << n << " missing from CAN_PROTOCOL.md";
    const SpecExample& ex = examples_.at(n);
    EXPECT_EQ(f.id, ex.id) << "example " << n;
    EXPECT_EQ(f.dlc, 8) << "example " << n;
    for (int i = 0; i < 8; ++i) EXPECT_EQ(f.data[i], ex.data[i]) << "example " << n << " byte " << i;
  }
  hal::CanFrame spec_frame(int n) {
    hal::CanFrame f;
    f.id = examples_.at(n).id;
    f.dlc = 8;
    f.data = examples_.at(n).data;
    return f;
  }
};
std::map<int, SpecExample> SpecExamples::examples_;

TEST_F(SpecExamples, AllElevenArePresent) { EXPECT_EQ(examples_.size(), 11u); }

TEST_F(SpecExamples, CurrentCommands) {
  hal::CanFrame f;
  ASSERT_TRUE(encode(CurrentCommand{2.5f, true, control::ControlMode::kPassiveOn, 0x2A}, 1, f));
  expect_frame(1, f);
  ASSERT_TRUE(encode(CurrentCommand{-1.234f, true, control::ControlMode::kSemiActive, 0xFF}, 1, f));
  expect_frame(2, f);
  CurrentCommand c;
  ASSERT_EQ(decode(spec_frame(2), 1, c), DecodeError::kOk);
  EXPECT_FLOAT_EQ(c.current_a, -1.234f);
  EXPECT_EQ(c.counter, 0xFF);
}

TEST_F(SpecExamples, IdleStatus) {
  hal::CanFrame f;
  ASSERT_TRUE(encode(IdleStatus{4383, 0.6f, 0.784f, scheduler_state::kRequested, idle_flag::kClockInvalid, 0x11}, 1, f));
  expect_frame(11, f);
  IdleStatus s;
  ASSERT_EQ(decode(spec_frame(11), 1, s), DecodeError::kOk);
  EXPECT_EQ(s.equivalent_idle_h, 4383u);
  EXPECT_FLOAT_EQ(s.participant_ratio, 0.6f);
  EXPECT_FLOAT_EQ(s.capacity_fraction, 0.784f);
  EXPECT_EQ(s.scheduler, scheduler_state::kRequested);
  EXPECT_EQ(s.flags, idle_flag::kClockInvalid);
}

TEST_F(SpecExamples, DriveStatus) {
  hal::CanFrame f;
  ASSERT_TRUE(encode(DriveStatus{2.481f, 2.5f, 0, DriveState::kFollowing, 7}, 2, f));
  expect_frame(3, f);
}

TEST_F(SpecExamples, DaqFrames) {
  hal::CanFrame f;
  ASSERT_TRUE(encode(DaqMotion{0.0123456f, true, -150000.5f, true, 0x10}, 3, f));
  expect_frame(4, f);
  ASSERT_TRUE(encode(DaqAccel{1.10523f, true, 0.0f, false, 0x10}, 3, f));
  expect_frame(5, f);
  DaqMotion m;
  ASSERT_EQ(decode(spec_frame(4), 3, m), DecodeError::kOk);
  EXPECT_NEAR(m.damper_disp_m, 0.0123456, 1e-9);
  EXPECT_FLOAT_EQ(m.damper_force_n, -150000.5f);
  DaqAccel a;
  ASSERT_EQ(decode(spec_frame(5), 3, a), DecodeError::kOk);
  EXPECT_FALSE(a.base_valid);
}

TEST_F(SpecExamples, MixingFrames) {
  hal::CanFrame f;
  ASSERT_TRUE(encode(MixingCommand{MixingAction::kStart, 0.0762f, 0.2f, 300.0f, 1}, 1, f));
  expect_frame(6, f);
  ASSERT_TRUE(encode(MixingStatus{MixingState::kRunning, 42.0f, 0.07619f, 0, 3}, 4, f));
  expect_frame(7, f);
}

TEST_F(SpecExamples, ControllerStatus) {
  hal::CanFrame f;
  ASSERT_TRUE(encode(ControllerStatus{control::ControlMode::kSemiActive, controller_flag::kDriveEnabled, 3, 258, 0x80},
                     1, f));
  expect_frame(8, f);
}

TEST_F(SpecExamples, SimulationFrames) {
  hal::CanFrame f;
  ASSERT_TRUE(encode(SimCoilState{2.49999f, 0xFE}, 3, f));
  expect_frame(9, f);
  ASSERT_TRUE(encode(SimCoilDrive{2.5f, true, 5}, 2, f));
  expect_frame(10, f);
}

}  // namespace
}  // namespace mrd::protocol
