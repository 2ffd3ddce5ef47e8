#pragma once
/// The record in which the idle-time estimator's state persists: its layout,
/// CRC, encoding and checks. The bytes go through hal::StateStore
/// (mrd/hal/state_store.hpp), which the board implements.
///
/// Record layout (all fields little-endian, doubles as IEEE-754 binary64):
/// <pre>
///   offset size field
///    0     4    magic 0x4944524D ("MRDI")
///    4     2    version (kStateRecordVersion)
///    6     2    record size in bytes (64)
///    8     8    equivalent idle time τ at the stamp, s
///   16     8    wall-clock stamp (RTC), s
///   24     8    lifetime displaced volume credited, m³
///   32     8    of which displaced while a mixing cycle ran, m³
///   40     4    mixing cycles confirmed
///   44     4    save sequence number
///   48     4    estimator status flags at the save (diagnostic)
///   52     8    reserved, zero
///   60     4    CRC-32 (IEEE 802.3, reflected, as zlib's crc32) of bytes 0..59
/// </pre>
/// Header-only, no heap, no exceptions, no I/O: builds freestanding.

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "mrd/hal/state_store.hpp"

namespace mrd::fw {

inline constexpr std::uint32_t kStateRecordMagic = 0x4944524Du;  // "MRDI" read as little-endian
inline constexpr std::uint16_t kStateRecordVersion = 1;
static_assert(hal::kStateRecordSize == 64, "the layout above fills 64 bytes");

/// CRC-32 as in IEEE 802.3 / zlib (polynomial 0x04C11DB7 reflected =
/// 0xEDB88320, initial value and final XOR 0xFFFFFFFF); check value
/// crc32("123456789") = 0xCBF43926.
namespace detail {
constexpr std::array<std::uint32_t, 256> make_crc32_table() noexcept {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? (0xEDB88320u ^ (c >> 1)) : (c >> 1);
    t[n] = c;
  }
  return t;
}
inline constexpr std::array<std::uint32_t, 256> kCrc32Table = make_crc32_table();
}  // namespace detail

constexpr std::uint32_t crc32(const std::uint8_t* data, std::size_t size) noexcept {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < size; ++i) c = detail::kCrc32Table[(c ^ data[i]) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

/// The estimator's state as stored (see the layout above).
struct PersistedIdleState {
  double equivalent_idle_s = 0.0;      ///< τ at the stamp, s (≥ 0)
  double rtc_s = 0.0;                  ///< wall-clock stamp, s
  double lifetime_volume_m3 = 0.0;     ///< displaced volume credited since commissioning, m³
  double mixing_volume_m3 = 0.0;       ///< part of it displaced by mixing cycles, m³
  std::uint32_t mixing_cycles = 0;     ///< mixing cycles confirmed
  std::uint32_t save_sequence = 0;     ///< increments with every save
  std::uint32_t flags = 0;             ///< IdleFlags at the save
};

/// Why a record was refused.
enum class DecodeStatus : std::uint8_t {
  kOk = 0,
  kBadMagic,    ///< not an estimator record
  kBadSize,     ///< the size field does not match hal::kStateRecordSize
  kBadVersion,  ///< a record of another layout version
  kBadCrc,      ///< bytes changed since the save
  kBadValue,    ///< CRC fine but a value is not finite or out of range
};

constexpr const char* decode_status_name(DecodeStatus s) noexcept {
  switch (s) {
    case DecodeStatus::kOk: return "ok";
    case DecodeStatus::kBadMagic: return "bad-magic";
    case DecodeStatus::kBadSize: return "bad-size";
    case DecodeStatus::kBadVersion: return "bad-version";
    case DecodeStatus::kBadCrc: return "bad-crc";
    case DecodeStatus::kBadValue: return "bad-value";
  }
  return "unknown";
}

namespace detail {
constexpr void put_u16(hal::StateRecord& r, std::size_t at, std::uint16_t v) noexcept {
  r[at] = static_cast<std::uint8_t>(v & 0xFFu);
  r[at + 1] = static_cast<std::uint8_t>(v >> 8);
}
constexpr void put_u32(hal::StateRecord& r, std::size_t at, std::uint32_t v) noexcept {
  for (std::size_t k = 0; k < 4; ++k) r[at + k] = static_cast<std::uint8_t>((v >> (8 * k)) & 0xFFu);
}
constexpr void put_f64(hal::StateRecord& r, std::size_t at, double v) noexcept {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  for (std::size_t k = 0; k < 8; ++k) r[at + k] = static_cast<std::uint8_t>((bits >> (8 * k)) & 0xFFu);
}
constexpr std::uint16_t get_u16(const hal::StateRecord& r, std::size_t at) noexcept {
  return static_cast<std::uint16_t>(r[at] | (r[at + 1] << 8));
}
constexpr std::uint32_t get_u32(const hal::StateRecord& r, std::size_t at) noexcept {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v |= static_cast<std::uint32_t>(r[at + k]) << (8 * k);
  return v;
}
constexpr double get_f64(const hal::StateRecord& r, std::size_t at) noexcept {
  std::uint64_t bits = 0;
  for (std::size_t k = 0; k < 8; ++k) bits |= static_cast<std::uint64_t>(r[at + k]) << (8 * k);
  return std::bit_cast<double>(bits);
}
inline constexpr std::size_t kCrcOffset = hal::kStateRecordSize - 4;
}  // namespace detail

/// Writes `s` as a record with version, size and CRC filled in.
constexpr hal::StateRecord encode_state(const PersistedIdleState& s) noexcept {
  hal::StateRecord r{};
  detail::put_u32(r, 0, kStateRecordMagic);
  detail::put_u16(r, 4, kStateRecordVersion);
  detail::put_u16(r, 6, static_cast<std::uint16_t>(hal::kStateRecordSize));
  detail::put_f64(r, 8, s.equivalent_idle_s);
  detail::put_f64(r, 16, s.rtc_s);
  detail::put_f64(r, 24, s.lifetime_volume_m3);
  detail::put_f64(r, 32, s.mixing_volume_m3);
  detail::put_u32(r, 40, s.mixing_cycles);
  detail::put_u32(r, 44, s.save_sequence);
  detail::put_u32(r, 48, s.flags);
  detail::put_u32(r, detail::kCrcOffset, crc32(r.data(), detail::kCrcOffset));
  return r;
}

/// Checks magic, size, version, CRC and value ranges, in that order, and
/// fills `out` only when all pass.
inline DecodeStatus decode_state(const hal::StateRecord& r, PersistedIdleState& out) noexcept {
  if (detail::get_u32(r, 0) != kStateRecordMagic) return DecodeStatus::kBadMagic;
  if (detail::get_u16(r, 6) != hal::kStateRecordSize) return DecodeStatus::kBadSize;
  if (detail::get_u16(r, 4) != kStateRecordVersion) return DecodeStatus::kBadVersion;
  if (detail::get_u32(r, detail::kCrcOffset) != crc32(r.data(), detail::kCrcOffset)) return DecodeStatus::kBadCrc;
  PersistedIdleState s;
  s.equivalent_idle_s = detail::get_f64(r, 8);
  s.rtc_s = detail::get_f64(r, 16);
  s.lifetime_volume_m3 = detail::get_f64(r, 24);
  s.mixing_volume_m3 = detail::get_f64(r, 32);
  s.mixing_cycles = detail::get_u32(r, 40);
  s.save_sequence = detail::get_u32(r, 44);
  s.flags = detail::get_u32(r, 48);
  const bool ok = std::isfinite(s.equivalent_idle_s) && s.equivalent_idle_s >= 0.0 && std::isfinite(s.rtc_s) &&
                  std::isfinite(s.lifetime_volume_m3) && s.lifetime_volume_m3 >= 0.0 &&
                  std::isfinite(s.mixing_volume_m3) && s.mixing_volume_m3 >= 0.0;
  if (!ok) return DecodeStatus::kBadValue;
  out = s;
  return DecodeStatus::kOk;
}

}  // namespace mrd::fw
