// The whole discrepancy workflow on a 60 s record at 1 kHz (60 001 samples):
// reading the CSV, deriving the velocity, the baseline, every candidate fit
// of every round, the backward check and the localization. Target: < 30 s.
// Cases: no hidden effect (one round) and two hidden effects (three rounds).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>

#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/synth.hpp"
#include "host_sim/discrepancy/workflow.hpp"

namespace {
namespace d = mrd::discrepancy;

std::filesystem::path record(int effects) {
  d::SynthSpec spec;
  spec.seed = 60;
  spec.duration_s = 60.0;
  spec.rate_hz = 1000.0;
  spec.input = d::SynthInput::broadband;
  if (effects == 2) spec.effects = {d::Effect::idle_settling, d::Effect::time_delay};
  const auto c = d::synthesize(spec);
  const auto path = std::filesystem::temp_directory_path() / ("mrd-bench-discrepancy-" + std::to_string(effects) + ".csv");
  std::ofstream(path) << d::measured_to_csv(c.data);
  return path;
}

void BM_DiscrepancyWorkflow60s(benchmark::State& state) {
  const auto path = record(static_cast<int>(state.range(0)));
  std::size_t named = 0;
  for (auto _ : state) {
    const d::MeasuredData data = d::read_measured(path);
    const d::DiscrepancyResult r = d::run_discrepancy(data);
    named = r.effects.size();
    benchmark::DoNotOptimize(r.gap_after);
  }
  state.counters["effects_named"] = static_cast<double>(named);
  std::filesystem::remove(path);
}
BENCHMARK(BM_DiscrepancyWorkflow60s)->Arg(0)->Arg(2)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
