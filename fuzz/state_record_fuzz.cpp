// libFuzzer target for the idle-time estimator's state record decoder
// (firmware/core/state_store.hpp). The input fills the 64-byte record; flag
// bits of the first byte put a correct magic, size, version (2, or 1 with
// bit 8) and CRC in place so that the fuzzer reaches the value checks and
// the version-1 conversion. Properties:
//  - no crash, no undefined behaviour, no read outside the record;
//  - an accepted record holds a non-negative idle time below 2^62 ms and
//    non-negative volumes, and re-encoding it (always version 2) decodes to
//    the very same values.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "firmware/core/state_store.hpp"

namespace {

using namespace mrd;

void require(bool ok) {
  if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::uint8_t flags = data[0];
  hal::StateRecord r{};
  std::memcpy(r.data(), data + 1, size - 1 < r.size() ? size - 1 : r.size());
  if ((flags & 1u) != 0) fw::detail::put_u32(r, 0, fw::kStateRecordMagic);
  if ((flags & 2u) != 0) {
    fw::detail::put_u16(r, 4, (flags & 8u) != 0 ? fw::kStateRecordVersionDoubles : fw::kStateRecordVersion);
    fw::detail::put_u16(r, 6, static_cast<std::uint16_t>(hal::kStateRecordSize));
  }
  if ((flags & 4u) != 0) fw::detail::put_u32(r, fw::detail::kCrcOffset, fw::crc32(r.data(), fw::detail::kCrcOffset));

  fw::PersistedIdleState s;
  if (fw::decode_state(r, s) != fw::DecodeStatus::kOk) return 0;
  require(s.equivalent_idle_ms < (std::uint64_t{1} << 62));
  require(s.lifetime_volume >= 0 && s.mixing_volume >= 0);
  fw::PersistedIdleState back;
  require(fw::decode_state(fw::encode_state(s), back) == fw::DecodeStatus::kOk);
  require(back.equivalent_idle_ms == s.equivalent_idle_ms && back.rtc_ms == s.rtc_ms &&
          back.lifetime_volume == s.lifetime_volume && back.mixing_volume == s.mixing_volume &&
          back.mixing_cycles == s.mixing_cycles && back.save_sequence == s.save_sequence && back.flags == s.flags);
  return 0;
}
