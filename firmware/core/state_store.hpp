#pragma once
/// The record in which the idle-time estimator's state persists: its layout,
/// CRC, encoding and checks. The bytes go through hal::StateStore
/// (mrd/hal/state_store.hpp), which the board implements.
///
/// Record layout, version 2 (all fields little-endian, integers):
/// <pre>
///   offset size field
///    0     4    magic 0x4944524D ("MRDI")
///    4     2    version (kStateRecordVersion = 2)
///    6     2    record size in bytes (64)
///    8     8    equivalent idle time τ at the stamp, ms (uint64)
///   16     8    wall-clock stamp (RTC), ms (int64)
///   24     8    lifetime displaced volume credited, 2^−40 m³ (int64)
///   32     8    of which displaced while a mixing cycle ran, 2^−40 m³ (int64)
///   40     4    mixing cycles confirmed
///   44     4    save sequence number
///   48     4    estimator status flags at the save (diagnostic)
///   52     8    reserved, zero
///   60     4    CRC-32 (IEEE 802.3, reflected, as zlib's crc32) of bytes 0..59
/// </pre>
/// Version 1 had the same layout with IEEE-754 binary64 seconds and m³ at
/// offsets 8–39. Rule: the estimator always writes version 2; decode_state()
/// reads both, converting a version-1 record to milliseconds and counts
/// (rounded to nearest), so a board updated in the field keeps its state.
/// Header-only, no heap, no exceptions, no I/O: builds freestanding.

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "mrd/hal/state_store.hpp"

namespace mrd::fw {

inline constexpr std::uint32_t kStateRecordMagic = 0x4944524Du;  // "MRDI" read as little-endian
inline constexpr std::uint16_t kStateRecordVersion = 2;
inline constexpr std::uint16_t kStateRecordVersionDoubles = 1;  ///< read only
/// One count of the volume fields, m³ (2^−40).
inline constexpr double kStateVolumeCountM3 = 1.0 / 1099511627776.0;
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
  std::uint64_t equivalent_idle_ms = 0;  ///< τ at the stamp, ms
  std::int64_t rtc_ms = 0;               ///< wall-clock stamp, ms
  std::int64_t lifetime_volume = 0;      ///< displaced volume credited since commissioning, 2^−40 m³ (≥ 0)
  std::int64_t mixing_volume = 0;        ///< part of it displaced by mixing cycles, 2^−40 m³ (≥ 0)
  std::uint32_t mixing_cycles = 0;       ///< mixing cycles confirmed
  std::uint32_t save_sequence = 0;       ///< increments with every save
  std::uint32_t flags = 0;               ///< IdleFlags at the save
};

/// Why a record was refused.
enum class DecodeStatus : std::uint8_t {
  kOk = 0,
  kBadMagic,    ///< not an estimator record
  kBadSize,     ///< the size field does not match hal::kStateRecordSize
  kBadVersion,  ///< a record of a layout version other than 1 or 2
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
constexpr void put_u64(hal::StateRecord& r, std::size_t at, std::uint64_t bits) noexcept {
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
constexpr std::uint64_t get_u64(const hal::StateRecord& r, std::size_t at) noexcept {
  std::uint64_t bits = 0;
  for (std::size_t k = 0; k < 8; ++k) bits |= static_cast<std::uint64_t>(r[at + k]) << (8 * k);
  return bits;
}
constexpr double get_f64(const hal::StateRecord& r, std::size_t at) noexcept {
  return std::bit_cast<double>(get_u64(r, at));
}
/// A version-1 value (double) as a whole number of `unit`s; false when not
/// finite, negative (unless `signed_ok`) or beyond 2^62 units.
inline bool v1_to_units(double v, double unit, bool signed_ok, std::int64_t& out) noexcept {
  if (!std::isfinite(v) || (!signed_ok && v < 0.0)) return false;
  const double n = v / unit;
  if (!(n < 4.611686018427388e18 && n > -4.611686018427388e18)) return false;
  out = std::llround(n);
  return true;
}
inline constexpr std::size_t kCrcOffset = hal::kStateRecordSize - 4;
}  // namespace detail

/// Writes `s` as a record with version, size and CRC filled in.
constexpr hal::StateRecord encode_state(const PersistedIdleState& s) noexcept {
  hal::StateRecord r{};
  detail::put_u32(r, 0, kStateRecordMagic);
  detail::put_u16(r, 4, kStateRecordVersion);
  detail::put_u16(r, 6, static_cast<std::uint16_t>(hal::kStateRecordSize));
  detail::put_u64(r, 8, s.equivalent_idle_ms);
  detail::put_u64(r, 16, static_cast<std::uint64_t>(s.rtc_ms));
  detail::put_u64(r, 24, static_cast<std::uint64_t>(s.lifetime_volume));
  detail::put_u64(r, 32, static_cast<std::uint64_t>(s.mixing_volume));
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
  const std::uint16_t version = detail::get_u16(r, 4);
  if (version != kStateRecordVersion && version != kStateRecordVersionDoubles) return DecodeStatus::kBadVersion;
  if (detail::get_u32(r, detail::kCrcOffset) != crc32(r.data(), detail::kCrcOffset)) return DecodeStatus::kBadCrc;
  PersistedIdleState s;
  s.mixing_cycles = detail::get_u32(r, 40);
  s.save_sequence = detail::get_u32(r, 44);
  s.flags = detail::get_u32(r, 48);
  if (version == kStateRecordVersionDoubles) {
    std::int64_t idle_ms = 0;
    const bool ok = detail::v1_to_units(detail::get_f64(r, 8), 1e-3, false, idle_ms) &&
                    detail::v1_to_units(detail::get_f64(r, 16), 1e-3, true, s.rtc_ms) &&
                    detail::v1_to_units(detail::get_f64(r, 24), kStateVolumeCountM3, false, s.lifetime_volume) &&
                    detail::v1_to_units(detail::get_f64(r, 32), kStateVolumeCountM3, false, s.mixing_volume);
    if (!ok) return DecodeStatus::kBadValue;
    s.equivalent_idle_ms = static_cast<std::uint64_t>(idle_ms);
  } else {
    s.equivalent_idle_ms = detail::get_u64(r, 8);
    s.rtc_ms = static_cast<std::int64_t>(detail::get_u64(r, 16));
    s.lifetime_volume = static_cast<std::int64_t>(detail::get_u64(r, 24));
    s.mixing_volume = static_cast<std::int64_t>(detail::get_u64(r, 32));
    const bool ok = s.equivalent_idle_ms < (std::uint64_t{1} << 62) && s.lifetime_volume >= 0 && s.mixing_volume >= 0;
    if (!ok) return DecodeStatus::kBadValue;
  }
  out = s;
  return DecodeStatus::kOk;
}

}  // namespace mrd::fw
