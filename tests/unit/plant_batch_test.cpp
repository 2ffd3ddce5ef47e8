// The batch path (host_sim/batch) against the scalar closed loop
// (run::run_closed_loop): every lane's peaks, coil figures and time series
// must equal the scalar run's, for every control mode,
// every lane kernel this CPU runs, batch sizes that are not multiples of
// the lane count, runs of different lengths, and real records as well as
// synthetic ones. The scalar path is the independent check: it steps the
// plant through Eigen and the physics headers, not through the lanes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <deque>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "host_sim/batch/batch_run.hpp"
#include "host_sim/batch/lane_block.hpp"
#include "host_sim/run/motions.hpp"
#include "host_sim/structure/building_file.hpp"
#include "mrd/units.hpp"

namespace {

using mrd::batch::BatchRun;
using mrd::batch::LaneIsa;
using mrd::control::ControlMode;
namespace fs = std::filesystem;

constexpr double kStep_s = 1e-3;

std::vector<LaneIsa> isas() {
  std::vector<LaneIsa> out;
  for (LaneIsa isa : {LaneIsa::kGeneric, LaneIsa::kX86_64V3, LaneIsa::kX86_64V4}) {
    if (mrd::batch::lane_isa_available(isa)) out.push_back(isa);
  }
  return out;
}

/// Issue 13 asks for 1e-12 relative; the lanes repeat the scalar plant's
/// operations in its order, so the values are the same doubles, and only
/// exact equality catches an operation out of order (a reordered 12-term
/// sum moves a peak by about 1e-16).
void expect_equal(double batch, double scalar, const std::string& what) {
  EXPECT_EQ(batch, scalar) << what;
}

void expect_same_summary(const mrd::plant::PlantSummary& b, const mrd::plant::PlantSummary& s) {
  EXPECT_EQ(b.ticks, s.ticks);
  expect_equal(b.peak_base_displacement_m, s.peak_base_displacement_m, "peak base displacement");
  expect_equal(b.peak_damper_force_n, s.peak_damper_force_n, "peak damper force");
  expect_equal(b.peak_base_velocity_m_s, s.peak_base_velocity_m_s, "peak base velocity");
  expect_equal(b.peak_superstructure_accel_m_s2, s.peak_superstructure_accel_m_s2, "peak floor acceleration");
  expect_equal(b.peak_base_accel_m_s2, s.peak_base_accel_m_s2, "peak base acceleration");
  expect_equal(b.peak_current_a, s.peak_current_a, "peak current");
  expect_equal(b.peak_isolator_force_n, s.peak_isolator_force_n, "peak isolator force");
  expect_equal(b.peak_story_drift_m, s.peak_story_drift_m, "peak story drift");
  expect_equal(b.peak_damper_stroke_m, s.peak_damper_stroke_m, "peak damper stroke");
  expect_equal(b.final_participant_ratio, s.final_participant_ratio, "final PR");
  expect_equal(b.sq, s.sq, "SQ");
  expect_equal(b.duration_s, s.duration_s, "duration");
  expect_equal(b.coil.peak_coil_current_a, s.coil.peak_coil_current_a, "coil peak");
  expect_equal(b.coil.rms_coil_current_a, s.coil.rms_coil_current_a, "coil rms");
  expect_equal(b.coil.time_above_rated_s, s.coil.time_above_rated_s, "time above rating");
  expect_equal(b.coil.command_changes_per_s, s.coil.command_changes_per_s, "command changes");
  expect_equal(b.coil.peak_coil_temperature_rise_k, s.coil.peak_coil_temperature_rise_k, "coil rise");
}

/// Runs of one batch with their own scaled copies of the ground motion (what
/// the scalar path is given).
struct Case {
  std::vector<BatchRun> runs;
  std::vector<std::vector<double>> scaled;  ///< ground_scale · record, per run
};

void add_run(Case& c, const std::vector<double>& record, std::size_t length, double scale, double idle_years,
             ControlMode mode) {
  BatchRun r;
  r.ground_accel_m_s2 = std::span<const double>(record.data(), std::min(length, record.size()));
  r.ground_scale = scale;
  r.idle_time_s = mrd::units::years_to_s(idle_years);
  r.mode = mode;
  c.runs.push_back(r);
  std::vector<double> s(r.ground_accel_m_s2.size());
  for (std::size_t k = 0; k < s.size(); ++k) s[k] = record[k] * scale;
  c.scaled.push_back(std::move(s));
}

mrd::plant::PlantSummary scalar_run(const mrd::plant::PlantSpec& plant, const BatchRun& r,
                                    const std::vector<double>& scaled, mrd::run::ClosedLoopRecord* record = nullptr) {
  mrd::plant::PlantSpec spec = plant;
  spec.idle_time_s = r.idle_time_s;
  auto controller = mrd::run::make_controller(r.mode, spec.step_s);
  return mrd::run::run_closed_loop(spec, scaled, *controller, record);
}

void expect_batch_equals_scalar(const Case& c, const mrd::plant::PlantSpec& plant = {}) {
  for (LaneIsa isa : isas()) {
    SCOPED_TRACE(mrd::batch::lane_isa_name(isa));
    mrd::batch::BatchOptions options;
    options.isa = isa;
    const auto batch = mrd::batch::run_closed_loop_batch(plant, c.runs, options);
    ASSERT_EQ(batch.size(), c.runs.size());
    for (std::size_t i = 0; i < c.runs.size(); ++i) {
      SCOPED_TRACE("run " + std::to_string(i) + " (" + mrd::control::mode_name(c.runs[i].mode) + ")");
      expect_same_summary(batch[i], scalar_run(plant, c.runs[i], c.scaled[i]));
    }
  }
}

const std::vector<double>& synthetic(unsigned seed, double duration_s) {
  static std::deque<std::vector<double>> keep;  // references stay valid
  keep.push_back(mrd::run::synthetic_study_motion(seed, mrd::run::kThesisPga_g, kStep_s, duration_s).accel_m_s2);
  return keep.back();
}

/// The four records of ../shared/ground_motions (Table 6.2) at the thesis
/// PGA; none when a record is missing.
const std::vector<std::vector<double>>& shared_records() {
  static const std::vector<std::vector<double>> records = [] {
    std::vector<std::vector<double>> out;
    const auto dir = mrd::run::find_shared_ground_motions();
    if (!dir) return out;
    for (const char* name : {"elcentro_ns.csv", "hachinohe_ns.csv", "kobe_jma_ns.csv", "northridge_sylmar_ns.csv"}) {
      if (!fs::exists(*dir / name)) return std::vector<std::vector<double>>{};
      out.push_back(mrd::run::load_study_motion(*dir / name, mrd::run::kThesisPga_g, kStep_s).accel_m_s2);
    }
    return out;
  }();
  return records;
}

/// The shared records are part of the checkout's surroundings (../shared
/// beside the clone, or MRD_SHARED_DIR): their absence is a failure.
#define REQUIRE_SHARED_RECORDS()                                                                        \
  do {                                                                                                  \
    if (shared_records().empty()) {                                                                     \
      FAIL() << "the four records of the shared ground_motions folder were not found (../shared beside " \
                "the checkout, or MRD_SHARED_DIR)";                                                     \
    }                                                                                                   \
  } while (false)

TEST(BatchExp, EveryKernelsExpIsTheCLibrarysBitForBit) {
  // The arguments the damper feeds exp(): −c·|i| and −c_PR·∫Q, from 0 down
  // to the underflow range, plus the tiny and positive edges.
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> wide(-800.0, 10.0), narrow(-4.0, 0.0);
  std::vector<double> x = {0.0, -0.0, 0x1p-60, -0x1p-54, -0x1p-53, 1e-310, -511.999, -512.0, -745.1, -746.0};
  for (int i = 0; i < 50000; ++i) x.push_back(wide(rng));
  for (int i = 0; i < 50000; ++i) x.push_back(narrow(rng));
  x.push_back(0.25);  // an odd count: the kernels' partial last vector
  std::vector<mrd::batch::LaneKernel> kernels = {mrd::batch::generic_lane_kernel()};
#if defined(__x86_64__)
  using mrd::batch::LaneIsa;
  if (mrd::batch::lane_isa_cpu_runs(LaneIsa::kX86_64V3)) kernels.push_back(mrd::batch::x86_64_v3_lane_kernel());
  if (mrd::batch::lane_isa_cpu_runs(LaneIsa::kX86_64V4)) kernels.push_back(mrd::batch::x86_64_v4_lane_kernel());
#endif
  for (const auto& k : kernels) {
    SCOPED_TRACE(k.name);
    std::vector<double> y(x.size());
    k.exp(x.data(), y.data(), x.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double e = std::exp(x[i]);
      if (std::memcmp(&e, &y[i], sizeof e) != 0) ++differ;
    }
    EXPECT_EQ(differ, 0u);
  }
}

// The instruction check against GCC's own reading of the psABI levels
// (libgcc's __builtin_cpu_supports("x86-64-v3"/"x86-64-v4"), which Clang 14
// lacks): under GCC both must agree on this CPU.
TEST(Batch, CpuLevelsAgreeWithGccsOwnCheck) {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  EXPECT_EQ(mrd::batch::lane_isa_cpu_runs(LaneIsa::kX86_64V3), __builtin_cpu_supports("x86-64-v3") != 0);
  EXPECT_EQ(mrd::batch::lane_isa_cpu_runs(LaneIsa::kX86_64V4), __builtin_cpu_supports("x86-64-v4") != 0);
#endif
  EXPECT_TRUE(mrd::batch::lane_isa_cpu_runs(LaneIsa::kGeneric));
}

TEST(Batch, AutoPicksAKernelThisCpuRuns) {
  const LaneIsa isa = mrd::batch::auto_lane_isa();
  EXPECT_NE(isa, LaneIsa::kAuto);
  EXPECT_TRUE(mrd::batch::lane_isa_available(isa));
  EXPECT_GE(mrd::batch::lane_count(isa), 4);
}

// Each mode alone, in batches of 1, 3, 5 and 11 runs (none a multiple of
// 4 or 8) over synthetic motions of different lengths, scalings and idle times.
TEST(Batch, SyntheticRunsOfEachModeEqualTheScalarLoop) {
  for (ControlMode mode : {ControlMode::kPassiveOff, ControlMode::kPassiveOn, ControlMode::kSemiActive}) {
    SCOPED_TRACE(mrd::control::mode_name(mode));
    for (std::size_t n : {1u, 3u, 5u, 11u}) {
      SCOPED_TRACE("batch of " + std::to_string(n));
      Case c;
      for (std::size_t i = 0; i < n; ++i) {
        const auto& rec = synthetic(static_cast<unsigned>(1 + i % 3), 12.0);
        add_run(c, rec, 4000 + 700 * i, 0.5 + 0.37 * static_cast<double>(i), 0.25 * static_cast<double>(i % 5),
                mode);
      }
      expect_batch_equals_scalar(c);
    }
  }
}

// The four shared records (Table 6.2) at several scalings and idle times,
// 13 runs per mode, each record cut to a different length.
TEST(Batch, RealRecordsOfEachModeEqualTheScalarLoop) {
  REQUIRE_SHARED_RECORDS();
  const auto& records = shared_records();
  for (ControlMode mode : {ControlMode::kPassiveOff, ControlMode::kPassiveOn, ControlMode::kSemiActive}) {
    SCOPED_TRACE(mrd::control::mode_name(mode));
    Case c;
    for (std::size_t i = 0; i < 13; ++i) {
      const auto& rec = records[i % records.size()];
      add_run(c, rec, 15000 + 1000 * i, 1.0 + 0.5 * static_cast<double>(i % 4), 0.5 * static_cast<double>(i % 6),
              mode);
    }
    expect_batch_equals_scalar(c);
  }
}

// One batch mixing the modes, an empty run and very different lengths.
TEST(Batch, MixedModesAndLengthsInOneBatch) {
  Case c;
  const auto& a = synthetic(7, 10.0);
  const auto& b = synthetic(8, 3.0);
  const ControlMode modes[] = {ControlMode::kPassiveOff, ControlMode::kSemiActive, ControlMode::kPassiveOn};
  for (std::size_t i = 0; i < 10; ++i) {
    add_run(c, i % 2 ? a : b, i == 4 ? 0 : 500 + 900 * i, 1.0 + 0.1 * static_cast<double>(i),
            0.3 * static_cast<double>(i), modes[i % 3]);
  }
  expect_batch_equals_scalar(c);
}

// A few samples of every time series, with records on some lanes only.
TEST(Batch, TimeSeriesSamplesEqualTheScalarLoop) {
  REQUIRE_SHARED_RECORDS();
  const std::vector<double>& rec = shared_records()[1];  // Hachinohe
  const mrd::plant::PlantSpec plant;
  for (LaneIsa isa : isas()) {
    SCOPED_TRACE(mrd::batch::lane_isa_name(isa));
    Case c;
    const ControlMode modes[] = {ControlMode::kPassiveOn, ControlMode::kSemiActive, ControlMode::kPassiveOff};
    for (std::size_t i = 0; i < 5; ++i) add_run(c, rec, 12000 + 1500 * i, 1.5, 0.5 + static_cast<double>(i), modes[i % 3]);
    std::vector<mrd::run::ClosedLoopRecord> recs(c.runs.size());
    for (std::size_t i = 0; i < c.runs.size(); i += 2) c.runs[i].record = &recs[i];
    mrd::batch::BatchOptions options;
    options.isa = isa;
    const auto batch = mrd::batch::run_closed_loop_batch(plant, c.runs, options);
    for (std::size_t i = 0; i < c.runs.size(); ++i) {
      SCOPED_TRACE("run " + std::to_string(i));
      mrd::run::ClosedLoopRecord s;
      expect_same_summary(batch[i], scalar_run(plant, c.runs[i], c.scaled[i], &s));
      if (!c.runs[i].record) continue;
      const auto& b = recs[i];
      ASSERT_EQ(b.time_s.size(), s.time_s.size());
      const std::size_t n = s.time_s.size();
      for (std::size_t k : {std::size_t{0}, n / 7, n / 3, n / 2, (3 * n) / 4, n - 1}) {
        SCOPED_TRACE("sample " + std::to_string(k));
        expect_equal(b.time_s[k], s.time_s[k], "t");
        expect_equal(b.ground_accel_m_s2[k], s.ground_accel_m_s2[k], "a_g");
        expect_equal(b.base_disp_m[k], s.base_disp_m[k], "x_b");
        expect_equal(b.base_vel_m_s[k], s.base_vel_m_s[k], "v_b");
        expect_equal(b.damper_force_n[k], s.damper_force_n[k], "F");
        expect_equal(b.desired_force_n[k], s.desired_force_n[k], "F_d");
        expect_equal(b.command_a[k], s.command_a[k], "u");
        expect_equal(b.current_a[k], s.current_a[k], "i");
        expect_equal(b.pr[k], s.pr[k], "PR");
        expect_equal(b.roof_accel_m_s2[k], s.roof_accel_m_s2[k], "roof acceleration");
        expect_equal(b.peak_floor_accel_m_s2[k], s.peak_floor_accel_m_s2[k], "floor acceleration");
      }
      ASSERT_EQ(b.story_elements, s.story_elements);
      ASSERT_EQ(b.story_drift_m, s.story_drift_m);
      ASSERT_EQ(b.isolator_force_n, s.isolator_force_n);
    }
  }
}

/// The plant on a building file of buildings/.
mrd::plant::PlantSpec plant_on(const char* file) {
  mrd::plant::PlantSpec plant;
  plant.building = mrd::structure::read_building_file(fs::path(MRD_BUILDINGS_DIR) / file);
  return plant;
}

// Any building: lead-rubber bearings (sub-steps, Bouc-Wen in the lanes), a
// friction pendulum with two dampers on different elements, a fixed base
// with Rayleigh damping; every mode, batches of 5 runs of different lengths,
// scalings and idle times, every peak the scalar plant reports.
TEST(Batch, AnyBuildingsRunsOfEachModeEqualTheScalarLoop) {
  for (const char* file : {"lead-rubber-7dof.toml", "friction-pendulum-5dof.toml", "fixed-base-8dof.toml"}) {
    SCOPED_TRACE(file);
    const mrd::plant::PlantSpec plant = plant_on(file);
    for (ControlMode mode : {ControlMode::kPassiveOff, ControlMode::kPassiveOn, ControlMode::kSemiActive}) {
      SCOPED_TRACE(mrd::control::mode_name(mode));
      Case c;
      for (std::size_t i = 0; i < 5; ++i) {
        const auto& rec = synthetic(static_cast<unsigned>(11 + i % 2), 6.0);
        add_run(c, rec, 3000 + 600 * i, 0.6 + 0.45 * static_cast<double>(i), 0.4 * static_cast<double>(i), mode);
      }
      expect_batch_equals_scalar(c, plant);
    }
  }
}

// A damper's own coil (MrDamperParams::coil_heat: 12 ohm, 3 K/W, 60 s) heats
// in both kinds of lanes as in the scalar loop, and not as the thesis coil.
TEST(Batch, ADampersOwnCoilHeatsInTheLanesAsInTheScalarLoop) {
  for (const char* file : {"", "lead-rubber-7dof.toml"}) {
    SCOPED_TRACE(*file ? file : "thesis shape");
    mrd::plant::PlantSpec plant = *file ? plant_on(file) : mrd::plant::PlantSpec{};
    plant.damper.coil_heat = {12.0, 3.0, 60.0};
    Case c;
    const ControlMode modes[] = {ControlMode::kPassiveOn, ControlMode::kSemiActive, ControlMode::kPassiveOff};
    for (std::size_t i = 0; i < 6; ++i)
      add_run(c, synthetic(static_cast<unsigned>(21 + i % 2), 8.0), 5000 + 500 * i, 1.0, 0.5, modes[i % 3]);
    expect_batch_equals_scalar(c, plant);
    const auto own = mrd::batch::run_closed_loop_batch(plant, c.runs);
    const auto thesis = mrd::batch::run_closed_loop_batch(*file ? plant_on(file) : mrd::plant::PlantSpec{}, c.runs);
    EXPECT_GT(own[0].coil.peak_coil_temperature_rise_k, 0.0);
    EXPECT_NE(own[0].coil.peak_coil_temperature_rise_k, thesis[0].coil.peak_coil_temperature_rise_k);
  }
}

// The isolated buildings' time series: isolator force and every story's drift.
TEST(Batch, AnyBuildingsTimeSeriesEqualTheScalarLoop) {
  for (const char* file : {"lead-rubber-7dof.toml", "friction-pendulum-5dof.toml", "thesis-6dof.toml"}) {
    SCOPED_TRACE(file);
    const mrd::plant::PlantSpec plant = plant_on(file);
    const auto& rec = synthetic(21, 5.0);
    for (LaneIsa isa : isas()) {
      SCOPED_TRACE(mrd::batch::lane_isa_name(isa));
      Case c;
      const ControlMode modes[] = {ControlMode::kSemiActive, ControlMode::kPassiveOn, ControlMode::kPassiveOff};
      for (std::size_t i = 0; i < 3; ++i) add_run(c, rec, 5000 - 900 * i, 2.0, 1.0, modes[i]);
      std::vector<mrd::run::ClosedLoopRecord> recs(c.runs.size());
      for (std::size_t i = 0; i < c.runs.size(); ++i) c.runs[i].record = &recs[i];
      mrd::batch::BatchOptions options;
      options.isa = isa;
      const auto batch = mrd::batch::run_closed_loop_batch(plant, c.runs, options);
      for (std::size_t i = 0; i < c.runs.size(); ++i) {
        SCOPED_TRACE("run " + std::to_string(i));
        mrd::run::ClosedLoopRecord s;
        expect_same_summary(batch[i], scalar_run(plant, c.runs[i], c.scaled[i], &s));
        const auto& b = recs[i];
        EXPECT_EQ(b.base_disp_m, s.base_disp_m);
        EXPECT_EQ(b.base_vel_m_s, s.base_vel_m_s);
        EXPECT_EQ(b.damper_force_n, s.damper_force_n);
        EXPECT_EQ(b.command_a, s.command_a);
        EXPECT_EQ(b.pr, s.pr);
        EXPECT_EQ(b.roof_accel_m_s2, s.roof_accel_m_s2);
        EXPECT_EQ(b.peak_floor_accel_m_s2, s.peak_floor_accel_m_s2);
        EXPECT_EQ(b.story_elements, s.story_elements);
        EXPECT_EQ(b.story_drift_m, s.story_drift_m);
        EXPECT_EQ(b.isolator_force_n, s.isolator_force_n);
      }
    }
  }
}

// Without story drifts the passive thesis lanes skip them: every other
// figure is unchanged and the drift peak says it was not computed.
TEST(Batch, WithoutStoryDriftsTheOtherPeaksAreUnchanged) {
  Case c;
  const auto& rec = synthetic(5, 6.0);
  const ControlMode modes[] = {ControlMode::kPassiveOff, ControlMode::kPassiveOn, ControlMode::kSemiActive};
  for (std::size_t i = 0; i < 6; ++i) add_run(c, rec, 4000 + 300 * i, 1.0 + 0.2 * static_cast<double>(i), 0.5, modes[i % 3]);
  mrd::batch::BatchOptions options;
  options.story_drift = false;
  const auto without = mrd::batch::run_closed_loop_batch({}, c.runs, options);
  const auto with = mrd::batch::run_closed_loop_batch({}, c.runs, {});
  for (std::size_t i = 0; i < c.runs.size(); ++i) {
    SCOPED_TRACE("run " + std::to_string(i));
    EXPECT_TRUE(std::isnan(without[i].peak_story_drift_m));
    EXPECT_GT(with[i].peak_story_drift_m, 0.0);
    mrd::plant::PlantSummary a = without[i];
    a.peak_story_drift_m = with[i].peak_story_drift_m;
    expect_same_summary(a, with[i]);
  }
}

// Semi-active runs of the fixed-point and double builds (one scalar core per
// lane: only the float build has lanes of the core) equal the scalar loop
// with that build's controller, mixed with float-build lanes' modes.
TEST(Batch, FixedAndDoubleBuildsEqualTheirScalarLoop) {
  Case c;
  const auto& rec = synthetic(9, 5.0);
  for (std::size_t i = 0; i < 5; ++i) {
    add_run(c, rec, 3000 + 400 * i, 0.8 + 0.3 * static_cast<double>(i), 0.4 * static_cast<double>(i),
            i == 2 ? ControlMode::kPassiveOn : ControlMode::kSemiActive);
  }
  for (mrd::run::NumericKind numeric : {mrd::run::NumericKind::kFixed, mrd::run::NumericKind::kDouble}) {
    SCOPED_TRACE(mrd::run::numeric_name(numeric));
    for (LaneIsa isa : isas()) {
      SCOPED_TRACE(mrd::batch::lane_isa_name(isa));
      mrd::batch::BatchOptions options;
      options.isa = isa;
      options.numeric = numeric;
      const auto batch = mrd::batch::run_closed_loop_batch({}, c.runs, options);
      for (std::size_t i = 0; i < c.runs.size(); ++i) {
        SCOPED_TRACE("run " + std::to_string(i));
        mrd::plant::PlantSpec spec;
        spec.idle_time_s = c.runs[i].idle_time_s;
        auto controller = mrd::run::make_controller(c.runs[i].mode, spec.step_s, numeric);
        expect_same_summary(batch[i], mrd::run::run_closed_loop(spec, c.scaled[i], *controller));
      }
    }
  }
}

// A calibration's bends of the Bingham laws (physics::LawShape) in the lanes:
// current exponents (f_c and c_0 through |I|^q), a viscous exponent, a
// spring on the damper's stroke, a transition time and a lost motion at
// reversals (a share of the force held up inside the play, with and without
// a band of force there), alone and together,
// with Eq. 4.4's transition and with the tanh one, on the thesis building,
// an isolated one and a fixed-base one whose second damper sits on the second
// story (its own stroke). Each lane equals the scalar loop bit for bit, in
// every mode and kernel, and the shape changes the run.
TEST(Batch, ACalibrationsShapeStepsInTheLanesAsInTheScalarLoop) {
  mrd::physics::LawShape exponents;
  exponents.yield_current_exponent = 0.7;
  exponents.viscous_current_exponent = 1.4;
  mrd::physics::LawShape viscous;
  viscous.viscous_exponent = 0.6;
  viscous.viscous_ref_m_s = 0.05;
  mrd::physics::LawShape spring;
  spring.stiffness_n_m = 2.0e5;
  mrd::physics::LawShape timed;
  timed.transition_time_s = 0.002;
  mrd::physics::LawShape lost;
  lost.lost_motion_m_per_n = 2e-9;  // 0.5 mm of play at 250 kN
  lost.lost_motion_share = 0.6;
  mrd::physics::LawShape lost_band = lost;
  lost_band.lost_motion_band_m_s = 0.01;
  mrd::physics::LawShape all = exponents;
  all.viscous_exponent = 0.6;
  all.viscous_ref_m_s = 0.05;
  all.stiffness_n_m = 2.0e5;
  all.transition_time_s = 0.002;
  all.lost_motion_m_per_n = 2e-9;
  all.lost_motion_share = 0.6;
  all.lost_motion_band_m_s = 0.01;
  using mrd::physics::ForceLaw;
  const struct {
    const char* name;
    ForceLaw law;
    mrd::physics::LawShape shape;
  } shapes[] = {{"current exponents", ForceLaw::kBingham, exponents},
                {"viscous exponent", ForceLaw::kBingham, viscous},
                {"spring", ForceLaw::kBingham, spring},
                {"transition time", ForceLaw::kBingham, timed},
                {"lost motion", ForceLaw::kBingham, lost},
                {"lost motion with a band", ForceLaw::kBingham, lost_band},
                {"all", ForceLaw::kBingham, all},
                {"tanh", ForceLaw::kBinghamTanh, {}},
                {"tanh, all", ForceLaw::kBinghamTanh, all},
                {"tanh, lost motion", ForceLaw::kBinghamTanh, lost_band}};
  for (const char* file : {"", "lead-rubber-7dof.toml", "fixed-base-8dof.toml"}) {
    SCOPED_TRACE(*file ? file : "thesis building");
    for (const auto& [name, law, shape] : shapes) {
      SCOPED_TRACE(name);
      mrd::plant::PlantSpec plant = *file ? plant_on(file) : mrd::plant::PlantSpec{};
      plant.damper.law = law;
      plant.damper.shape = shape;
      ASSERT_TRUE(mrd::batch::lanes_vectorize(plant.damper));
      Case c;
      const ControlMode modes[] = {ControlMode::kSemiActive, ControlMode::kPassiveOn, ControlMode::kPassiveOff};
      for (std::size_t i = 0; i < 3; ++i)
        add_run(c, synthetic(static_cast<unsigned>(31 + i), 6.0), 6000 - 1000 * i, 1.5, 0.5 * static_cast<double>(i), modes[i]);
      expect_batch_equals_scalar(c, plant);
      const auto bent = mrd::batch::run_closed_loop_batch(plant, c.runs);
      const auto plain = mrd::batch::run_closed_loop_batch(*file ? plant_on(file) : mrd::plant::PlantSpec{}, c.runs);
      EXPECT_NE(bent[0].peak_damper_force_n, plain[0].peak_damper_force_n);
    }
  }
}

// The laws the lanes do not vectorize (Bouc–Wen, with a calibration's
// current exponent and lost motion; Spencer et al.'s modified Bouc–Wen with
// the laboratory's published fit, issue text: k0 = 1.501e-4 N/mm, k1 =
// 1.2388 N/mm, x0 = 2.309e-3 mm, α(i) = −38.152 i² + 41.508 i + 15.221 N/mm,
// γ(i) = 1.8941 e^(−3.6561 i) mm⁻², c0(i) = 7.626 i + 0.9249 N·s/mm, c1(i) =
// 78.337 i + 9.867 N·s/mm, A = 300, n = 2, β = γ; in SI below) step in the
// lanes through the scalar damper, one per damper and lane: each lane equals
// the scalar loop bit for bit, in every mode and kernel.
TEST(Batch, TheOtherLawsStepInTheLanesThroughTheScalarDamper) {
  mrd::plant::PlantSpec bouc_wen;
  bouc_wen.damper.law = mrd::physics::ForceLaw::kBoucWen;
  bouc_wen.damper.bouc_wen.yield_disp_m = 0.002;
  bouc_wen.damper.bouc_wen.stiffness_n_m = 1.0e5;
  bouc_wen.damper.shape.yield_current_exponent = 0.8;
  bouc_wen.damper.shape.lost_motion_m_per_n = 2e-9;
  bouc_wen.damper.shape.lost_motion_share = 0.5;
  mrd::plant::PlantSpec spencer = plant_on("lab-frame-2dof.toml");
  spencer.damper.law = mrd::physics::ForceLaw::kSpencer;
  mrd::physics::SpencerParams& p = spencer.damper.spencer;
  p.alpha_n_m = 15221.0;
  p.alpha_per_a_n_m = 41508.0;
  p.alpha_per_a2_n_m = -38152.0;
  p.c0_ns_m = 924.9;
  p.c0_per_a_ns_m = 7626.0;
  p.c1_ns_m = 9867.0;
  p.c1_per_a_ns_m = 78337.0;
  p.gamma_per_m_pow_n = 1.8941e6;
  p.gamma_rate_per_a = 3.6561;
  p.beta_over_gamma = 1.0;
  p.a = 300.0;
  p.n = 2.0;
  p.k0_n_m = 0.1501;
  p.k1_n_m = 1238.8;
  p.x0_m = 2.309e-6;
  spencer.damper.rating.current_a = 1.0;
  // A tanh law behind a series compliance (a solve per step) with a lost motion beside it.
  mrd::plant::PlantSpec series;
  series.damper.law = mrd::physics::ForceLaw::kBinghamTanh;
  series.damper.shape.series_compliance_m_per_n = 5e-9;
  series.damper.shape.lost_motion_m_per_n = 2e-9;
  series.damper.shape.lost_motion_share = 0.5;
  for (const auto& [name, plant] :
       {std::pair{"bouc_wen", bouc_wen}, std::pair{"spencer", spencer}, std::pair{"series", series}}) {
    SCOPED_TRACE(name);
    EXPECT_FALSE(mrd::batch::lanes_vectorize(plant.damper));
    Case c;
    const ControlMode modes[] = {ControlMode::kSemiActive, ControlMode::kPassiveOn, ControlMode::kPassiveOff};
    const double scale = plant.damper.law == mrd::physics::ForceLaw::kSpencer ? 0.05 : 1.0;  // the 1 kN damper's frame
    for (std::size_t i = 0; i < 5; ++i)
      add_run(c, synthetic(static_cast<unsigned>(41 + i % 2), 4.0), 4000 - 500 * i, scale,
              0.25 * static_cast<double>(i), modes[i % 3]);
    expect_batch_equals_scalar(c, plant);
    const auto lanes = mrd::batch::run_closed_loop_batch(plant, c.runs);
    EXPECT_GT(lanes[1].peak_damper_force_n, 0.0);
  }
}

TEST(Batch, RefusesTheHardwarePlant) {
  mrd::plant::PlantSpec plant;
  plant.kind = mrd::plant::PlantKind::kHardware;
  const std::vector<double> a(10, 0.1);
  const BatchRun r{a};
  EXPECT_THROW((void)mrd::batch::run_closed_loop_batch(plant, std::span<const BatchRun>(&r, 1)),
               std::invalid_argument);
}

}  // namespace
