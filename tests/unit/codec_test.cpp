// The CAN codec: CRC, quantization, round trips and every rejection rule of
// CAN_PROTOCOL.md ("Error handling at the receiver").
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string_view>

#include "mrd/protocol/codec.hpp"

namespace mrd::protocol {
namespace {

constexpr NodeIds kNodes{};

/// Recomputes byte 7 after a test edited a frame on purpose, so that only the
/// edited property is wrong.
void reseal(hal::CanFrame& f) { f.data[7] = frame_crc(f.id, f.data); }

TEST(Crc8, CatalogueCheckValue) {
  // CRC-8/SAE-J1850 in the CRC catalogue (Williams / reveng): check = 0x4B.
  constexpr std::string_view kCheck = "123456789";
  const auto* p = reinterpret_cast<const std::uint8_t*>(kCheck.data());
  EXPECT_EQ(crc8_j1850({p, kCheck.size()}), 0x4B);
}

TEST(Crc8, EmptyInputIsInitXorOut) {
  // No data: the register stays at init 0xFF, final XOR 0xFF gives 0x00.
  EXPECT_EQ(crc8_j1850({}), 0x00);
}

TEST(Codec, CurrentCommandRoundTrip) {
  CurrentCommand in{.current_a = -7.5f, .enable = true, .mode = control::ControlMode::kSemiActive, .counter = 200};
  hal::CanFrame f;
  ASSERT_TRUE(encode(in, kNodes.controller, f));
  EXPECT_EQ(f.id, 0x011u);
  EXPECT_EQ(f.dlc, 8);
  CurrentCommand out;
  ASSERT_EQ(decode(f, kNodes.controller, out), DecodeError::kOk);
  EXPECT_EQ(out.current_a, -7.5f);  // −7500 mA exactly
  EXPECT_TRUE(out.enable);
  EXPECT_EQ(out.mode, control::ControlMode::kSemiActive);
  EXPECT_EQ(out.counter, 200);
}

TEST(Codec, QuantizesToTheNearestMilliampere) {
  // 0.0004 A → 0 mA, 0.0006 A → 1 mA, −0.0006 A → −1 mA (half a count is 0.0005 A).
  const std::pair<float, std::int16_t> cases[] = {{0.0004f, 0}, {0.0006f, 1}, {-0.0006f, -1}, {9.9996f, 10000}};
  for (const auto& [a, raw] : cases) {
    hal::CanFrame f;
    ASSERT_TRUE(encode(CurrentCommand{.current_a = a}, 1, f)) << a;
    EXPECT_EQ(static_cast<std::int16_t>(f.data[0] | (f.data[1] << 8)), raw) << a;
  }
}

TEST(Codec, EncoderRefusesOutOfRangeAndNonFinite) {
  hal::CanFrame f;
  EXPECT_FALSE(encode(CurrentCommand{.current_a = 10.01f}, 1, f));
  EXPECT_FALSE(encode(CurrentCommand{.current_a = -10.01f}, 1, f));
  EXPECT_FALSE(encode(CurrentCommand{.current_a = std::numeric_limits<float>::quiet_NaN()}, 1, f));
  EXPECT_FALSE(encode(CurrentCommand{.current_a = std::numeric_limits<float>::infinity()}, 1, f));
  EXPECT_FALSE(encode(CurrentCommand{.current_a = 1.0f}, 0, f)) << "node 0 is never a sender";
  EXPECT_FALSE(encode(CurrentCommand{.current_a = 1.0f}, 16, f)) << "node ids are 4 bits";
  EXPECT_FALSE(encode(DaqMotion{.damper_disp_m = 0.51f}, 3, f));
  EXPECT_FALSE(encode(DaqMotion{.damper_force_n = 800.1e3f}, 3, f));
  EXPECT_FALSE(encode(DaqAccel{.base_accel_m_s2 = -80.01f}, 3, f));
  EXPECT_FALSE(encode(MixingCommand{.amplitude_m = 0.25f}, 1, f));
  EXPECT_FALSE(encode(DriveStatus{.faults = 0x40}, 2, f));
  EXPECT_TRUE(encode(CurrentCommand{.current_a = 10.0f}, 1, f)) << "the range is inclusive";
}

TEST(Codec, DaqMotionCarriesNotAvailable) {
  DaqMotion in{.damper_disp_m = 0.25f, .disp_valid = false, .damper_force_n = -1234.5f, .force_valid = true};
  hal::CanFrame f;
  ASSERT_TRUE(encode(in, kNodes.daq, f));
  EXPECT_EQ(f.data[0], 0x00);
  EXPECT_EQ(f.data[1], 0x00);
  EXPECT_EQ(f.data[2], 0x80);  // 0x800000
  DaqMotion out;
  ASSERT_EQ(decode(f, kNodes.daq, out), DecodeError::kOk);
  EXPECT_FALSE(out.disp_valid);
  EXPECT_EQ(out.damper_disp_m, 0.0f);
  EXPECT_TRUE(out.force_valid);
  EXPECT_EQ(out.damper_force_n, -1234.5f);  // −12345 counts of 0.1 N
}

TEST(Codec, RoundTripsEveryMessage) {
  hal::CanFrame f;
  DriveStatus ds{.measured_current_a = -29.999f, .setpoint_a = 30.0f, .faults = drive_fault::kCommandTimeout,
                 .state = DriveState::kSafe, .counter = 9};
  ASSERT_TRUE(encode(ds, kNodes.drive, f));
  DriveStatus ds2;
  ASSERT_EQ(decode(f, kNodes.drive, ds2), DecodeError::kOk);
  EXPECT_EQ(ds2.measured_current_a, -29.999f);
  EXPECT_EQ(ds2.setpoint_a, 30.0f);
  EXPECT_EQ(ds2.faults, drive_fault::kCommandTimeout);
  EXPECT_EQ(ds2.state, DriveState::kSafe);

  DaqAccel da{.ground_accel_m_s2 = -79.99999f, .base_accel_m_s2 = 3.14159f, .counter = 1};
  ASSERT_TRUE(encode(da, kNodes.daq, f));
  DaqAccel da2;
  ASSERT_EQ(decode(f, kNodes.daq, da2), DecodeError::kOk);
  EXPECT_NEAR(da2.ground_accel_m_s2, -79.99999f, 0.5e-5);
  EXPECT_NEAR(da2.base_accel_m_s2, 3.14159f, 0.5e-5);

  MixingCommand mc{.action = MixingAction::kStart, .amplitude_m = 0.0762f, .frequency_hz = 0.2f, .duration_s = 600.0f};
  ASSERT_TRUE(encode(mc, kNodes.controller, f));
  MixingCommand mc2;
  ASSERT_EQ(decode(f, kNodes.controller, mc2), DecodeError::kOk);
  EXPECT_EQ(mc2.action, MixingAction::kStart);
  EXPECT_NEAR(mc2.amplitude_m, 0.0762f, 0.5e-5);
  EXPECT_NEAR(mc2.frequency_hz, 0.2f, 0.005);
  EXPECT_EQ(mc2.duration_s, 600.0f);

  MixingStatus ms{.state = MixingState::kAborted, .elapsed_s = 65535.0f, .amplitude_m = 0.2f,
                  .faults = mixing_fault::kVelocityLimit};
  ASSERT_TRUE(encode(ms, kNodes.actuator, f));
  MixingStatus ms2;
  ASSERT_EQ(decode(f, kNodes.actuator, ms2), DecodeError::kOk);
  EXPECT_EQ(ms2.state, MixingState::kAborted);
  EXPECT_EQ(ms2.elapsed_s, 65535.0f);
  EXPECT_EQ(ms2.faults, mixing_fault::kVelocityLimit);

  ControllerStatus cs{.mode = control::ControlMode::kPassiveOn, .flags = controller_flag::kAll, .overruns = 65535,
                      .rejected_frames = 1, .counter = 255};
  ASSERT_TRUE(encode(cs, kNodes.controller, f));
  ControllerStatus cs2;
  ASSERT_EQ(decode(f, kNodes.controller, cs2), DecodeError::kOk);
  EXPECT_EQ(cs2.flags, controller_flag::kAll);
  EXPECT_EQ(cs2.overruns, 65535);
  EXPECT_EQ(cs2.counter, 255);

  SimCoilState sc{.coil_current_a = -2.00001f, .counter = 3};
  ASSERT_TRUE(encode(sc, kNodes.daq, f));
  SimCoilState sc2;
  ASSERT_EQ(decode(f, kNodes.daq, sc2), DecodeError::kOk);
  EXPECT_NEAR(sc2.coil_current_a, -2.00001f, 0.5e-5);

  SimCoilDrive sd{.applied_current_a = 2.5f, .output_on = true, .counter = 4};
  ASSERT_TRUE(encode(sd, kNodes.drive, f));
  SimCoilDrive sd2;
  ASSERT_EQ(decode(f, kNodes.drive, sd2), DecodeError::kOk);
  EXPECT_EQ(sd2.applied_current_a, 2.5f);
  EXPECT_TRUE(sd2.output_on);
}

class CommandFrame : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(encode(CurrentCommand{.current_a = 1.0f, .enable = true, .counter = 5}, kNodes.controller, f_));
  }
  DecodeError decode_f() {
    out_ = CurrentCommand{.current_a = 99.0f};
    return decode(f_, kNodes.controller, out_);
  }
  hal::CanFrame f_;
  CurrentCommand out_;
};

TEST_F(CommandFrame, RejectsWrongLength) {
  for (const std::uint8_t dlc : {std::uint8_t{0}, std::uint8_t{1}, std::uint8_t{7}}) {
    f_.dlc = dlc;
    EXPECT_EQ(decode_f(), DecodeError::kWrongLength) << int(dlc);
    EXPECT_EQ(out_.current_a, 99.0f) << "a rejected frame leaves the output untouched";
  }
}

TEST_F(CommandFrame, RejectsEverySingleBitError) {
  // Any one flipped bit of bytes 0..7 must fail the CRC (CRC-8 detects all
  // single-bit errors).
  for (int byte = 0; byte < 8; ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      hal::CanFrame g = f_;
      g.data[byte] = static_cast<std::uint8_t>(g.data[byte] ^ (1u << bit));
      CurrentCommand out;
      EXPECT_EQ(decode(g, kNodes.controller, out), DecodeError::kBadChecksum) << byte << ":" << bit;
    }
  }
}

TEST_F(CommandFrame, NeverTakesAFrameFromAnotherNode) {
  // The same command, correctly sealed, but sent by node 5: not a command.
  for (std::uint8_t node = 0; node <= kMaxNodeId; ++node) {
    if (node == kNodes.controller) continue;
    f_.id = can_id(MsgId::kCurrentCommand, node);
    reseal(f_);
    EXPECT_EQ(decode_f(), DecodeError::kWrongId) << int(node);
  }
  // Another message with the controller's node id is not a command either.
  f_.id = can_id(MsgId::kControllerStatus, kNodes.controller);
  reseal(f_);
  EXPECT_EQ(decode_f(), DecodeError::kWrongId);
}

TEST_F(CommandFrame, RejectsTheRightPayloadUnderAnotherIdentifier) {
  // A node that copies a valid payload to its own id fails the CRC check,
  // because the CRC covers the identifier; asked as its own sender it is
  // still rejected.
  f_.id = can_id(MsgId::kCurrentCommand, 5);
  CurrentCommand out;
  EXPECT_EQ(decode(f_, 5, out), DecodeError::kBadChecksum);
}

TEST_F(CommandFrame, RejectsExtendedAndRemoteFrames) {
  f_.extended = true;
  EXPECT_EQ(decode_f(), DecodeError::kWrongId);
  f_.extended = false;
  f_.remote = true;
  EXPECT_EQ(decode_f(), DecodeError::kWrongId);
}

TEST_F(CommandFrame, RejectsOutOfRangeCurrent) {
  // 10.001 A = raw 10001 = 0x2711, correctly sealed.
  f_.data[0] = 0x11;
  f_.data[1] = 0x27;
  reseal(f_);
  EXPECT_EQ(decode_f(), DecodeError::kOutOfRange);
  // −10.001 A = raw −10001 = 0xD8EF.
  f_.data[0] = 0xEF;
  f_.data[1] = 0xD8;
  reseal(f_);
  EXPECT_EQ(decode_f(), DecodeError::kOutOfRange);
}

TEST_F(CommandFrame, RejectsReservedBitsAndUndefinedMode) {
  hal::CanFrame good = f_;
  f_.data[2] |= 0x02;
  reseal(f_);
  EXPECT_EQ(decode_f(), DecodeError::kBadField);
  f_ = good;
  f_.data[3] = 3;  // no control mode 3
  reseal(f_);
  EXPECT_EQ(decode_f(), DecodeError::kBadField);
  f_ = good;
  f_.data[5] = 0x01;
  reseal(f_);
  EXPECT_EQ(decode_f(), DecodeError::kBadField);
}

TEST(Codec, DaqRejectsOutOfRangeRaw) {
  // Stroke raw 5000001 (0.5000001 m) = 0x4C4B41, sealed: out of range.
  hal::CanFrame f;
  ASSERT_TRUE(encode(DaqMotion{}, 3, f));
  f.data[0] = 0x41;
  f.data[1] = 0x4B;
  f.data[2] = 0x4C;
  reseal(f);
  DaqMotion out;
  EXPECT_EQ(decode(f, 3, out), DecodeError::kOutOfRange);
}

TEST(Codec, IdleStatusRefusesWhatItCannotCarry) {
  hal::CanFrame f;
  // 2^24 − 1 hours is the largest idle time; a fraction above 1, a scheduler
  // state past 6 or an undefined flag is refused.
  EXPECT_TRUE(encode(IdleStatus{0xFFFFFF, 1.0f, 0.0f, scheduler_state::kMaintenanceRequired, idle_flag::kAll, 0}, 1, f));
  EXPECT_FALSE(encode(IdleStatus{0x1000000, 1.0f, 1.0f, 0, 0, 0}, 1, f));
  EXPECT_FALSE(encode(IdleStatus{0, 1.003f, 1.0f, 0, 0, 0}, 1, f));   // 250.75 counts rounds to 251 > 250
  EXPECT_FALSE(encode(IdleStatus{0, 1.0f, -0.003f, 0, 0, 0}, 1, f));
  EXPECT_FALSE(encode(IdleStatus{0, 1.0f, 1.0f, 7, 0, 0}, 1, f));
  EXPECT_FALSE(encode(IdleStatus{0, 1.0f, 1.0f, 0, 0x08, 0}, 1, f));
  EXPECT_FALSE(encode(IdleStatus{0, std::numeric_limits<float>::quiet_NaN(), 1.0f, 0, 0, 0}, 1, f));

  ASSERT_TRUE(encode(IdleStatus{10, 0.5f, 0.5f, scheduler_state::kDue, 0, 0}, 1, f));
  IdleStatus s;
  hal::CanFrame g = f;
  g.data[5] |= 0x80;  // reserved bit 7
  reseal(g);
  EXPECT_EQ(decode(g, 1, s), DecodeError::kBadField);
  g = f;
  g.data[5] = 0x07;  // scheduler state 7 is undefined
  reseal(g);
  EXPECT_EQ(decode(g, 1, s), DecodeError::kBadField);
  g = f;
  g.data[4] = 251;  // capacity 1.004
  reseal(g);
  EXPECT_EQ(decode(g, 1, s), DecodeError::kOutOfRange);
  EXPECT_EQ(decode(f, 2, s), DecodeError::kWrongId);  // only from the controller's node
}

TEST(CounterCheck, FollowsTheRulesOfTheSpec) {
  CounterCheck c;
  EXPECT_EQ(c.check(250), CounterVerdict::kSynced);
  EXPECT_EQ(c.check(251), CounterVerdict::kAccepted);
  EXPECT_EQ(c.check(251), CounterVerdict::kRepeated);
  EXPECT_EQ(c.check(250), CounterVerdict::kStale) << "one behind: a replay";
  EXPECT_EQ(c.check(255), CounterVerdict::kAccepted) << "3 lost";
  EXPECT_EQ(c.check(0), CounterVerdict::kAccepted) << "wraps 255 → 0";
  EXPECT_EQ(c.check(8), CounterVerdict::kAccepted) << "8 ahead: 7 lost, still accepted";
  EXPECT_EQ(c.check(17), CounterVerdict::kStale) << "9 ahead is too far";
  EXPECT_EQ(c.last(), 8);
  EXPECT_EQ(c.lost_frames(), 3u + 7u);
  c.desync();
  EXPECT_EQ(c.check(100), CounterVerdict::kSynced);
  EXPECT_EQ(c.check(101), CounterVerdict::kAccepted);
}

TEST(CounterCheck, AReplayedOldSequenceIsRejected) {
  CounterCheck c;
  for (int i = 0; i < 40; ++i) ASSERT_TRUE(counter_ok(c.check(static_cast<std::uint8_t>(i))));
  // Replaying frames 10..30 recorded earlier: every one is behind.
  for (int i = 10; i <= 30; ++i) EXPECT_EQ(c.check(static_cast<std::uint8_t>(i)), CounterVerdict::kStale) << i;
}

}  // namespace
}  // namespace mrd::protocol
