// The RTHS frames (host_sim/rths_board/rths_frames.hpp) held to the protocol's
// documents: the example frames 12–15 of common/protocol/CAN_PROTOCOL.md byte
// for byte (their bytes were worked out by hand and with a separate bitwise
// CRC, shown in the spec), and mrd.dbc's signal definitions decoding frames
// of the RTHS codec to the values the codec decodes.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "host_sim/rths_board/rths_frames.hpp"
#include "tests/unit/protocol_spec_files.hpp"

namespace mrd::rths_board {
namespace {

namespace sf = protocol::spec_files;
using protocol::DecodeError;

constexpr std::uint8_t kRuntimeNode = 1;
constexpr std::uint8_t kLabNode = 5;

hal::CanFrame rths_spec_frame(const std::map<int, sf::SpecExample>& ex, int n) {
  hal::CanFrame f;
  f.id = ex.at(n).id;
  f.dlc = 8;
  f.data = ex.at(n).data;
  return f;
}

void expect_rths_frame(const std::map<int, sf::SpecExample>& ex, int n, const hal::CanFrame& f) {
  ASSERT_TRUE(ex.count(n)) << "example " << n << " missing from CAN_PROTOCOL.md";
  EXPECT_EQ(f.id, ex.at(n).id) << "example " << n;
  EXPECT_EQ(f.dlc, 8) << "example " << n;
  for (int i = 0; i < 8; ++i) EXPECT_EQ(f.data[i], ex.at(n).data[i]) << "example " << n << " byte " << i;
}

TEST(RthsFramesSpec, EncodeTheSpecExamplesByteForByte) {
  const auto ex = sf::read_spec_examples(MRD_PROTOCOL_DIR);
  hal::CanFrame f;
  ASSERT_TRUE(encode(RthsCommand{12.34567e-3, -0.5e-3, 0x2A}, kRuntimeNode, f));
  expect_rths_frame(ex, 12, f);
  ASSERT_TRUE(encode(RthsMeasurement{12.3e-3, -1234.56, 0x2B}, kLabNode, f));
  expect_rths_frame(ex, 13, f);
  ASSERT_TRUE(encode(RthsLabStatus{LabState::kStopped, LabStopReason::kForceLimit, 1000, 7}, kLabNode, f));
  expect_rths_frame(ex, 14, f);
  ASSERT_TRUE(encode(RthsRunStatus{RunState::kFinished, 5000, 2}, kRuntimeNode, f));
  expect_rths_frame(ex, 15, f);
}

TEST(RthsFramesSpec, DecodeTheSpecExamples) {
  const auto ex = sf::read_spec_examples(MRD_PROTOCOL_DIR);
  ASSERT_TRUE(ex.count(15));
  RthsCommand c;
  ASSERT_EQ(decode(rths_spec_frame(ex, 12), kRuntimeNode, c), DecodeError::kOk);
  EXPECT_NEAR(c.command_m, 12.34567e-3, 1e-12);
  EXPECT_NEAR(c.target_m, -0.5e-3, 1e-12);
  EXPECT_EQ(c.counter, 0x2A);
  RthsMeasurement m;
  ASSERT_EQ(decode(rths_spec_frame(ex, 13), kLabNode, m), DecodeError::kOk);
  EXPECT_NEAR(m.displacement_m, 12.3e-3, 1e-12);
  EXPECT_NEAR(m.force_n, -1234.56, 1e-9);
  EXPECT_EQ(m.counter, 0x2B);
  RthsLabStatus s;
  ASSERT_EQ(decode(rths_spec_frame(ex, 14), kLabNode, s), DecodeError::kOk);
  EXPECT_EQ(s.state, LabState::kStopped);
  EXPECT_EQ(s.stop, LabStopReason::kForceLimit);
  EXPECT_EQ(s.rate_hz, 1000);
  RthsRunStatus r;
  ASSERT_EQ(decode(rths_spec_frame(ex, 15), kRuntimeNode, r), DecodeError::kOk);
  EXPECT_EQ(r.state, RunState::kFinished);
  EXPECT_EQ(r.ticks, 5000u);
}

using RthsValues = std::map<std::string, double>;

void expect_dbc_decodes_as_codec(const std::map<std::string, sf::DbcMessage>& dbc, const std::string& name,
                                 const hal::CanFrame& f, const RthsValues& codec) {
  ASSERT_TRUE(dbc.count(name)) << name << " is missing from mrd.dbc";
  const sf::DbcMessage& msg = dbc.at(name);
  EXPECT_EQ(msg.id, f.id) << name;
  EXPECT_EQ(msg.dlc, 8) << name;
  for (const auto& [key, value] : codec) {
    bool found = false;
    for (const auto& s : msg.signals) found |= s.name == key;
    EXPECT_TRUE(found) << name << "." << key << " is missing from mrd.dbc";
  }
  for (const auto& s : msg.signals) {
    const double v = sf::dbc_value(s, f.data);
    if (s.name == "crc") {
      EXPECT_EQ(v, f.data[7]) << name;
      continue;
    }
    ASSERT_TRUE(codec.count(s.name)) << name << "." << s.name << " is not a signal of the RTHS codec";
    EXPECT_NEAR(v, codec.at(s.name), 1e-9 * std::max(1.0, std::fabs(v))) << name << "." << s.name;
  }
}

TEST(RthsFramesSpec, DbcDecodesFramesAsTheCodecDoes) {
  const auto dbc = sf::read_dbc(MRD_PROTOCOL_DIR);
  hal::CanFrame f;
  // Values off the grid and near the ends of the ranges.
  ASSERT_TRUE(encode(RthsCommand{-83.886e-3, 0.0123456789, 0xFE}, kRuntimeNode, f));
  RthsCommand c;
  ASSERT_EQ(decode(f, kRuntimeNode, c), DecodeError::kOk);
  expect_dbc_decodes_as_codec(dbc, "RthsCommand", f,
                              {{"command", c.command_m}, {"target", c.target_m}, {"counter", c.counter}});
  ASSERT_TRUE(encode(RthsMeasurement{-0.00000001, 83886.06, 0x01}, kLabNode, f));
  RthsMeasurement m;
  ASSERT_EQ(decode(f, kLabNode, m), DecodeError::kOk);
  expect_dbc_decodes_as_codec(dbc, "RthsMeasurement", f,
                              {{"displacement", m.displacement_m}, {"force", m.force_n}, {"counter", m.counter}});
  ASSERT_TRUE(encode(RthsLabStatus{LabState::kStopped, LabStopReason::kCommandTimeout, 4096, 0x80}, kLabNode, f));
  RthsLabStatus s;
  ASSERT_EQ(decode(f, kLabNode, s), DecodeError::kOk);
  expect_dbc_decodes_as_codec(dbc, "RthsLabStatus", f,
                              {{"state", double(s.state)}, {"stop", double(s.stop)}, {"rate", s.rate_hz},
                               {"counter", s.counter}});
  ASSERT_TRUE(encode(RthsRunStatus{RunState::kAborted, 4000000000u, 0x33}, kRuntimeNode, f));
  RthsRunStatus r;
  ASSERT_EQ(decode(f, kRuntimeNode, r), DecodeError::kOk);
  expect_dbc_decodes_as_codec(dbc, "RthsRunStatus", f,
                              {{"state", double(r.state)}, {"ticks", double(r.ticks)}, {"counter", r.counter}});
}

}  // namespace
}  // namespace mrd::rths_board
