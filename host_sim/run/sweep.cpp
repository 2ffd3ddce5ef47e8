#include "host_sim/run/sweep.hpp"

#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>

#include "host_sim/run/controller.hpp"
#include "mrd/units.hpp"

namespace mrd::run {

std::vector<double> idle_grid(double from_years, double to_years, double step_years) {
  std::vector<double> grid;
  const auto n = static_cast<long>(std::floor((to_years - from_years) / step_years + 1e-9));
  for (long k = 0; k <= n; ++k) grid.push_back(from_years + static_cast<double>(k) * step_years);
  return grid;
}

std::vector<SweepRow> run_sweep(const SweepSpec& spec, const std::function<void(std::size_t, std::size_t)>& progress) {
  std::vector<SweepRow> rows;
  for (std::size_t m = 0; m < spec.motions.size(); ++m) {
    for (auto mode : spec.modes) {
      for (double y : spec.idle_years) rows.push_back({m, mode, y, {}});
    }
  }
  // Build one controller per mode up front so an unavailable mode fails
  // before any work starts.
  for (auto mode : spec.modes) (void)make_controller(mode, spec.base.step_s);

  const std::size_t total = rows.size();
  unsigned threads = spec.threads ? spec.threads : std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(total, 1)));
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  std::mutex mu;
  std::exception_ptr failure;

  const auto worker = [&] {
    for (;;) {
      const std::size_t i = next.fetch_add(1);
      if (i >= total) return;
      try {
        SweepRow& r = rows[i];
        plant::PlantSpec s = spec.base;
        s.idle_time_s = units::years_to_s(r.idle_years);
        auto controller = make_controller(r.mode, s.step_s);
        r.summary = run_closed_loop(s, spec.motions[r.motion_index].accel_m_s2, *controller);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mu);
        if (!failure) failure = std::current_exception();
        next.store(total);
        return;
      }
      std::lock_guard<std::mutex> lock(mu);
      ++done;
      if (progress) progress(done, total);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return rows;
}

}  // namespace mrd::run
