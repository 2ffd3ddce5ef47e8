// libFuzzer target for the idle-time estimator's state record decoder
// (firmware/core/state_store.hpp). The input fills the 64-byte record; flag
// bits of the first byte put a correct magic, size, version and CRC in place
// so that the fuzzer reaches the value checks. Properties:
//  - no crash, no undefined behaviour, no read outside the record;
//  - an accepted record holds finite, non-negative times and volumes and a
//    finite stamp, and re-encoding it decodes to the very same values.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "firmware/core/state_store.hpp"

namespace {

using namespace mrd;

void require(bool ok) {
  if (!ok) __builtin_trap();
}

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::uint8_t flags = data[0];
  hal::StateRecord r{};
  std::memcpy(r.data(), data + 1, size - 1 < r.size() ? size - 1 : r.size());
  if ((flags & 1u) != 0) fw::detail::put_u32(r, 0, fw::kStateRecordMagic);
  if ((flags & 2u) != 0) {
    fw::detail::put_u16(r, 4, fw::kStateRecordVersion);
    fw::detail::put_u16(r, 6, static_cast<std::uint16_t>(hal::kStateRecordSize));
  }
  if ((flags & 4u) != 0) fw::detail::put_u32(r, fw::detail::kCrcOffset, fw::crc32(r.data(), fw::detail::kCrcOffset));

  fw::PersistedIdleState s;
  if (fw::decode_state(r, s) != fw::DecodeStatus::kOk) return 0;
  require(std::isfinite(s.equivalent_idle_s) && s.equivalent_idle_s >= 0.0 && std::isfinite(s.rtc_s));
  require(std::isfinite(s.lifetime_volume_m3) && s.lifetime_volume_m3 >= 0.0);
  require(std::isfinite(s.mixing_volume_m3) && s.mixing_volume_m3 >= 0.0);
  fw::PersistedIdleState back;
  require(fw::decode_state(fw::encode_state(s), back) == fw::DecodeStatus::kOk);
  require(same(back.equivalent_idle_s, s.equivalent_idle_s) && same(back.rtc_s, s.rtc_s) &&
          same(back.lifetime_volume_m3, s.lifetime_volume_m3) && same(back.mixing_volume_m3, s.mixing_volume_m3) &&
          back.mixing_cycles == s.mixing_cycles && back.save_sequence == s.save_sequence && back.flags == s.flags);
  return 0;
}
