// libFuzzer target for the measured-record .mat reader (libmatio behind the
// project's completeness checks). Each input is written to a temporary file
// and read through read_measured, as `mrd discrepancy --measured x.mat` does.
// Properties:
//  - no crash, no undefined behaviour, no read past the file's bytes; every
//    refusal is an io::UsageError;
//  - an accepted record has equal-length columns, strictly increasing time and
//    finite values.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/io/usage_error.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

const std::string& temp_path() {
  static const std::string path = "/tmp/mrd-mat-fuzz-" + std::to_string(::getpid()) + ".mat";
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace mrd::discrepancy;
  {
    std::FILE* f = std::fopen(temp_path().c_str(), "wb");
    if (!f) return 0;
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  try {
    const MeasuredData m = read_measured(temp_path());
    const std::size_t n = m.size();
    require(m.displacement_m.size() == n && m.force_n.size() == n && m.current_cmd_a.size() == n);
    for (std::size_t i = 1; i < n; ++i) require(m.time_s[i] > m.time_s[i - 1]);
    for (std::size_t i = 0; i < n; ++i) require(std::isfinite(m.force_n[i]) && std::isfinite(m.displacement_m[i]));
  } catch (const mrd::io::UsageError&) {
  }
  std::remove(temp_path().c_str());
  return 0;
}
