// mrd.dbc mirrors CAN_PROTOCOL.md: every DBC message has the identifier of the
// spec, and decoding the spec's example frames with the DBC's own signal
// definitions (start bit, length, sign, factor — the way a CAN tool does)
// gives the values the codec decodes. The RTHS messages' values are checked
// against their own codec in tests/rths_board/rths_frames_spec_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "mrd/protocol/codec.hpp"
#include "protocol_spec_files.hpp"

namespace mrd::protocol {
namespace {

using spec_files::dbc_value;
using spec_files::DbcMessage;

std::map<std::string, DbcMessage> read_dbc() { return spec_files::read_dbc(MRD_PROTOCOL_DIR); }

using Values = std::map<std::string, double>;

/// What the codec decodes from a frame, named as the DBC names the signals.
std::function<Values(const hal::CanFrame&)> codec_view(const std::string& msg) {
  auto bit = [](unsigned v, int b) { return static_cast<double>((v >> b) & 1u); };
  if (msg == "CurrentCommand")
    return [](const hal::CanFrame& f) {
      CurrentCommand c;
      EXPECT_EQ(decode(f, 1, c), DecodeError::kOk);
      return Values{{"current_cmd", c.current_a}, {"enable", c.enable}, {"mode", double(c.mode)}, {"counter", c.counter}};
    };
  if (msg == "DriveStatus")
    return [bit](const hal::CanFrame& f) {
      DriveStatus s;
      EXPECT_EQ(decode(f, 2, s), DecodeError::kOk);
      return Values{{"measured_current", s.measured_current_a}, {"setpoint", s.setpoint_a},
                    {"fault_over_current", bit(s.faults, 0)}, {"fault_over_temperature", bit(s.faults, 1)},
                    {"fault_under_voltage", bit(s.faults, 2)}, {"fault_command_timeout", bit(s.faults, 3)},
                    {"fault_command_rejected", bit(s.faults, 4)}, {"fault_line", bit(s.faults, 5)},
                    {"state", double(s.state)}, {"counter", s.counter}};
    };
  if (msg == "DaqMotion")
    return [](const hal::CanFrame& f) {
      DaqMotion s;
      EXPECT_EQ(decode(f, 3, s), DecodeError::kOk);
      Values v{{"damper_disp", s.damper_disp_m}, {"damper_force", s.damper_force_n}, {"counter", s.counter}};
      if (!s.disp_valid) v.erase("damper_disp");  // the "not available" code has no physical value
      if (!s.force_valid) v.erase("damper_force");
      return v;
    };
  if (msg == "DaqAccel")
    return [](const hal::CanFrame& f) {
      DaqAccel s;
      EXPECT_EQ(decode(f, 3, s), DecodeError::kOk);
      Values v{{"ground_accel", s.ground_accel_m_s2}, {"base_accel", s.base_accel_m_s2}, {"counter", s.counter}};
      if (!s.ground_valid) v.erase("ground_accel");
      if (!s.base_valid) v.erase("base_accel");
      return v;
    };
  if (msg == "MixingCommand")
    return [](const hal::CanFrame& f) {
      MixingCommand s;
      EXPECT_EQ(decode(f, 1, s), DecodeError::kOk);
      return Values{{"action", double(s.action)}, {"amplitude", s.amplitude_m}, {"frequency", s.frequency_hz},
                    {"duration", s.duration_s}, {"counter", s.counter}};
    };
  if (msg == "MixingStatus")
    return [bit](const hal::CanFrame& f) {
      MixingStatus s;
      EXPECT_EQ(decode(f, 4, s), DecodeError::kOk);
      return Values{{"state", double(s.state)}, {"elapsed", s.elapsed_s}, {"amplitude", s.amplitude_m},
                    {"fault_stroke_limit", bit(s.faults, 0)}, {"fault_velocity_limit", bit(s.faults, 1)},
                    {"fault_command_timeout", bit(s.faults, 2)}, {"counter", s.counter}};
    };
  if (msg == "ControllerStatus")
    return [bit](const hal::CanFrame& f) {
      ControllerStatus s;
      EXPECT_EQ(decode(f, 1, s), DecodeError::kOk);
      return Values{{"mode", double(s.mode)}, {"flag_drive_enabled", bit(s.flags, 0)},
                    {"flag_sensor_timeout", bit(s.flags, 1)}, {"flag_drive_fault", bit(s.flags, 2)},
                    {"flag_drive_silent", bit(s.flags, 3)}, {"flag_bus_error", bit(s.flags, 4)},
                    {"flag_maintenance_due", bit(s.flags, 5)}, {"overruns", s.overruns},
                    {"rejected_frames", s.rejected_frames}, {"counter", s.counter}};
    };
  if (msg == "IdleStatus")
    return [bit](const hal::CanFrame& f) {
      IdleStatus s;
      EXPECT_EQ(decode(f, 1, s), DecodeError::kOk);
      return Values{{"equivalent_idle", double(s.equivalent_idle_h)}, {"participant_ratio", s.participant_ratio},
                    {"capacity", s.capacity_fraction}, {"scheduler", s.scheduler},
                    {"flag_assumed_settled", bit(s.flags, 0)}, {"flag_clock_invalid", bit(s.flags, 1)},
                    {"flag_save_failed", bit(s.flags, 2)}, {"counter", s.counter}};
    };
  if (msg == "SimCoilState")
    return [](const hal::CanFrame& f) {
      SimCoilState s;
      EXPECT_EQ(decode(f, 3, s), DecodeError::kOk);
      return Values{{"coil_current", s.coil_current_a}, {"counter", s.counter}};
    };
  if (msg == "SimCoilDrive")
    return [](const hal::CanFrame& f) {
      SimCoilDrive s;
      EXPECT_EQ(decode(f, 2, s), DecodeError::kOk);
      return Values{{"applied_current", s.applied_current_a}, {"output_on", s.output_on}, {"counter", s.counter}};
    };
  return nullptr;
}

struct Expected {
  const char* name;
  MsgId msg;
  std::uint8_t node;
};
constexpr Expected kMessages[] = {
    {"CurrentCommand", MsgId::kCurrentCommand, 1}, {"DriveStatus", MsgId::kDriveStatus, 2},
    {"DaqMotion", MsgId::kDaqMotion, 3},           {"DaqAccel", MsgId::kDaqAccel, 3},
    {"MixingCommand", MsgId::kMixingCommand, 1},   {"MixingStatus", MsgId::kMixingStatus, 4},
    {"ControllerStatus", MsgId::kControllerStatus, 1}, {"SimCoilState", MsgId::kSimCoilState, 3},
    {"SimCoilDrive", MsgId::kSimCoilDrive, 2},     {"IdleStatus", MsgId::kIdleStatus, 1},
    // RTHS: the runtime sends as the controller (1), the laboratory as node 5.
    {"RthsCommand", MsgId::kRthsCommand, 1},       {"RthsMeasurement", MsgId::kRthsMeasurement, 5},
    {"RthsLabStatus", MsgId::kRthsLabStatus, 5},   {"RthsRunStatus", MsgId::kRthsRunStatus, 1},
};

TEST(Dbc, HasEveryMessageWithTheSpecIdentifier) {
  const auto dbc = read_dbc();
  ASSERT_EQ(dbc.size(), std::size(kMessages));
  for (const auto& e : kMessages) {
    ASSERT_TRUE(dbc.count(e.name)) << e.name;
    EXPECT_EQ(dbc.at(e.name).id, can_id(e.msg, e.node)) << e.name;
    EXPECT_EQ(dbc.at(e.name).dlc, 8) << e.name;
  }
}

TEST(Dbc, EveryMessageEndsWithCounterAndCrcAndHasNoOverlap) {
  for (const auto& [name, msg] : read_dbc()) {
    std::uint64_t used = 0;
    bool counter = false, crc = false;
    for (const auto& s : msg.signals) {
      const std::uint64_t mask = ((s.length == 64) ? ~0ull : ((1ull << s.length) - 1)) << s.start_bit;
      EXPECT_EQ(used & mask, 0u) << name << "." << s.name << " overlaps";
      used |= mask;
      counter |= s.name == "counter" && s.start_bit == 48 && s.length == 8;
      crc |= s.name == "crc" && s.start_bit == 56 && s.length == 8;
    }
    EXPECT_TRUE(counter) << name;
    EXPECT_TRUE(crc) << name;
  }
}

TEST(Dbc, DecodesFramesAsTheCodecDoes) {
  const auto dbc = read_dbc();
  // One frame per message, encoded by the codec with values off the grid.
  std::vector<std::pair<std::string, hal::CanFrame>> frames(10);
  ASSERT_TRUE(encode(CurrentCommand{-3.1415f, true, control::ControlMode::kSemiActive, 17}, 1, frames[0].second));
  ASSERT_TRUE(encode(DriveStatus{-12.345f, 29.5f, 0x29, DriveState::kFault, 3}, 2, frames[1].second));
  ASSERT_TRUE(encode(DaqMotion{-0.2345678f, true, 199999.9f, true, 4}, 3, frames[2].second));
  ASSERT_TRUE(encode(DaqAccel{-1.23456f, true, 0.0f, false, 5}, 3, frames[3].second));
  ASSERT_TRUE(encode(MixingCommand{MixingAction::kStart, 0.0762f, 0.2f, 900.0f, 6}, 1, frames[4].second));
  ASSERT_TRUE(encode(MixingStatus{MixingState::kDone, 300.0f, 0.07f, 0x05, 7}, 4, frames[5].second));
  ASSERT_TRUE(encode(ControllerStatus{control::ControlMode::kPassiveOn, 0x2A, 1000, 65535, 8}, 1, frames[6].second));
  ASSERT_TRUE(encode(SimCoilState{-29.12345f, 9}, 3, frames[7].second));
  ASSERT_TRUE(encode(SimCoilDrive{-2.5f, true, 10}, 2, frames[8].second));
  ASSERT_TRUE(encode(IdleStatus{16777215, 0.123f, 1.0f, scheduler_state::kMaintenanceRequired, idle_flag::kAll, 11}, 1,
                     frames[9].second));
  const char* names[] = {"CurrentCommand", "DriveStatus", "DaqMotion", "DaqAccel", "MixingCommand",
                         "MixingStatus", "ControllerStatus", "SimCoilState", "SimCoilDrive", "IdleStatus"};
  for (int i = 0; i < 10; ++i) {
    const hal::CanFrame& f = frames[i].second;
    const DbcMessage& msg = dbc.at(names[i]);
    ASSERT_EQ(f.id, msg.id) << names[i];
    const Values codec = codec_view(names[i])(f);
    for (const auto& [key, value] : codec) {
      bool found = false;
      for (const auto& s : msg.signals) found |= s.name == key;
      EXPECT_TRUE(found) << names[i] << "." << key << " is missing from mrd.dbc";
    }
    for (const auto& s : msg.signals) {
      const double v = dbc_value(s, f.data);
      if (s.name == "crc") {
        EXPECT_EQ(v, f.data[7]);
        continue;
      }
      if (!codec.count(s.name)) {
        // Only a "not available" code may be missing from the codec's view.
        EXPECT_EQ(v, -8388608.0 * s.factor) << names[i] << "." << s.name;
        continue;
      }
      EXPECT_NEAR(v, codec.at(s.name), 1e-6 * std::max(1.0, std::fabs(v))) << names[i] << "." << s.name;
    }
  }
}

}  // namespace
}  // namespace mrd::protocol
