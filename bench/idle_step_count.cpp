// Runs N ticks of one numeric build of the idle-time estimator and the
// mixing scheduler on a synthetic stroke (30 s of ±5 mm at 0.5 Hz, then
// 90 s still, repeated: an open episode for 90 s of every 120 s, the settled
// phase for the rest), starting 11.3 days after a full mixing (the forecast
// is below the 0.8 threshold: the scheduler requests, times out, retries),
// each part through its own out-of-line function, so that callgrind counts
// the instructions of exactly that part:
//   estimator_step_once   BasicIdleEstimator::step
//   queries_step_once     predicted_capacity + volume_to_ceiling (the mixing task asks both every tick)
//   scheduler_step_once   BasicMixingScheduler::step
// bench/idle_callgrind.sh runs it for the three builds and prints Ir per tick.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "firmware/core/idle_estimator.hpp"
#include "firmware/core/mixing_scheduler.hpp"

namespace {

using namespace mrd;

template <class P>
[[gnu::noinline]] void estimator_step_once(fw::BasicIdleEstimator<P>& e, const fw::BasicIdleEstimatorInput<P>& in) {
  e.step(in);
}

template <class P>
[[gnu::noinline]] void queries_step_once(const fw::BasicIdleEstimator<P>& e, const fw::BasicMixingScheduler<P>& s,
                                         fw::BasicMixingSchedulerInput<P>& in) {
  in.forecast_capacity_fraction = e.predicted_capacity(s.forecast_horizon_ticks());
  in.volume_needed_m3 = e.volume_to_ceiling(s.ceiling_gap());
  in.measured_volume_m3 = e.lifetime_volume();
}

template <class P>
[[gnu::noinline]] fw::SchedulerState scheduler_step_once(fw::BasicMixingScheduler<P>& s,
                                                         const fw::BasicMixingSchedulerInput<P>& in) {
  return s.step(in).state;
}

void set_rtc(fw::RtcSeconds& in, std::uint64_t tick) { in.rtc_s = 1.7e9 + static_cast<double>(tick) * 1e-3; }
void set_rtc(fw::RtcMillis& in, std::uint64_t tick) { in.rtc_ms = 1700000000000 + static_cast<std::int64_t>(tick); }

template <class P>
int run(std::size_t n) {
  using Sample = typename fw::IdleArith<P>::Sample;
  std::vector<double> stroke_m(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * 1e-3;
    stroke_m[k] = std::fmod(t, 120.0) < 30.0 ? 0.005 * std::sin(2.0 * 3.141592653589793 * 0.5 * t) : 0.0;
  }
  static fw::BasicIdleEstimator<P> est;
  static fw::BasicMixingScheduler<P> sch;
  fw::IdleEstimatorConfig ec;
  fw::MixingSchedulerConfig sc;
  if (!est.init(ec) || !sch.init(sc)) return 1;
  typename fw::BasicIdleEstimator<P>::Rtc rtc{};
  if constexpr (std::is_same_v<decltype(rtc), double>) {
    rtc = 1.7e9;
  } else {
    rtc = 1700000000000;
  }
  est.boot_with(11.3 * 86400.0, 0, rtc);
  fw::BasicIdleEstimatorInput<P> ei;
  fw::BasicMixingSchedulerInput<P> si;
  unsigned due = 0;
  for (std::size_t k = 0; k < n; ++k) {
    ei.tick = k + 1;
    set_rtc(ei, k + 1);
    ei.damper_disp_m = static_cast<Sample>(stroke_m[k]);
    estimator_step_once(est, ei);
    si.tick = k + 1;
    queries_step_once(est, sch, si);
    due += scheduler_step_once(sch, si) != fw::SchedulerState::kIdle ? 1u : 0u;
  }
  std::printf("%s: %zu ticks, PR %.6f, capacity %.6f, %u episodes closed, %u ticks not idle\n", P::kName, n,
              static_cast<double>(est.estimate().participant_ratio), static_cast<double>(est.estimate().capacity_fraction),
              est.model().episodes_closed(), due);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const bool known = argc == 3 && (std::strcmp(argv[1], "double") == 0 || std::strcmp(argv[1], "float") == 0 ||
                                   std::strcmp(argv[1], "fixed") == 0);
  if (!known) {
    std::fprintf(stderr, "usage: %s double|float|fixed TICKS\n", argv[0]);
    return 2;
  }
  const long n = std::atol(argv[2]);
  if (n <= 0) {
    std::fprintf(stderr, "%s: TICKS must be a positive integer, got '%s'\n", argv[0], argv[2]);
    return 2;
  }
  const auto ticks = static_cast<std::size_t>(n);
  if (std::strcmp(argv[1], "fixed") == 0) return run<num::Fixed32Policy>(ticks);
  if (std::strcmp(argv[1], "float") == 0) return run<num::Float32Policy>(ticks);
  return run<fw::Float64Policy>(ticks);
}
