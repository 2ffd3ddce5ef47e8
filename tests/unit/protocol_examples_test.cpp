// The example frames of common/protocol/CAN_PROTOCOL.md, asserted byte for
// byte. The expected bytes are read from the spec itself (they were computed
// with an independent bitwise CRC and struct packing, not with this codec),
// so the spec and the codec cannot drift apart.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "mrd/protocol/codec.hpp"
#include "protocol_spec_files.hpp"

namespace mrd::protocol {
namespace {

using spec_files::SpecExample;

std::map<int, SpecExample> read_spec_examples() { return spec_files::read_spec_examples(MRD_PROTOCOL_DIR); }

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

TEST_F(SpecExamples, AllFifteenArePresent) { EXPECT_EQ(examples_.size(), 15u); }

// Examples 12–15 are the RTHS messages (their bytes are asserted against the
// RTHS codec in tests/rths_board/rths_frames_spec_test.cpp); here their
// identifiers: msg id << 4 | sender, the runtime as node 1, the laboratory as 5.
TEST_F(SpecExamples, RthsIdentifiers) {
  ASSERT_EQ(examples_.count(15), 1u);
  EXPECT_EQ(examples_.at(12).id, can_id(MsgId::kRthsCommand, 1));
  EXPECT_EQ(examples_.at(13).id, can_id(MsgId::kRthsMeasurement, 5));
  EXPECT_EQ(examples_.at(14).id, can_id(MsgId::kRthsLabStatus, 5));
  EXPECT_EQ(examples_.at(15).id, can_id(MsgId::kRthsRunStatus, 1));
  // The protocol's CRC over each example as written in the spec.
  for (int n = 12; n <= 15; ++n) {
    EXPECT_EQ(examples_.at(n).data[7], frame_crc(examples_.at(n).id, examples_.at(n).data)) << "example " << n;
  }
}

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
