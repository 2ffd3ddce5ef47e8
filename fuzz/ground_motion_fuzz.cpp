// libFuzzer target for the ground-motion readers (shared CSV and PEER .AT2).
// The first byte picks the format, the rest is the file's text. Properties:
//  - no crash, no undefined behaviour; every refusal is an io::UsageError;
//  - an accepted record has at least two samples (CSV) or NPTS samples (AT2),
//    a step within [kMinRecordStep_s, kMaxRecordStep_s] and every sample
//    finite and within ±kMaxRecordAccel_m_s2.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "host_sim/excitation/ground_motion.hpp"
#include "host_sim/io/usage_error.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const bool at2 = (data[0] & 1u) != 0;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  using namespace mrd::excitation;
  try {
    const GroundMotion m = at2 ? parse_peer_at2(text, "fuzz.AT2", "fuzz") : parse_ground_motion_csv(text, "fuzz.csv", "fuzz");
    require(at2 || m.accel_m_s2.size() >= 2);
    require(m.dt_s >= kMinRecordStep_s && m.dt_s <= kMaxRecordStep_s);
    for (const double a : m.accel_m_s2) require(std::isfinite(a) && std::abs(a) <= kMaxRecordAccel_m_s2);
  } catch (const mrd::io::UsageError&) {
  }
  return 0;
}
