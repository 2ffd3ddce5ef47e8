// What a fragility study will cost before it runs (disk, time, memory), and
// the warnings on runs beyond the model.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "host_sim/excitation/ground_motion.hpp"
#include "host_sim/risk/fragility_report.hpp"
#include "host_sim/risk/stochastic_motion.hpp"
#include "host_sim/risk/study_estimate.hpp"

namespace mrd::risk {
namespace {

/// Two records ("a", "bbb") x PGA 0.1, 0.25 g x idle 0, 0.5 years x passive-on.
FragilityPlan two_by_two_plan() {
  FragilityPlan p;
  p.records = {{"a", "file a.csv", std::vector<double>(1001, 0.0)},
               {"bbb", "file bbb.csv", std::vector<double>(2001, 0.0)}};
  p.pga_g = {0.1, 0.25};
  p.idle_years = {0.0, 0.5};
  p.modes = {control::ControlMode::kPassiveOn};
  return p;
}

// runs.csv of 8 runs whose peaks all take the longest "%.9g" form,
// 1.23456789e-100 (15 characters). Header: 144 bytes with its newline. A row:
// index (1) + record (1 or 3) + "passive-on" (10) + idle ("0" or "0.5") + PGA
// ("0.1" or "0.25") + 5 peaks x 15 + 9 commas + newline = 96 + record + idle +
// PGA; over the 8 rows (each record, idle and PGA in 4 of them):
// 8·96 + 4·(1 + 3) + 4·(1 + 3) + 4·(3 + 4) = 768 + 16 + 16 + 28 = 828.
TEST(RiskEstimate, RunsCsvBoundIsTheLongestRunsCsv) {
  const FragilityPlan plan = two_by_two_plan();
  const StudyShape shape = study_shape(plan, default_limit_states(0.2, 0.3));
  ASSERT_EQ(shape.run_count(), 8u);
  const DiskEstimate d = estimate_disk(shape);
  EXPECT_EQ(d.runs_csv, 144u + 828u);
  const double longest = 1.23456789e-100;
  const std::vector<RunMetrics> runs(8, RunMetrics{longest, longest, longest, longest, longest});
  EXPECT_EQ(runs_csv(plan, runs).size(), d.runs_csv);
  // Real peaks are shorter: the bound holds.
  const std::vector<RunMetrics> real(8, RunMetrics{0.1234, 152345.6, 2.5, 3.25, 0.0042});
  EXPECT_LE(runs_csv(plan, real).size(), d.runs_csv);
  EXPECT_EQ(d.journal, 8u * 64u);
  EXPECT_EQ(d.plots, 1u * 3u * kPlotBytesBound);  // one control x three limit states (stroke, gap, accel)
  EXPECT_EQ(d.total(), d.runs_csv + d.journal + d.curves + d.plots + d.summary);
}

// fragility.csv with the longest numbers stays within the curves' bound.
TEST(RiskEstimate, CurvesBoundHoldsForTheLongestNumbers) {
  const FragilityPlan plan = two_by_two_plan();
  const auto states = default_limit_states(0.2, 0.3);
  std::vector<FragilityCurve> curves;
  for (std::size_t idle = 0; idle < 2; ++idle) {
    for (std::size_t s = 0; s < 3; ++s) {
      FragilityCurve c;
      c.idle = idle;
      c.limit_state = s;
      c.fit = {FitStatus::kFitted, 1.23456789e-100, 1.23456789e-100};
      c.band.median_low = c.band.median_high = c.band.beta_low = c.band.beta_high = 1.23456789e-100;
      c.band.im.assign(41, 1.23456789e-100);
      c.band.p_low = c.band.p_high = c.band.im;
      curves.push_back(c);
    }
  }
  const DiskEstimate d = estimate_disk(study_shape(plan, states));
  EXPECT_LE(fragility_csv(plan, states, curves).size() + fragility_curves_csv(plan, states, curves).size(), d.curves);
}

// 2 records of 1001 samples x 2 PGAs x 1 idle time x 2 modes = 8008 steps,
// 4004 per mode; at 1000 and 4000 steps/s: 4.004 + 1.001 = 5.005 s of one
// worker, over 2 workers 2.5025 s, plus 1 s to make the records.
TEST(RiskEstimate, WallTimeIsStepsOverTheMeasuredRateAndTheWorkers) {
  StudyShape s;
  s.record_names = {"a", "b"};
  s.record_samples = {1001, 1001};
  s.pga_g = {0.1, 0.2};
  s.idle_years = {0.0};
  s.modes = {control::ControlMode::kPassiveOn, control::ControlMode::kPassiveOff};
  EXPECT_DOUBLE_EQ(s.steps(), 8008.0);
  EXPECT_NEAR(estimate_wall_s(s, {1000.0, 4000.0}, 2, 1.0), 3.5025, 1e-12);
}

// Workers: ranks x threads, the threads at most the cores, at most the
// chunks of 8 runs (20 runs: 3 chunks).
TEST(RiskEstimate, WorkersAreBoundedByCoresAndChunks) {
  EXPECT_EQ(study_workers(20, 2, 4, 2), 3u);     // 2 x min(4, 2) = 4, 3 chunks
  EXPECT_EQ(study_workers(1000, 2, 4, 2), 4u);   // 2 x min(4, 2)
  EXPECT_EQ(study_workers(1000, 1, 1, 64), 1u);
  EXPECT_EQ(study_workers(1, 4, 8, 8), 1u);      // one chunk
}

// An 8-s stochastic motion is made at 0.01 s (801 samples, 8 s) and
// resampled to 1 ms: 8001 samples; the shape says so before it is made.
TEST(RiskEstimate, SyntheticShapeCountsTheSamplesTheRecordsWillHave) {
  FragilityPlan plan;
  plan.pga_g = {0.3};
  plan.idle_years = {0.0};
  plan.modes = {control::ControlMode::kPassiveOn};
  StochasticMotionRanges ranges;
  ranges.duration_s = 8.0;
  const StudyShape s = synthetic_study_shape(plan, default_limit_states(0.2, 0.3), ranges, 3);
  ASSERT_EQ(s.record_samples.size(), 3u);
  EXPECT_EQ(s.record_samples[0], 8001u);
  EXPECT_EQ(s.record_names[2], "stochastic-2");
  const auto made = excitation::resample_linear(stochastic_motion(ranges, record_seed(plan.seed, 0), 0), 1e-3);
  EXPECT_EQ(made.size(), 8001u);
  // Memory: 3 records x 8001 samples x 8 bytes at least.
  EXPECT_GE(estimate_memory(s), 3u * 8001u * 8u);
}

TEST(RiskEstimate, PilotMeasuresAPositiveRate) {
  const double rate = pilot_steps_per_s(plant::PlantSpec{}, control::ControlMode::kPassiveOn, 0.3, 0.0, 0.001);
  EXPECT_TRUE(std::isfinite(rate));
  EXPECT_GT(rate, 0.0);
}

// A folder that does not exist yet is examined at its nearest existing
// ancestor.
TEST(RiskEstimate, FreeSpaceOfAFolderNotYetMadeIsItsParents) {
  const auto tmp = std::filesystem::temp_directory_path();
  const auto space = file_system_space(tmp / ("mrd-absent-" + std::to_string(::getpid())) / "out");
  ASSERT_TRUE(space.has_value());
  EXPECT_EQ(space->examined, std::filesystem::absolute(tmp).lexically_normal());
}

TEST(RiskEstimate, SizesAndDurationsReadAsAPersonWouldSayThem) {
  EXPECT_EQ(format_bytes(999), "999 B");
  EXPECT_EQ(format_bytes(1234), "1.23 kB");
  EXPECT_EQ(format_bytes(999'999), "1 MB");
  EXPECT_EQ(format_bytes(80'300'000'000), "80.3 GB");
  EXPECT_EQ(format_duration(0.42), "0.42 s");
  EXPECT_EQ(format_duration(90.0), "1.5 min");
  EXPECT_EQ(format_duration(5400.0), "1.5 h");
  EXPECT_EQ(format_duration(3.0 * 86400.0), "3 days");
}

// Of three runs, two beyond the damper's ±0.2921 m stroke (worst 0.5 m) and
// one beyond its 200 kN (250 kN): one sentence each with count and worst.
TEST(RiskEstimate, RunsBeyondTheModelAreCountedWithTheirWorstPeak) {
  const std::vector<RunMetrics> runs{{0.1, 150e3, 1, 1, 0.01}, {0.5, 250e3, 1, 1, 0.01}, {0.3, 100e3, 1, 1, 0.01}};
  const auto w = fragility_warnings(runs);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0].rfind("in 2 of 3 runs: peak stroke 0.5 m exceeds the damper's +-0.2921 m", 0), 0u) << w[0];
  EXPECT_EQ(w[1].rfind("in 1 of 3 runs: peak damper force 2.5e+05 N exceeds the damper's 2e+05 N capacity", 0), 0u)
      << w[1];
  EXPECT_TRUE(fragility_warnings({{0.2921, 200e3, 1, 1, 0.01}}).empty());
}

}  // namespace
}  // namespace mrd::risk
