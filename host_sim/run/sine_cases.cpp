#include "host_sim/run/sine_cases.hpp"

namespace mrd::run {

std::vector<ThesisSineResult> run_thesis_sine_cases() {
  std::vector<ThesisSineResult> results;
  for (const auto& c : thesis_sine_cases()) results.push_back({c, run_sine_rig(c.spec)});
  return results;
}

}  // namespace mrd::run
