#include "host_sim/rths_board/rths_frames.hpp"

#include <cmath>

namespace mrd::rths_board {
namespace {

using protocol::DecodeError;
using protocol::MsgId;

// Each RTHS id is one message of its own: no other protocol message shares it.
constexpr MsgId kAllMessages[] = {MsgId::kCurrentCommand,   MsgId::kDriveStatus,     MsgId::kDaqMotion,
                                  MsgId::kDaqAccel,         MsgId::kMixingCommand,   MsgId::kMixingStatus,
                                  MsgId::kControllerStatus, MsgId::kIdleStatus,      MsgId::kRthsCommand,
                                  MsgId::kRthsMeasurement,  MsgId::kRthsLabStatus,   MsgId::kRthsRunStatus,
                                  MsgId::kSimCoilState,     MsgId::kSimCoilDrive};
constexpr bool unique(MsgId id) {
  int n = 0;
  for (MsgId m : kAllMessages) n += static_cast<std::uint8_t>(m) == static_cast<std::uint8_t>(id) ? 1 : 0;
  return n == 1;
}
static_assert(unique(MsgId::kRthsCommand) && unique(MsgId::kRthsMeasurement) && unique(MsgId::kRthsLabStatus) &&
                  unique(MsgId::kRthsRunStatus),
              "an RTHS message id is also another protocol message");

constexpr double kDispCountsPerM = 1e8;   // 10 nm
constexpr double kForceCountsPerN = 1e2;  // 0.01 N
constexpr std::int64_t kInt24Max = 8388607;

bool put_i24(hal::CanFrame& f, int at, double value, double counts_per_unit) noexcept {
  const double scaled = value * counts_per_unit;
  if (!std::isfinite(scaled) || std::fabs(scaled) > static_cast<double>(kInt24Max)) return false;
  const std::int64_t raw = std::llround(scaled);
  if (raw > kInt24Max || raw < -kInt24Max) return false;
  const auto u = static_cast<std::uint32_t>(raw & 0xFFFFFF);
  f.data[at] = static_cast<std::uint8_t>(u & 0xFF);
  f.data[at + 1] = static_cast<std::uint8_t>((u >> 8) & 0xFF);
  f.data[at + 2] = static_cast<std::uint8_t>((u >> 16) & 0xFF);
  return true;
}

std::uint32_t get_u(const hal::CanFrame& f, int at, int bytes) noexcept {
  std::uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | f.data[at + i];
  return v;
}

/// 24-bit two's complement; the raw −2²³ is never sent (out of range).
bool get_i24(const hal::CanFrame& f, int at, double counts_per_unit, double& out) noexcept {
  const std::uint32_t u = get_u(f, at, 3);
  const std::int64_t raw = (u & 0x800000u) ? static_cast<std::int64_t>(u) - 0x1000000 : static_cast<std::int64_t>(u);
  if (raw < -kInt24Max) return false;
  out = static_cast<double>(raw) / counts_per_unit;
  return true;
}

bool begin(hal::CanFrame& f, MsgId m, std::uint8_t sender) noexcept {
  if (sender < 1 || sender > protocol::kMaxNodeId) return false;
  f = hal::CanFrame{};
  f.id = protocol::can_id(m, sender);
  f.dlc = protocol::kFrameDlc;
  return true;
}

bool finish(hal::CanFrame& f, std::uint8_t counter) noexcept {
  f.data[6] = counter;
  f.data[7] = protocol::frame_crc(f.id, f.data);
  return true;
}

DecodeError check(const hal::CanFrame& f, MsgId m, std::uint8_t sender) noexcept {
  if (sender < 1 || sender > protocol::kMaxNodeId || f.extended || f.remote || f.id != protocol::can_id(m, sender))
    return DecodeError::kWrongId;
  if (f.dlc != protocol::kFrameDlc) return DecodeError::kWrongLength;
  if (f.data[7] != protocol::frame_crc(f.id, f.data)) return DecodeError::kBadChecksum;
  return DecodeError::kOk;
}

}  // namespace

const char* lab_stop_reason_name(LabStopReason r) noexcept {
  switch (r) {
    case LabStopReason::kNone: return "none";
    case LabStopReason::kForceLimit: return "force_limit";
    case LabStopReason::kTrackingLimit: return "tracking_limit";
    case LabStopReason::kNotFinite: return "not_finite";
    case LabStopReason::kCommandTimeout: return "command_timeout";
  }
  return "unknown";
}

const char* lab_state_name(LabState s) noexcept {
  switch (s) {
    case LabState::kWaiting: return "waiting";
    case LabState::kRunning: return "running";
    case LabState::kStopped: return "stopped";
  }
  return "unknown";
}

bool encode(const RthsCommand& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  return begin(out, MsgId::kRthsCommand, sender) && put_i24(out, 0, m.command_m, kDispCountsPerM) &&
         put_i24(out, 3, m.target_m, kDispCountsPerM) && finish(out, m.counter);
}

bool encode(const RthsMeasurement& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  return begin(out, MsgId::kRthsMeasurement, sender) && put_i24(out, 0, m.displacement_m, kDispCountsPerM) &&
         put_i24(out, 3, m.force_n, kForceCountsPerN) && finish(out, m.counter);
}

bool encode(const RthsLabStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  if (static_cast<std::uint8_t>(m.state) > 2 || static_cast<std::uint8_t>(m.stop) > 4) return false;
  if (!begin(out, MsgId::kRthsLabStatus, sender)) return false;
  out.data[0] = static_cast<std::uint8_t>(m.state);
  out.data[1] = static_cast<std::uint8_t>(m.stop);
  out.data[2] = static_cast<std::uint8_t>(m.rate_hz & 0xFF);
  out.data[3] = static_cast<std::uint8_t>(m.rate_hz >> 8);
  return finish(out, m.counter);
}

bool encode(const RthsRunStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  const auto s = static_cast<std::uint8_t>(m.state);
  if (s < 1 || s > 3 || !begin(out, MsgId::kRthsRunStatus, sender)) return false;
  out.data[0] = s;
  for (int i = 0; i < 4; ++i) out.data[1 + i] = static_cast<std::uint8_t>((m.ticks >> (8 * i)) & 0xFF);
  return finish(out, m.counter);
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, RthsCommand& out) noexcept {
  if (const DecodeError e = check(f, MsgId::kRthsCommand, sender); e != DecodeError::kOk) return e;
  RthsCommand m;
  if (!get_i24(f, 0, kDispCountsPerM, m.command_m) || !get_i24(f, 3, kDispCountsPerM, m.target_m))
    return DecodeError::kOutOfRange;
  m.counter = f.data[6];
  out = m;
  return DecodeError::kOk;
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, RthsMeasurement& out) noexcept {
  if (const DecodeError e = check(f, MsgId::kRthsMeasurement, sender); e != DecodeError::kOk) return e;
  RthsMeasurement m;
  if (!get_i24(f, 0, kDispCountsPerM, m.displacement_m) || !get_i24(f, 3, kForceCountsPerN, m.force_n))
    return DecodeError::kOutOfRange;
  m.counter = f.data[6];
  out = m;
  return DecodeError::kOk;
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, RthsLabStatus& out) noexcept {
  if (const DecodeError e = check(f, MsgId::kRthsLabStatus, sender); e != DecodeError::kOk) return e;
  if (f.data[0] > 2 || f.data[1] > 4 || f.data[4] != 0 || f.data[5] != 0) return DecodeError::kBadField;
  out.state = static_cast<LabState>(f.data[0]);
  out.stop = static_cast<LabStopReason>(f.data[1]);
  out.rate_hz = static_cast<std::uint16_t>(get_u(f, 2, 2));
  out.counter = f.data[6];
  return DecodeError::kOk;
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, RthsRunStatus& out) noexcept {
  if (const DecodeError e = check(f, MsgId::kRthsRunStatus, sender); e != DecodeError::kOk) return e;
  if (f.data[0] < 1 || f.data[0] > 3 || f.data[5] != 0) return DecodeError::kBadField;
  out.state = static_cast<RunState>(f.data[0]);
  out.ticks = get_u(f, 1, 4);
  out.counter = f.data[6];
  return DecodeError::kOk;
}

}  // namespace mrd::rths_board
