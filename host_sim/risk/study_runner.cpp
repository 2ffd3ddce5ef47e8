#include "host_sim/risk/study_runner.hpp"

#include <sys/resource.h>

#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "host_sim/risk/run_journal.hpp"

namespace mrd::risk {
namespace {

/// User + system CPU time of this process, s.
double process_cpu_s() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

std::vector<std::size_t> rank_share(std::size_t run_count, int rank, int size) {
  std::vector<std::size_t> runs;
  const std::size_t chunks = (run_count + kChunkRuns - 1) / kChunkRuns;
  for (std::size_t c = static_cast<std::size_t>(rank); c < chunks; c += static_cast<std::size_t>(size)) {
    for (std::size_t r = c * kChunkRuns; r < std::min(run_count, (c + 1) * kChunkRuns); ++r) runs.push_back(r);
  }
  return runs;
}

StudyRunResult run_study(const FragilityPlan& plan, const Cluster& cluster, const StudyRunOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0_s = process_cpu_s();
  const std::size_t count = plan.run_count();
  const std::uint64_t fingerprint = plan.fingerprint();
  const auto attempt =
      static_cast<unsigned>(cluster.broadcast(cluster.rank() == 0 ? journal_file_count(options.journal_dir) : 0));
  const auto kept = load_journal(options.journal_dir, fingerprint, count);
  // Every rank has read the journals before any rank appends to a new one.
  (void)cluster.any(false);

  const std::vector<std::size_t> share = rank_share(count, cluster.rank(), cluster.size());
  std::vector<RunMetrics> metrics(share.size());
  std::vector<std::size_t> pending;  // positions in `share`
  for (std::size_t i = 0; i < share.size(); ++i) {
    if (kept[share[i]]) {
      metrics[i] = *kept[share[i]];
    } else {
      pending.push_back(i);
    }
  }

  if (!pending.empty()) {
    JournalWriter journal(options.journal_dir, fingerprint, attempt, cluster.rank());
    const std::size_t chunks = (pending.size() + kChunkRuns - 1) / kChunkRuns;
    const unsigned threads = static_cast<unsigned>(std::min<std::size_t>(std::max(1u, options.threads), chunks));
    std::atomic<std::size_t> next{0};
    std::mutex mu;
    std::size_t done = 0;
    std::exception_ptr failure;
    const auto worker = [&] {
      std::vector<std::size_t> runs;
      std::vector<RunMetrics> out;
      for (;;) {
        const std::size_t c = next.fetch_add(1);
        if (c >= chunks) return;
        runs.clear();
        for (std::size_t p = c * kChunkRuns; p < std::min(pending.size(), (c + 1) * kChunkRuns); ++p) {
          runs.push_back(share[pending[p]]);
        }
        out.assign(runs.size(), {});
        try {
          simulate_runs(plan, runs, out);
          std::lock_guard<std::mutex> lock(mu);
          for (std::size_t k = 0; k < runs.size(); ++k) {
            journal.append(runs[k], out[k]);
            metrics[pending[c * kChunkRuns + k]] = out[k];
          }
          done += runs.size();
          if (options.progress) {
            options.progress(
                {done, pending.size(), std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()});
          }
        } catch (...) {
          std::lock_guard<std::mutex> lock(mu);
          if (!failure) failure = std::current_exception();
          next.store(chunks);
          return;
        }
      }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
  }

  StudyRunResult result;
  result.computed_here = pending.size();
  result.cpu_s = process_cpu_s() - cpu0_s;
  result.runs = cluster.gather(count, share, metrics);
  // Every run missing from the journal at the start is computed in this session.
  std::size_t resumed = 0;
  for (const auto& k : kept) resumed += k.has_value();
  result.resumed = resumed;
  result.computed = count - resumed;
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace mrd::risk
