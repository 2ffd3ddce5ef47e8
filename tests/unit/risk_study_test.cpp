// The fragility study's plan, split, resume journal, stochastic motions and
// run function.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <algorithm>
#include <set>
#include <span>

#include "host_sim/risk/fragility_plan.hpp"
#include "host_sim/risk/run_journal.hpp"
#include "host_sim/risk/stochastic_motion.hpp"
#include "host_sim/risk/study_runner.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/controller.hpp"
#include "mrd/units.hpp"

namespace mrd::risk {
namespace {

FragilityPlan small_plan() {
  FragilityPlan p;
  p.records = {{"a", "", {}}, {"b", "", {}}, {"c", "", {}}};
  p.pga_g = {0.1, 0.2};
  p.idle_years = {0.0, 0.5, 1.0};
  p.modes = {control::ControlMode::kPassiveOff, control::ControlMode::kPassiveOn};
  return p;
}

TEST(RiskStudy, RunIndexIsModeIdlePgaRecordWithRecordFastest) {
  const FragilityPlan p = small_plan();
  ASSERT_EQ(p.run_count(), 2u * 3u * 2u * 3u);
  // Run 17 = ((0·3 + 2)·2 + 1)·3 + 2: mode 0, idle 2, PGA 1, record 2.
  const RunKey k = p.key(17);
  EXPECT_EQ(k.mode, 0u);
  EXPECT_EQ(k.idle, 2u);
  EXPECT_EQ(k.pga, 1u);
  EXPECT_EQ(k.record, 2u);
  for (std::size_t i = 0; i < p.run_count(); ++i) EXPECT_EQ(p.index(p.key(i)), i);
}

TEST(RiskStudy, RankSharesCoverEveryRunOnce) {
  for (int size : {1, 2, 3, 7}) {
    std::multiset<std::size_t> all;
    for (int r = 0; r < size; ++r) {
      for (auto i : rank_share(101, r, size)) all.insert(i);
    }
    ASSERT_EQ(all.size(), 101u);
    for (std::size_t i = 0; i < 101; ++i) EXPECT_EQ(all.count(i), 1u);
  }
  // Chunks of 8: rank 1 of 2 holds runs 8–15, 24–31, ...
  const auto share = rank_share(40, 1, 2);
  EXPECT_EQ(share.front(), 8u);
  EXPECT_EQ(share[8], 24u);
}

TEST(RiskStudy, FingerprintChangesWithTheInputs) {
  FragilityPlan a = small_plan(), b = small_plan();
  EXPECT_EQ(a.fingerprint(), b.fingerprint());
  b.pga_g[1] = 0.25;
  EXPECT_NE(a.fingerprint(), b.fingerprint());
  b = small_plan();
  b.seed = 2;
  EXPECT_NE(a.fingerprint(), b.fingerprint());
  // Spencer's parameters count for that law only; the coil's heating when it is not the thesis coil's.
  b = small_plan();
  b.base.damper.spencer.alpha_n_m = 1.0e4;
  EXPECT_EQ(a.fingerprint(), b.fingerprint());
  b.base.damper.law = physics::ForceLaw::kSpencer;
  FragilityPlan c = b;
  c.base.damper.spencer.alpha_n_m = 2.0e4;
  EXPECT_NE(b.fingerprint(), c.fingerprint());
  c = small_plan();
  c.base.damper.coil_heat.time_constant_s = 600.0;
  EXPECT_NE(a.fingerprint(), c.fingerprint());
}

// The record's CRC checked with zlib's crc32 over magic and bytes 8–63.
TEST(RiskStudy, JournalRecordRoundTripsAndRejectsCorruption) {
  const RunMetrics m{0.1, 2e5, 3.0, 4.0, 0.005};
  unsigned char b[kJournalRecordBytes];
  encode_journal_record(42, 7, m, b);
  EXPECT_EQ(std::memcmp(b, "MRDJ", 4), 0);
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32(crc, b, 4);
  crc = crc32(crc, b + 8, 56);
  std::uint32_t stored = 0;
  std::memcpy(&stored, b + 4, 4);
  EXPECT_EQ(stored, static_cast<std::uint32_t>(crc));
  const auto r = decode_journal_record(b);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->fingerprint, 42u);
  EXPECT_EQ(r->run, 7u);
  EXPECT_EQ(r->metrics.peak_damper_force_n, 2e5);
  EXPECT_EQ(r->metrics.peak_story_drift_m, 0.005);
  b[30] ^= 1;
  EXPECT_FALSE(decode_journal_record(b));
}

TEST(RiskStudy, JournalKeepsWholeRecordsOfItsStudyOnly) {
  const auto dir = std::filesystem::temp_directory_path() / ("mrd-journal-test-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  {
    JournalWriter w(dir, 99, 0, 0);
    w.append(3, {1, 2, 3, 4, 5});
    w.append(5, {6, 7, 8, 9, 10});
    JournalWriter other(dir, 98, 1, 0);
    other.append(4, {1, 1, 1, 1, 1});
  }
  // A torn record at the end of a file, as a kill during write() leaves it.
  {
    unsigned char b[kJournalRecordBytes];
    encode_journal_record(99, 6, {1, 1, 1, 1, 1}, b);
    std::ofstream f(dir / "part-0-r0.journal", std::ios::binary | std::ios::app);
    f.write(reinterpret_cast<const char*>(b), 40);
  }
  EXPECT_EQ(journal_file_count(dir), 2u);
  const auto runs = load_journal(dir, 99, 10);
  EXPECT_TRUE(runs[3]);
  EXPECT_TRUE(runs[5]);
  EXPECT_FALSE(runs[4]);
  EXPECT_FALSE(runs[6]);
  EXPECT_EQ(runs[5]->peak_base_displacement_m, 6.0);
  std::filesystem::remove_all(dir);
}

// Stochastic motions: PGA exactly 1 g, reproducible per seed, different
// between seeds, and at rest at the start (the envelope is 0 at t = 0).
TEST(RiskStudy, StochasticMotionIsSeededAndScaled) {
  StochasticMotionRanges r;
  r.duration_s = 10.0;
  const auto a = stochastic_motion(r, record_seed(1, 0), 0);
  const auto b = stochastic_motion(r, record_seed(1, 0), 0);
  const auto c = stochastic_motion(r, record_seed(1, 1), 1);
  EXPECT_EQ(a.accel_m_s2, b.accel_m_s2);
  EXPECT_NE(a.accel_m_s2, c.accel_m_s2);
  EXPECT_DOUBLE_EQ(a.pga_m_s2(), units::kStandardGravity_m_s2);
  EXPECT_EQ(a.accel_m_s2.size(), 1001u);
  EXPECT_EQ(a.accel_m_s2.front(), 0.0);
  EXPECT_EQ(a.name, "stochastic-0");
  const auto p = draw_stochastic_params(r, record_seed(1, 0));
  EXPECT_GE(p.f_mid_hz, r.f_mid_lo_hz);
  EXPECT_LE(p.f_mid_hz, r.f_mid_hi_hz);
}

// The study's run function gives run::run_closed_loop's peaks bit for bit
// (the same plant and controller stepped the same way), plus story drifts.
TEST(RiskStudy, RunFunctionEqualsTheScalarClosedLoop) {
  FragilityPlan p;
  StochasticMotionRanges r;
  r.duration_s = 8.0;
  const auto m = stochastic_motion(r, record_seed(3, 0), 0);
  p.records = {{m.name, m.source, excitation::resample_linear(m, 1e-3)}};
  p.pga_g = {0.4};
  p.idle_years = {0.5};
  p.modes = {control::ControlMode::kSemiActive};
  const std::vector<std::size_t> runs{0};
  std::vector<RunMetrics> out(1);
  simulate_runs(p, runs, out);

  plant::PlantSpec spec = p.base;
  spec.idle_time_s = units::years_to_s(0.5);
  std::vector<double> accel = p.records[0].accel_1g_m_s2;
  for (double& a : accel) a *= 0.4;
  auto controller = run::make_controller(control::ControlMode::kSemiActive, 1e-3);
  const plant::PlantSummary s = run::run_closed_loop(spec, accel, *controller);
  EXPECT_EQ(out[0].peak_base_displacement_m, s.peak_base_displacement_m);
  EXPECT_EQ(out[0].peak_damper_force_n, s.peak_damper_force_n);
  EXPECT_EQ(out[0].peak_floor_accel_m_s2, s.peak_superstructure_accel_m_s2);
  EXPECT_EQ(out[0].peak_base_accel_m_s2, s.peak_base_accel_m_s2);
  // A story's drift is below the base's own travel and above zero.
  EXPECT_GT(out[0].peak_story_drift_m, 0.0);
  EXPECT_LT(out[0].peak_story_drift_m, s.peak_base_displacement_m);
}

// A chunk of runs in SIMD lanes (records of different lengths, every mode,
// two PGAs and idle times) gives what the runs give one by one through
// plant::Plant, every metric bit for bit; a building with lead-rubber
// bearings (any building's lanes) too.
TEST(RiskStudy, ChunksInLanesEqualTheRunsOneByOne) {
  for (const bool isolated : {false, true}) {
    SCOPED_TRACE(isolated ? "lead-rubber building" : "thesis building");
    FragilityPlan p;
    if (isolated) {
      structure::LeadRubberBearing lrb;
      lrb.count = 8;
      lrb.characteristic_strength_n = 30.0e3;
      lrb.post_yield_stiffness_n_m = 0.4e6;
      lrb.yield_displacement_m = 0.01;
      p.base.building.story_stiffness_n_m[0] = 0.0;
      p.base.building.isolators = {lrb};
    }
    StochasticMotionRanges r;
    for (std::uint64_t i = 0; i < 3; ++i) {
      r.duration_s = 3.0 + 1.5 * static_cast<double>(i);
      const auto m = stochastic_motion(r, record_seed(5, i), i);
      p.records.push_back({m.name, m.source, excitation::resample_linear(m, 1e-3)});
    }
    p.pga_g = {0.2, 0.5};
    p.idle_years = {0.0, 1.5};
    p.modes = {control::ControlMode::kPassiveOff, control::ControlMode::kPassiveOn, control::ControlMode::kSemiActive};
    ASSERT_TRUE(lanes_take(p));
    std::vector<std::size_t> runs(p.run_count());
    for (std::size_t i = 0; i < runs.size(); ++i) runs[i] = i;
    std::vector<RunMetrics> lanes(runs.size()), one(runs.size());
    for (std::size_t c = 0; c < runs.size(); c += kChunkRuns) {
      const std::size_t n = std::min(kChunkRuns, runs.size() - c);
      simulate_runs(p, std::span(runs).subspan(c, n), std::span(lanes).subspan(c, n));
    }
    simulate_runs_one_by_one(p, runs, one);
    for (std::size_t i = 0; i < runs.size(); ++i) {
      SCOPED_TRACE("run " + std::to_string(i));
      EXPECT_EQ(lanes[i].peak_base_displacement_m, one[i].peak_base_displacement_m);
      EXPECT_EQ(lanes[i].peak_damper_force_n, one[i].peak_damper_force_n);
      EXPECT_EQ(lanes[i].peak_floor_accel_m_s2, one[i].peak_floor_accel_m_s2);
      EXPECT_EQ(lanes[i].peak_base_accel_m_s2, one[i].peak_base_accel_m_s2);
      EXPECT_EQ(lanes[i].peak_story_drift_m, one[i].peak_story_drift_m);
    }
  }
}

}  // namespace
}  // namespace mrd::risk
