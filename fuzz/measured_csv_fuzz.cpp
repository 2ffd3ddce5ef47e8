// libFuzzer target for the measured-record CSV parser of the discrepancy
// workflow. Properties:
//  - no crash, no undefined behaviour; every refusal is an io::UsageError;
//  - an accepted record has equal-length columns, at least kMinSamples rows,
//    strictly increasing time, and force, displacement and current within the
//    kMaxMeasured* limits, the force and displacement not constant.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/io/usage_error.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace mrd::discrepancy;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const MeasuredData m = parse_measured_csv(text, "fuzz.csv");
    const std::size_t n = m.size();
    require(n >= kMinSamples);
    require(m.displacement_m.size() == n && m.force_n.size() == n && m.current_cmd_a.size() == n);
    require(m.velocity_m_s.empty() || m.velocity_m_s.size() == n);
    for (std::size_t i = 1; i < n; ++i) require(m.time_s[i] > m.time_s[i - 1]);
    for (std::size_t i = 0; i < n; ++i) {
      require(std::abs(m.force_n[i]) <= kMaxMeasuredForce_n);
      require(std::abs(m.displacement_m[i]) <= kMaxMeasuredDisplacement_m);
      require(std::abs(m.current_cmd_a[i]) <= kMaxMeasuredCurrent_a);
    }
    const auto [f_lo, f_hi] = std::minmax_element(m.force_n.begin(), m.force_n.end());
    require(*f_lo < *f_hi);
  } catch (const mrd::io::UsageError&) {
  }
  return 0;
}
