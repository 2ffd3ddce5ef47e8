#pragma once
/// Independent fits run side by side: the discrepancy workflow's candidate
/// fits and the calibration's laws and left-out folds. Each job writes only
/// its own slot, so the results do not depend on the number of threads.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace mrd::discrepancy {

/// Runs `job(i)` for i in [0, count) on up to `threads` threads (0: all
/// cores). An exception a job throws stops the jobs not yet started and is
/// rethrown here, after every thread has joined (the first one thrown).
template <typename Job>
void parallel_for(std::size_t count, unsigned threads, Job job) {
  const unsigned hw = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  const std::size_t workers = std::min<std::size_t>(hw, count);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) job(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::mutex failed_mutex;
  std::exception_ptr failed;
  std::vector<std::thread> pool;
  pool.reserve(workers);
  for (std::size_t w = 0; w < workers; ++w) {
    pool.emplace_back([&] {
      for (std::size_t i = next++; i < count; i = next++) {
        try {
          job(i);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(failed_mutex);
          if (!failed) failed = std::current_exception();
          next = count;
        }
      }
    });
  }
  for (auto& t : pool) t.join();
  if (failed) std::rethrow_exception(failed);
}

}  // namespace mrd::discrepancy
