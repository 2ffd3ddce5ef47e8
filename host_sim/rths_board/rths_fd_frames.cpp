#include "host_sim/rths_board/rths_fd_frames.hpp"

#include <cmath>

namespace mrd::rths_board {
namespace {

using protocol::DecodeError;
using protocol::MsgId;

constexpr double kFdDispCountsPerM = 1e9;   // 1 nm
constexpr double kFdForceCountsPerN = 1e3;  // 1 mN
constexpr std::int64_t kInt32Max = 2147483647;

bool put_i32(hal::CanFdFrame& f, std::size_t at, double value, double counts_per_unit) noexcept {
  const double scaled = value * counts_per_unit;
  if (!std::isfinite(scaled) || std::fabs(scaled) > static_cast<double>(kInt32Max)) return false;
  const std::int64_t raw = std::llround(scaled);
  if (raw > kInt32Max || raw < -kInt32Max) return false;
  const auto u = static_cast<std::uint32_t>(raw & 0xFFFFFFFF);
  for (std::size_t i = 0; i < 4; ++i) f.data[at + i] = static_cast<std::uint8_t>((u >> (8 * i)) & 0xFF);
  return true;
}

bool get_i32(const hal::CanFdFrame& f, std::size_t at, double counts_per_unit, double& out) noexcept {
  std::uint32_t u = 0;
  for (std::size_t i = 4; i-- > 0;) u = (u << 8) | f.data[at + i];
  const std::int64_t raw = (u & 0x80000000u) ? static_cast<std::int64_t>(u) - 0x100000000LL : static_cast<std::int64_t>(u);
  if (raw < -kInt32Max) return false;
  out = static_cast<double>(raw) / counts_per_unit;
  return true;
}

bool begin(hal::CanFdFrame& f, MsgId m, std::uint8_t sender) noexcept {
  if (sender < 1 || sender > protocol::kMaxNodeId) return false;
  f = hal::CanFdFrame{};
  f.id = protocol::can_id(m, sender);
  f.fd = true;
  f.brs = true;
  f.len = kRthsFdLength;
  return true;
}

void finish(hal::CanFdFrame& f, std::uint16_t counter) noexcept {
  f.data[8] = static_cast<std::uint8_t>(counter & 0xFF);
  f.data[9] = static_cast<std::uint8_t>(counter >> 8);
  f.data[10] = 0;
  f.data[11] = rths_fd_crc(f.id, f);
}

DecodeError check(const hal::CanFdFrame& f, MsgId m, std::uint8_t sender) noexcept {
  if (sender < 1 || sender > protocol::kMaxNodeId || !f.fd || f.extended || f.id != protocol::can_id(m, sender))
    return DecodeError::kWrongId;
  if (f.len != kRthsFdLength) return DecodeError::kWrongLength;
  if (f.data[11] != rths_fd_crc(f.id, f)) return DecodeError::kBadChecksum;
  if (f.data[10] != 0) return DecodeError::kBadField;
  return DecodeError::kOk;
}

std::uint16_t counter_of(const hal::CanFdFrame& f) noexcept {
  return static_cast<std::uint16_t>(f.data[8] | (f.data[9] << 8));
}

}  // namespace

std::uint8_t rths_fd_crc(std::uint32_t id, const hal::CanFdFrame& f) noexcept {
  std::uint8_t bytes[2 + 11];
  bytes[0] = static_cast<std::uint8_t>(id & 0xFF);
  bytes[1] = static_cast<std::uint8_t>((id >> 8) & 0xFF);
  for (std::size_t i = 0; i < 11; ++i) bytes[2 + i] = f.data[i];
  return protocol::crc8_j1850(bytes);
}

bool encode_fd(const RthsFdCommand& m, std::uint8_t sender, hal::CanFdFrame& out) noexcept {
  if (!begin(out, MsgId::kRthsCommand, sender) || !put_i32(out, 0, m.command_m, kFdDispCountsPerM) ||
      !put_i32(out, 4, m.target_m, kFdDispCountsPerM))
    return false;
  finish(out, m.counter);
  return true;
}

bool encode_fd(const RthsFdMeasurement& m, std::uint8_t sender, hal::CanFdFrame& out) noexcept {
  if (!begin(out, MsgId::kRthsMeasurement, sender) || !put_i32(out, 0, m.displacement_m, kFdDispCountsPerM) ||
      !put_i32(out, 4, m.force_n, kFdForceCountsPerN))
    return false;
  finish(out, m.counter);
  return true;
}

DecodeError decode_fd(const hal::CanFdFrame& f, std::uint8_t sender, RthsFdCommand& out) noexcept {
  if (const DecodeError e = check(f, MsgId::kRthsCommand, sender); e != DecodeError::kOk) return e;
  RthsFdCommand m;
  if (!get_i32(f, 0, kFdDispCountsPerM, m.command_m) || !get_i32(f, 4, kFdDispCountsPerM, m.target_m))
    return DecodeError::kOutOfRange;
  m.counter = counter_of(f);
  out = m;
  return DecodeError::kOk;
}

DecodeError decode_fd(const hal::CanFdFrame& f, std::uint8_t sender, RthsFdMeasurement& out) noexcept {
  if (const DecodeError e = check(f, MsgId::kRthsMeasurement, sender); e != DecodeError::kOk) return e;
  RthsFdMeasurement m;
  if (!get_i32(f, 0, kFdDispCountsPerM, m.displacement_m) || !get_i32(f, 4, kFdForceCountsPerN, m.force_n))
    return DecodeError::kOutOfRange;
  m.counter = counter_of(f);
  out = m;
  return DecodeError::kOk;
}

}  // namespace mrd::rths_board
