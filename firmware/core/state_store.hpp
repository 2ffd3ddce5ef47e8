#pragma once
/// Crash-safe persistence of the idle-time estimator's state.
///
/// The estimator's state travels as one fixed-size record of kStateRecordSize
/// bytes. The board implements StateStore (a file on Linux, see
/// firmware/platform/linux/file_state_store.hpp; a flash page on a
/// microcontroller); InMemoryStateStore serves tests and the simulator.
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

namespace mrd::fw {

inline constexpr std::size_t kStateRecordSize = 64;
inline constexpr std::uint32_t kStateRecordMagic = 0x4944524Du;  // "MRDI" read as little-endian
inline constexpr std::uint16_t kStateRecordVersion = 1;

/// One persisted record, as bytes.
using StateRecord = std::array<std::uint8_t, kStateRecordSize>;

/// What a StateStore reports.
enum class StoreStatus : std::uint8_t {
  kOk = 0,
  kMissing,    ///< nothing stored yet
  kWrongSize,  ///< a record is there but has the wrong length (e.g. truncated)
  kIoError,    ///< the medium failed (read, write, sync or rename)
};

constexpr const char* store_status_name(StoreStatus s) noexcept {
  switch (s) {
    case StoreStatus::kOk: return "ok";
    case StoreStatus::kMissing: return "missing";
    case StoreStatus::kWrongSize: return "wrong-size";
    case StoreStatus::kIoError: return "io-error";
  }
  return "unknown";
}

/// Where the board keeps the record. `save` must be atomic with respect to
/// power loss: after a crash, `load` returns the previous record or the new
/// one, never a mix (the record's CRC catches what the medium does not).
/// Neither call is made from the control step; see IdleEstimator.
class StateStore {
 public:
  virtual StoreStatus load(StateRecord& out) noexcept = 0;
  virtual StoreStatus save(const StateRecord& record) noexcept = 0;

 protected:
  StateStore() = default;
  StateStore(const StateStore&) = default;
  StateStore& operator=(const StateStore&) = default;
  ~StateStore() = default;
};

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
  kBadSize,     ///< the size field does not match kStateRecordSize
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
constexpr void put_u16(StateRecord& r, std::size_t at, std::uint16_t v) noexcept {
  r[at] = static_cast<std::uint8_t>(v & 0xFFu);
  r[at + 1] = static_cast<std::uint8_t>(v >> 8);
}
constexpr void put_u32(StateRecord& r, std::size_t at, std::uint32_t v) noexcept {
  for (std::size_t k = 0; k < 4; ++k) r[at + k] = static_cast<std::uint8_t>((v >> (8 * k)) & 0xFFu);
}
constexpr void put_f64(StateRecord& r, std::size_t at, double v) noexcept {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  for (std::size_t k = 0; k < 8; ++k) r[at + k] = static_cast<std::uint8_t>((bits >> (8 * k)) & 0xFFu);
}
constexpr std::uint16_t get_u16(const StateRecord& r, std::size_t at) noexcept {
  return static_cast<std::uint16_t>(r[at] | (r[at + 1] << 8));
}
constexpr std::uint32_t get_u32(const StateRecord& r, std::size_t at) noexcept {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v |= static_cast<std::uint32_t>(r[at + k]) << (8 * k);
  return v;
}
constexpr double get_f64(const StateRecord& r, std::size_t at) noexcept {
  std::uint64_t bits = 0;
  for (std::size_t k = 0; k < 8; ++k) bits |= static_cast<std::uint64_t>(r[at + k]) << (8 * k);
  return std::bit_cast<double>(bits);
}
inline constexpr std::size_t kCrcOffset = kStateRecordSize - 4;
}  // namespace detail

/// Writes `s` as a record with version, size and CRC filled in.
constexpr StateRecord encode_state(const PersistedIdleState& s) noexcept {
  StateRecord r{};
  detail::put_u32(r, 0, kStateRecordMagic);
  detail::put_u16(r, 4, kStateRecordVersion);
  detail::put_u16(r, 6, static_cast<std::uint16_t>(kStateRecordSize));
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
inline DecodeStatus decode_state(const StateRecord& r, PersistedIdleState& out) noexcept {
  if (detail::get_u32(r, 0) != kStateRecordMagic) return DecodeStatus::kBadMagic;
  if (detail::get_u16(r, 6) != kStateRecordSize) return DecodeStatus::kBadSize;
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

/// A StateStore in RAM, for tests and the simulator. A stored record can be
/// damaged on purpose (`bytes()`, `truncate()`) and the next save made to
/// fail (`fail_next_save()`).
class InMemoryStateStore final : public StateStore {
 public:
  StoreStatus load(StateRecord& out) noexcept override {
    ++loads_;
    if (!has_record_) return StoreStatus::kMissing;
    if (size_ != kStateRecordSize) return StoreStatus::kWrongSize;
    out = record_;
    return StoreStatus::kOk;
  }
  StoreStatus save(const StateRecord& record) noexcept override {
    if (fail_next_save_) {
      fail_next_save_ = false;
      return StoreStatus::kIoError;
    }
    record_ = record;
    size_ = kStateRecordSize;
    has_record_ = true;
    ++saves_;
    return StoreStatus::kOk;
  }

  bool has_record() const noexcept { return has_record_; }
  void clear() noexcept { has_record_ = false; }
  StateRecord& bytes() noexcept { return record_; }
  const StateRecord& bytes() const noexcept { return record_; }
  /// Pretends only the first `size` bytes survived.
  void truncate(std::size_t size) noexcept { size_ = size < kStateRecordSize ? size : kStateRecordSize; }
  void fail_next_save() noexcept { fail_next_save_ = true; }
  std::uint32_t saves() const noexcept { return saves_; }
  std::uint32_t loads() const noexcept { return loads_; }

 private:
  StateRecord record_{};
  std::size_t size_ = 0;
  bool has_record_ = false;
  bool fail_next_save_ = false;
  std::uint32_t saves_ = 0;
  std::uint32_t loads_ = 0;
};

}  // namespace mrd::fw
