#pragma once
/// The runs of a fragility study and how one is simulated: every record ×
/// intensity × idle time × control mode, numbered in a fixed order so that
/// any split of the work (threads, MPI ranks, a resumed study) gives the same
/// results in the same order.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "host_sim/plant/plant.hpp"
#include "mrd/control/io.hpp"

namespace mrd::risk {

/// A ground motion at the runs' step, scaled to a PGA of 1 g (a run
/// multiplies it by its PGA in g).
struct StudyRecord {
  std::string name;
  std::string source;
  std::vector<double> accel_1g_m_s2;
};

/// Peaks of one run (SI). Story drift: largest |x_i − x_{i−1}| over the
/// stories (plant::PlantSummary::peak_story_drift_m: elements 1..N−1 of an
/// isolated building, floor 1 relative to the base; every element of a fixed
/// base one).
struct RunMetrics {
  double peak_base_displacement_m = 0.0;
  double peak_damper_force_n = 0.0;
  double peak_floor_accel_m_s2 = 0.0;  ///< absolute, floors 1–5
  double peak_base_accel_m_s2 = 0.0;   ///< absolute
  double peak_story_drift_m = 0.0;
};
inline constexpr std::size_t kRunMetricCount = 5;

/// Indices of one run's factors.
struct RunKey {
  std::size_t mode = 0, idle = 0, pga = 0, record = 0;
};

struct FragilityPlan {
  std::vector<StudyRecord> records;
  std::vector<double> pga_g;       ///< intensity levels, g, increasing
  std::vector<double> idle_years;  ///< idle times, years, increasing
  std::vector<control::ControlMode> modes;
  plant::PlantSpec base{};  ///< step, building, damper, settling (idle_time_s set per run)
  std::uint64_t seed = 1;   ///< study seed (synthetic records, bootstrap)

  std::size_t run_count() const noexcept { return modes.size() * idle_years.size() * pga_g.size() * records.size(); }
  /// Run `run`'s factors: index = ((mode·n_idle + idle)·n_pga + pga)·n_records + record.
  RunKey key(std::size_t run) const noexcept;
  std::size_t index(const RunKey& k) const noexcept;
  /// FNV-1a hash of everything that decides the runs' results (the records'
  /// samples, levels, idle times, modes, step, plant kind, the building's,
  /// damper's and fluid's values, seed): a journal kept for another study is
  /// not reused.
  std::uint64_t fingerprint() const;
};

/// Simulates the runs `runs` of `plan` into `out` (same length): the
/// closed loop of run::run_closed_loop (plant::Plant stepped with the
/// firmware's controller of the run's mode), with the story drifts read
/// after every step. One call per chunk of runs: the chunk's runs step side
/// by side in SIMD lanes (host_sim/batch, the same peaks bit for bit) when
/// the lanes take the plan's plant (lanes_take), else one by one.
void simulate_runs(const FragilityPlan& plan, std::span<const std::size_t> runs, std::span<RunMetrics> out);

/// The same, one run after the other through plant::Plant.
void simulate_runs_one_by_one(const FragilityPlan& plan, std::span<const std::size_t> runs, std::span<RunMetrics> out);

/// True when the SIMD lanes step the plan's plant: the thesis (ideal) plant
/// kind, on any building, with any damper law (batch::lanes_vectorize says
/// which laws the lanes vectorize; the scalar damper steps the others in them).
bool lanes_take(const FragilityPlan& plan) noexcept;

}  // namespace mrd::risk
