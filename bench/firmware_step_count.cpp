// Runs N control steps of one numeric build of the firmware core on recorded
// realistic inputs, each through the out-of-line function `step_once`, so
// that callgrind can count the instructions of exactly the step:
//   valgrind --tool=callgrind --toggle-collect='*step_once*' mrd_bench_firmware_steps fixed 100000
// bench/firmware_callgrind.sh runs it for both builds and prints Ir per step.
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "firmware_inputs.hpp"

namespace {

template <class Policy>
[[gnu::noinline]] mrd::control::ControllerOutput step_once(mrd::fw::DamperController<Policy>& c,
                                                           const mrd::control::ControllerInput& in) {
  return c.step(in);
}

template <class Policy>
int run(std::size_t n) {
  const auto inputs = mrd::bench::recorded_inputs(n);
  static mrd::fw::DamperController<Policy> c;
  if (c.init(mrd::fw::ControllerConfig{}) != mrd::fw::ConfigError::kNone) return 1;
  double sum_a = 0.0;
  for (const auto& in : inputs) sum_a += static_cast<double>(step_once(c, in).current_command_a);
  std::printf("%s: %zu steps, mean command %.4f A, over-drive %u, back-drive %u, off %u, hold %u ticks\n",
              Policy::kName, n, sum_a / static_cast<double>(n),
              c.status().branch(mrd::fw::OdbdcoBranch::kOverDrive), c.status().branch(mrd::fw::OdbdcoBranch::kBackDrive),
              c.status().branch(mrd::fw::OdbdcoBranch::kOff), c.status().branch(mrd::fw::OdbdcoBranch::kTarget));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 || (std::strcmp(argv[1], "float") != 0 && std::strcmp(argv[1], "fixed") != 0)) {
    std::fprintf(stderr, "usage: %s float|fixed STEPS\n", argv[0]);
    return 2;
  }
  const long n = std::atol(argv[2]);
  if (n <= 0) {
    std::fprintf(stderr, "%s: STEPS must be a positive integer, got '%s'\n", argv[0], argv[2]);
    return 2;
  }
  const auto steps = static_cast<std::size_t>(n);
  return std::strcmp(argv[1], "fixed") == 0 ? run<mrd::num::Fixed32Policy>(steps)
                                            : run<mrd::num::Float32Policy>(steps);
}
