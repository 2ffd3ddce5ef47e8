#pragma once
/// Runs a fragility study's plan on this process's share of the work and
/// gathers the results on rank 0, keeping every completed run in the resume
/// journal.
///
/// Split: the runs in order are cut in chunks of kChunkRuns; chunk c belongs
/// to rank c mod N. A rank's threads take its pending chunks in order. Each
/// run depends only on its own inputs, so the results, and runs.csv written
/// from them in run order, are the same for any N, any thread count and any
/// resumption.

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

#include "host_sim/risk/cluster.hpp"
#include "host_sim/risk/fragility_plan.hpp"

namespace mrd::risk {

inline constexpr std::size_t kChunkRuns = 8;

/// What a rank reports as it goes: its completed and total runs of this
/// session (resumed runs excluded) and the time since it started.
struct StudyProgress {
  std::size_t done = 0;
  std::size_t total = 0;
  double elapsed_s = 0.0;
};

struct StudyRunOptions {
  unsigned threads = 1;                                ///< worker threads of this rank (≥ 1)
  std::filesystem::path journal_dir;                   ///< resume store (see run_journal.hpp)
  std::function<void(const StudyProgress&)> progress;  ///< called under a lock, on worker threads
};

struct StudyRunResult {
  std::vector<RunMetrics> runs;   ///< every run, in run order (rank 0 only; empty elsewhere)
  std::size_t resumed = 0;        ///< runs found in the journal, over all ranks (rank 0)
  std::size_t computed = 0;       ///< runs simulated in this session, over all ranks (rank 0)
  double wall_s = 0.0;            ///< of this session, rank 0
  std::size_t computed_here = 0;  ///< runs this process simulated
  double cpu_s = 0.0;             ///< CPU time (user + system) this process spent on them, s
};

/// The runs of rank `rank` of `size` (see the split above).
std::vector<std::size_t> rank_share(std::size_t run_count, int rank, int size);

/// Runs the pending runs of this rank and gathers. Throws what a run throws.
StudyRunResult run_study(const FragilityPlan& plan, const Cluster& cluster, const StudyRunOptions& options);

}  // namespace mrd::risk
