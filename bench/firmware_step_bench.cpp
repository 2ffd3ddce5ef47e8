// Host time of one control step of the firmware core, float and fixed-point
// builds, semi-active mode, on recorded realistic inputs (firmware_inputs.hpp).
// Reports ns per step. Instructions per step: bench/firmware_callgrind.sh.
#include <benchmark/benchmark.h>

#include "firmware_inputs.hpp"

namespace {

const std::vector<mrd::control::ControllerInput>& inputs() {
  static const auto in = mrd::bench::recorded_inputs(1 << 16);  // 65.5 s
  return in;
}

template <class Policy>
void BM_FirmwareStep(benchmark::State& state) {
  mrd::fw::DamperController<Policy> c;
  if (c.init(mrd::fw::ControllerConfig{}) != mrd::fw::ConfigError::kNone) {
    state.SkipWithError("init failed");
    return;
  }
  const auto& in = inputs();
  std::size_t i = 0;
  std::uint64_t tick = 0;
  for (auto _ : state) {
    mrd::control::ControllerInput x = in[i];
    x.tick = tick++;
    benchmark::DoNotOptimize(c.step(x));
    if (++i == in.size()) {
      i = 0;
      c.reset();
      tick = 0;
    }
  }
  state.counters["ns_per_step"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.SetLabel(Policy::kName);
}
BENCHMARK(BM_FirmwareStep<mrd::num::Float32Policy>);
BENCHMARK(BM_FirmwareStep<mrd::num::Fixed32Policy>);

}  // namespace

BENCHMARK_MAIN();
