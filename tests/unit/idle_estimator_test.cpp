// Idle-time estimator: the thesis model reproduced for one episode
// (against physics::MrDamper), consistency over repeated episodes, the dead
// band, the clock rules, the save cadence and the capacity definition.
#include "firmware/core/idle_estimator.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>
#include <type_traits>
#include <vector>

#include "firmware/platform/sim/memory_state_store.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/units.hpp"

// Counts heap allocations so that a test can prove step() makes none. It
// replaces the global operator new of this test program only. Not inlined,
// so that the compiler sees new paired with delete, not with free().
namespace {
std::atomic<long> g_allocations{0};
}  // namespace
[[gnu::noinline]] void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace mrd::fw {
namespace {

constexpr double kDt = 1.0e-3;     // control period, s
constexpr double kRtc0 = 1.7e9;    // wall clock at the test's boot, s
constexpr double kYear = units::kSecondsPerYear;

double t_max_s() { return physics::max_settling_time_s(physics::SettlingParams{}); }
/// T_max as the estimator counts it: Eq. 5.4 rounded up to whole 1 ms ticks.
double t_max_tick_s() { return std::ceil(t_max_s() / kDt) * kDt; }

/// Steps an estimator with a running tick and an RTC that follows it.
class Rig {
 public:
  /// Counts every |Δx| (no dead band) unless `c` says otherwise.
  explicit Rig(IdleEstimatorConfig c = exact()) {
    c.period_s = kDt;
    EXPECT_TRUE(est.init(c));
  }
  static IdleEstimatorConfig exact() {
    IdleEstimatorConfig c;
    c.dead_band_m = 0.0;
    return c;
  }
  void boot_with(double idle_s) { est.boot_with(idle_s, 0, kRtc0); }
  void sample(double disp_m, bool mixing = false) {
    last_disp_m = disp_m;
    IdleEstimatorInput in;
    in.tick = tick;
    in.rtc_s = kRtc0 + static_cast<double>(tick) * kDt;
    in.damper_disp_m = disp_m;
    in.mixing_active = mixing;
    est.step(in);
  }
  /// Advances the clock by `dt_s` and takes one sample at the same
  /// displacement as the last one.
  void idle_for(double dt_s) {
    tick += static_cast<std::uint64_t>(std::llround(dt_s / kDt));
    sample(last_disp_m);
  }
  void next(double disp_m, bool mixing = false) {
    ++tick;
    sample(disp_m, mixing);
  }
  double t() const { return static_cast<double>(tick) * kDt; }
  IdleEstimator est;
  std::uint64_t tick = 0;
  double last_disp_m = 0.0;
};

// ------------------------------------------------ one episode = thesis model

struct EpisodeCase {
  const char* name;
  double idle_years;
  int history;  // 0: Table 5.1 case-1 sine, 1: random velocity
};

void set_rtc(RtcSeconds& in, double rtc_s) { in.rtc_s = rtc_s; }
void set_rtc(RtcMillis& in, double rtc_s) { in.rtc_ms = std::llround(rtc_s * 1e3); }

/// Largest |PR − MrDamper's PR| and |capacity − its capacity| over one
/// idle-then-excite episode of 30 s at 1 kHz, and the volume difference at
/// the end, for one numeric build of the estimator.
struct EpisodeErrors {
  double pr = 0.0;
  double first_pr = 0.0;
  double capacity = 0.0;
  double volume_m3 = 0.0;
  bool open = false;
};

template <class P>
EpisodeErrors run_episode(const EpisodeCase& c) {
  using Sample = typename IdleArith<P>::Sample;
  const double idle_s = c.idle_years * kYear;
  BasicIdleEstimator<P> est;
  IdleEstimatorConfig config;
  config.dead_band_m = 0.0;
  config.period_s = kDt;
  EXPECT_TRUE(est.init(config));
  typename BasicIdleEstimator<P>::Rtc rtc0{};
  if constexpr (std::is_same_v<typename IdleArith<P>::Rtc, double>) {
    rtc0 = kRtc0;
  } else {
    rtc0 = std::llround(kRtc0 * 1e3);
  }
  est.boot_with(idle_s, 0, rtc0);

  physics::MrDamperParams dp;
  physics::MrDamper damper(dp, kDt, physics::settling_quotient(idle_s, t_max_s()));
  damper.reset(physics::settling_quotient(idle_s, t_max_s()), 2.5);
  const physics::BinghamParams b;
  const double f1 = physics::damper_force_n(b, 2.5, 0.1, 1.0);

  std::mt19937 rng(11);
  std::normal_distribution<double> kick(0.0, 0.02);
  double x_m = 0.0, v_m_s = 0.0;
  typename BasicIdleEstimator<P>::Input in;
  const auto sample = [&](std::uint64_t tick) {
    in.tick = tick;
    set_rtc(in, kRtc0 + static_cast<double>(tick) * kDt);
    in.damper_disp_m = static_cast<Sample>(x_m);
    est.step(in);
  };
  sample(0);
  EpisodeErrors e;
  e.first_pr = std::fabs(static_cast<double>(est.estimate().participant_ratio) - damper.participant_ratio());
  for (int n = 0; n < 30000; ++n) {
    const double t = n * kDt;
    if (c.history == 0) {
      v_m_s = 0.0254 * 2.0 * units::kPi * 0.5 * std::cos(2.0 * units::kPi * 0.5 * t);  // 25.4 mm, 0.5 Hz
    } else {
      v_m_s = 0.98 * v_m_s + kick(rng);
    }
    damper.step(2.5, v_m_s);
    x_m += v_m_s * kDt;
    sample(static_cast<std::uint64_t>(n + 1));
    const double pr = damper.participant_ratio();
    e.pr = std::max(e.pr, std::fabs(static_cast<double>(est.estimate().participant_ratio) - pr));
    // Capacity: damper force at 2.5 A and 0.1 m/s with this PR over PR = 1.
    e.capacity = std::max(e.capacity, std::fabs(static_cast<double>(est.estimate().capacity_fraction) -
                                                physics::damper_force_n(b, 2.5, 0.1, pr) / f1));
  }
  e.open = est.estimate().episode_open;
  e.volume_m3 = std::fabs(static_cast<double>(est.estimate().episode_volume_m3) - damper.displaced_volume_m3());
  return e;
}

class SingleEpisode : public ::testing::TestWithParam<EpisodeCase> {};

// One idle-then-excite episode: the estimator, fed the damper displacement,
// gives the participant ratio physics::MrDamper computes from the velocity
// (Eq. 5.5–5.9), sample for sample. MrDamper integrates |v|·A·T with v held
// over the step; the displacement it implies moves by v·T per step, so the
// two agree up to the numbers of each build. Tolerances, from the formats
// (PR = b + (a − b)e^−x; |∂PR/∂SQ| ≤ 7·0.9 + 4.5·0.395 + 0.9·x·e^−x·3.65 ≤ 9.3;
// |∂PR/∂x|·|x| ≤ 0.9/e = 0.33 per relative error of x):
//  - double: T_max is a whole number of 1 ms ticks (rounded by ≤ 0.5 ms of
//    2.69e7 s: SQ off by ≤ 1.9e−11 relative) → PR ≤ 9.3·1.9e−11 = 1.8e−10;
//    the rest is double rounding (< 1e−13). Bound 5e−10.
//  - float: the displacement crosses as float (x ≤ 0.6 m: ≤ 3e−8 m a
//    sample, so the displaced volume is off by ≤ 6e−8 m·A per direction
//    change and, being a sum of |Δx|, by ≤ 2^−24 relative per step); SQ, the
//    three exponentials and Eq. 5.9 each carry ≤ 4 float roundings
//    (2^−24 = 6e−8 relative): SQ error 2.4e−7 → PR 2.2e−6 worst case; x
//    relative error 6 roundings = 3.6e−7 → 0.33·3.6e−7 = 1.2e−7; affine
//    sums ≤ 2 roundings of 1 = 1.2e−7. Bound 3e−6.
//  - fixed: SQ in Q1.30 (≤ 2^−31 + the tick rounding above); c·SQ to Q5.26
//    (½ LSB 7.5e−9, plus c in Q3.28: 1.9e−9) → a_PR, b_PR by ≤ 0.9·(7.5e−9 +
//    1.9e−9 + exp's 3.8e−9) + 3 roundings of Q1.30 (1.4e−9) = 1.3e−8; c_PR
//    by 5.474·1.32e−8 = 7.2e−8 (0.5 relative·e−6 at c = 0.142), rate c/unit
//    in Q13.18 (½ LSB 1.9e−6 per 142 /m³ = 1.3e−8): x relative ≤ 5.2e−7
//    → 0.33·5.2e−7 = 1.7e−7; the float crossing of x as for float (the
//    Disp grid is 3.7e−9 m, finer than float's 3e−8 m at 0.3 m) adds
//    ≤ 0.33·(2^−24) per step of relative volume; exp(−x) ≤ 3.8e−9.
//    Bound 1e−6 (float input dominates).
// The capacity is affine in PR with slope 0.93 (Table 4.1 at 2.5 A and
// 0.1 m/s), plus one rounding: same bounds.
template <class P>
void expect_episode(const EpisodeCase& c, double tol_pr, double tol_volume_m3) {
  const EpisodeErrors e = run_episode<P>(c);
  EXPECT_LT(e.first_pr, tol_pr) << P::kName;
  EXPECT_LT(e.pr, tol_pr) << P::kName;
  EXPECT_LT(e.capacity, tol_pr) << P::kName;
  EXPECT_LT(e.volume_m3, tol_volume_m3) << P::kName;
  EXPECT_TRUE(e.open) << P::kName;
}

TEST_P(SingleEpisode, ReproducesMrDamperInDouble) { expect_episode<Float64Policy>(GetParam(), 5e-10, 1e-12); }
// Volume: float's 2^−24 of up to 0.05 m³ an episode = 3e−9 m³.
TEST_P(SingleEpisode, ReproducesMrDamperInFloat) { expect_episode<num::Float32Policy>(GetParam(), 3e-6, 1e-8); }
TEST_P(SingleEpisode, ReproducesMrDamperInFixedPoint) {
  expect_episode<num::Fixed32Policy>(GetParam(), 1e-6, 1e-8);
}

INSTANTIATE_TEST_SUITE_P(IdleTimes, SingleEpisode,
                         ::testing::Values(EpisodeCase{"FullyMixedSine", 0.0, 0},
                                           EpisodeCase{"QuarterYearSine", 0.25, 0},
                                           EpisodeCase{"HalfYearRandom", 0.5, 1},
                                           EpisodeCase{"TwoAndAHalfYearsSine", 2.5, 0},
                                           EpisodeCase{"TwoAndAHalfYearsRandom", 2.5, 1}),
                         [](const auto& p) { return std::string(p.param.name); });

// ------------------------------------------------ repeated episodes

// Idle periods add: 0.3 y then 0.3 y without motion is 0.6 y, whether the
// board kept running or was off in between (the time off is the RTC gap).
TEST(IdleEstimator, IdlePeriodsAdd) {
  Rig running;
  running.boot_with(0.3 * kYear);
  running.sample(0.0);
  running.idle_for(0.3 * kYear);
  EXPECT_NEAR(running.est.estimate().equivalent_idle_s, 0.6 * kYear, 1e-3);

  Rig before;
  before.boot_with(0.0);
  before.sample(0.0);
  before.idle_for(0.3 * kYear);
  sim::MemoryStateStore store;
  ASSERT_EQ(before.est.save(store), SaveOutcome::kSaved);
  IdleEstimator after;
  ASSERT_TRUE(after.init({}));
  const auto rep = after.boot(store, 0, kRtc0 + 0.6 * kYear, true);  // off for another 0.3 y
  EXPECT_EQ(rep.flags, 0u);
  EXPECT_NEAR(rep.offline_s, 0.3 * kYear, 1e-3);
  EXPECT_NEAR(after.estimate().equivalent_idle_s, 0.6 * kYear, 1e-3);

  // Both equal a single 0.6-year idle period (Eq. 5.5–5.6).
  const double sq = 0.6 * kYear / t_max_s();
  const double a_pr = 0.10 + 0.90 * std::exp(-7.0 * sq);
  EXPECT_NEAR(running.est.estimate().participant_ratio, a_pr, 1e-9);
  EXPECT_NEAR(after.estimate().participant_ratio, a_pr, 1e-9);
}

// Past T_max (Eq. 5.4, 0.853 years) the fluid is fully settled and stays so.
TEST(IdleEstimator, IdleTimeSaturatesAtMaxSettlingTime) {
  Rig rig;
  rig.boot_with(0.0);
  rig.sample(0.0);
  rig.idle_for(5.0 * kYear);
  EXPECT_DOUBLE_EQ(rig.est.estimate().equivalent_idle_s, t_max_tick_s());
  EXPECT_DOUBLE_EQ(rig.est.estimate().sq, 1.0);
}

/// Moves the damper at 0.1 m/s peak (±20 mm at 0.8 Hz) for `seconds`.
void shake(Rig& rig, double seconds) {
  const int n = static_cast<int>(seconds / kDt);
  const double t0 = rig.t();
  for (int k = 1; k <= n; ++k) rig.next(0.02 * std::sin(2.0 * units::kPi * 0.8 * (rig.t() + kDt - t0)));
}

// Long motion after full settling reaches the ceiling b_PR(1) (Table 5.6 by
// hand: 0.605 + 0.395·e^−4.5 = 0.609388); when the damper stops, the episode
// closes after quiet_close_s (60 s) and τ becomes a_PR⁻¹(b_PR) plus the
// episode's length: SQ = −ln((0.609388 − 0.1)/0.9)/7 = 0.0813121.
TEST(IdleEstimator, LongMotionReachesTheCeilingThenSettlesFromIt) {
  Rig rig;
  rig.boot_with(t_max_s());
  rig.sample(0.0);
  const double t_open = rig.t();
  shake(rig, 200.0);  // ∫Q ≈ 200 s · 0.064 m/s · 0.01062 m² ≈ 136 L: c_PR·∫Q ≈ 19
  EXPECT_NEAR(rig.est.estimate().participant_ratio, 0.609388, 1e-6);
  const double t_stop = rig.t();
  rig.idle_for(59.0);
  EXPECT_TRUE(rig.est.estimate().episode_open);
  rig.idle_for(2.0);
  EXPECT_FALSE(rig.est.estimate().episode_open);
  const double expected_tau = 0.0813121 * t_max_s() + (t_stop + 60.0 - t_open);
  EXPECT_NEAR(rig.est.estimate().equivalent_idle_s, expected_tau, 1e-6 * t_max_s());
}

// Each new episode starts from a smaller τ, so its ceiling is higher: near
// full mixing τ' ≈ (b_final'/a_initial')·τ + length = (1.778/6.3)·τ + length
// (slopes of Eq. 5.7 and 5.6 at SQ = 0: 0.395·4.5 and 0.9·7). With 200 s of
// motion plus 60 s of quiet per episode the fixed point is ≈ 260/0.72 ≈ 360 s.
TEST(IdleEstimator, RepeatedMotionReturnsToFullyMixed) {
  Rig rig;
  rig.boot_with(t_max_s());
  rig.sample(0.0);
  double last_tau = rig.est.estimate().equivalent_idle_s;
  for (int episode = 0; episode < 10; ++episode) {
    shake(rig, 200.0);
    rig.idle_for(61.0);
    ASSERT_FALSE(rig.est.estimate().episode_open);
    const double tau = rig.est.estimate().equivalent_idle_s;
    EXPECT_LT(tau, last_tau) << episode;
    last_tau = tau;
  }
  EXPECT_LT(last_tau, 500.0);
  EXPECT_GT(rig.est.estimate().participant_ratio, 0.999);
  EXPECT_EQ(rig.est.model().episodes_closed(), 10u);
}

// Motion that never stops still closes an episode every max_episode_s (1 h)
// and then counts that hour as idle time: ambient motion cannot hide
// settling for longer than an hour.
TEST(IdleEstimator, ContinuousMotionClosesEpisodesHourly) {
  Rig rig;
  rig.boot_with(0.0);
  rig.sample(0.0);
  for (int k = 1; k <= 9000; ++k) {  // 2.5 h of ±1 mm at 0.5 Hz, sampled at 1 s
    rig.tick += 1000;
    rig.sample(0.001 * std::sin(2.0 * units::kPi * 0.5 * (k + 0.25)));
  }
  EXPECT_EQ(rig.est.model().episodes_closed(), 2u);
  EXPECT_TRUE(rig.est.estimate().episode_open);
  // τ as if closed now includes at least the open episode's half hour.
  EXPECT_GE(rig.est.estimate().equivalent_idle_s, 1800.0);
}

// The play operator: noise smaller than the dead band earns nothing; a sine
// of amplitude A over N whole cycles from x = 0 counts (A − d) up to the
// first peak, 2(A − d) per following half swing (2N − 1 of them) and
// (A − 2d) back to 0: 4NA − (4N + 1)d. With d = 0 it is 4NA.
TEST(IdleEstimator, DeadBandIgnoresNoiseAndUndercountsMotion) {
  const double a_m = 0.01, d_m = 0.0005, area = 0.01062;
  IdleEstimatorConfig c = Rig::exact();
  c.dead_band_m = d_m;
  Rig noisy(c);
  noisy.boot_with(0.0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(-0.4 * d_m, 0.4 * d_m);
  noisy.sample(0.0);
  for (int k = 0; k < 20000; ++k) noisy.next(noise(rng));
  EXPECT_EQ(noisy.est.estimate().lifetime_volume_m3, 0.0);
  EXPECT_FALSE(noisy.est.estimate().episode_open);

  for (double band : {0.0, d_m}) {
    c.dead_band_m = band;
    Rig rig(c);
    rig.boot_with(0.0);
    rig.sample(0.0);
    for (int k = 1; k <= 10000; ++k) rig.next(a_m * std::sin(2.0 * units::kPi * 1.0 * k * kDt));  // 10 cycles at 1 Hz
    const double expected = (40.0 * a_m - 41.0 * band) * area;
    EXPECT_NEAR(rig.est.estimate().lifetime_volume_m3, expected, 1e-9 * area) << band;
  }
}

TEST(IdleEstimator, InvalidDisplacementEarnsNoCredit) {
  Rig rig;
  rig.boot_with(0.0);
  rig.sample(0.0);
  for (int k = 1; k <= 1000; ++k) {
    ++rig.tick;
    IdleEstimatorInput in;
    in.tick = rig.tick;
    in.rtc_s = kRtc0 + rig.t();
    in.damper_disp_m = 0.05 * std::sin(k * 0.1);
    in.disp_valid = false;
    rig.est.step(in);
  }
  EXPECT_EQ(rig.est.estimate().lifetime_volume_m3, 0.0);
}

TEST(IdleEstimator, MixingCreditsGoToTheMixingCounter) {
  Rig rig;
  rig.boot_with(0.0);
  rig.sample(0.0);
  rig.next(0.001, true);   // 1 mm while mixing
  rig.next(0.003, false);  // 2 mm of other motion
  EXPECT_NEAR(rig.est.estimate().mixing_volume_m3, 0.001 * 0.01062, 1e-15);
  EXPECT_NEAR(rig.est.estimate().lifetime_volume_m3, 0.003 * 0.01062, 1e-15);
}

// ------------------------------------------------ clock

TEST(IdleEstimator, ClockBackwardsWhileRunningMeansFullySettled) {
  Rig rig;
  rig.boot_with(86400.0);
  rig.sample(0.0);
  rig.idle_for(10.0);
  EXPECT_EQ(rig.est.estimate().flags, 0u);
  IdleEstimatorInput in;
  in.tick = ++rig.tick;
  in.rtc_s = kRtc0 + rig.t() - 3600.0;  // NTP set the clock back an hour
  rig.est.step(in);
  EXPECT_EQ(rig.est.estimate().equivalent_idle_s, t_max_tick_s());
  EXPECT_TRUE(rig.est.estimate().flags & kIdleClockBackwards);
  EXPECT_TRUE(rig.est.estimate().flags & kIdleAssumedSettled);
  EXPECT_TRUE(rig.est.save_due());
}

// In-boot time comes from the ticks: a forward RTC jump changes nothing.
TEST(IdleEstimator, ClockForwardJumpDoesNotAddIdleTime) {
  Rig rig;
  rig.boot_with(86400.0);
  rig.sample(0.0);
  IdleEstimatorInput in;
  in.tick = rig.tick += 1000;
  in.rtc_s = kRtc0 + 30.0 * 86400.0;
  rig.est.step(in);
  EXPECT_NEAR(rig.est.estimate().equivalent_idle_s, 86401.0, 1e-6);
  EXPECT_EQ(rig.est.estimate().flags, 0u);
}

TEST(IdleEstimator, StepWithoutBootAssumesTheWorst) {
  IdleEstimator est;
  ASSERT_TRUE(est.init({}));
  est.step(IdleEstimatorInput{});
  EXPECT_EQ(est.estimate().equivalent_idle_s, t_max_tick_s());
  EXPECT_TRUE(est.estimate().flags & kIdleNoSavedState);
}

// ------------------------------------------------ persistence cadence

TEST(IdleEstimator, SavesAtTheIntervalAndOnStateChanges) {
  IdleEstimatorConfig c = Rig::exact();
  c.save_interval_s = 600.0;
  Rig rig(c);
  rig.boot_with(0.0);
  rig.sample(0.0);
  EXPECT_FALSE(rig.est.save_due());
  rig.idle_for(599.0);
  EXPECT_FALSE(rig.est.save_due());
  rig.idle_for(1.0);
  EXPECT_TRUE(rig.est.save_due());
  sim::MemoryStateStore store;
  ASSERT_EQ(rig.est.save(store), SaveOutcome::kSaved);
  EXPECT_FALSE(rig.est.save_due());

  // An episode closing is a state change worth saving at once.
  shake(rig, 5.0);
  EXPECT_FALSE(rig.est.save_due());
  rig.idle_for(61.0);
  EXPECT_TRUE(rig.est.save_due());
  ASSERT_EQ(rig.est.save(store), SaveOutcome::kSaved);

  // A failed save is flagged and stays due.
  rig.est.note_mixing_confirmed();
  EXPECT_TRUE(rig.est.save_due());
  store.fail_next_save();
  EXPECT_EQ(rig.est.save(store), SaveOutcome::kFailed);
  EXPECT_TRUE(rig.est.estimate().flags & kIdleSaveFailed);
  EXPECT_TRUE(rig.est.save_due());
  EXPECT_EQ(rig.est.save(store), SaveOutcome::kSaved);
  EXPECT_FALSE(rig.est.estimate().flags & kIdleSaveFailed);
  EXPECT_EQ(store.saves(), 3u);
}

// The saved record restores τ and the counters; the stamp is the last RTC
// reading advanced by the ticks since. The record holds milliseconds and
// volume counts of 2^−40 m³: the volume comes back within half a count.
TEST(IdleEstimator, SaveAndBootRoundTrip) {
  Rig rig;
  rig.boot_with(1000.0);
  rig.sample(0.0);
  shake(rig, 10.0);
  rig.idle_for(100.0);
  rig.est.note_mixing_confirmed();
  sim::MemoryStateStore store;
  ASSERT_EQ(rig.est.save(store), SaveOutcome::kSaved);
  PersistedIdleState s;
  ASSERT_EQ(decode_state(store.bytes(), s), DecodeStatus::kOk);
  EXPECT_EQ(s.rtc_ms, std::llround((kRtc0 + rig.t()) * 1e3));
  EXPECT_EQ(s.mixing_cycles, 1u);

  IdleEstimator again;
  ASSERT_TRUE(again.init({}));
  again.boot(store, 0, static_cast<double>(s.rtc_ms) * 1e-3, true);
  EXPECT_NEAR(again.estimate().equivalent_idle_s, rig.est.estimate().equivalent_idle_s, 1e-6);
  EXPECT_NEAR(again.estimate().lifetime_volume_m3, rig.est.estimate().lifetime_volume_m3, 0.5 * kVolumeCountM3);
  EXPECT_EQ(again.estimate().mixing_cycles, 1u);
}

TEST(IdleEstimator, NoClockNoSave) {
  IdleEstimator est;
  ASSERT_TRUE(est.init({}));
  sim::MemoryStateStore store;
  est.boot(store, 0, 0.0, false);
  EXPECT_EQ(est.save(store), SaveOutcome::kSkippedNoClock);
  EXPECT_FALSE(store.has_record());
}

// ------------------------------------------------ capacity and forecasts

// Table 4.1 by hand at 2.5 A and 0.1 m/s (transition factor 1):
//   f_c(PR) = PR·170 kN·(1 − e^−1.75) + 4.1 kN·e^−1.75     (Eq. 5.10)
//   c_0(PR) = PR·365 kN·s/m·(1 − e^−2.875) + 82.5 kN·s/m·e^−2.875   (Eq. 5.11)
TEST(SettlingModel, CapacityFromTable41) {
  SettlingModel m;
  ASSERT_TRUE(m.init({}));
  const double e1 = std::exp(-0.7 * 2.5), e2 = std::exp(-1.15 * 2.5);
  const auto force = [&](double pr) {
    return pr * 170e3 * (1 - e1) + 4.1e3 * e1 + 0.1 * (pr * 365e3 * (1 - e2) + 82.5e3 * e2);
  };
  for (double pr : {0.1, 0.5, 0.8, 1.0}) {
    EXPECT_NEAR(m.capacity_of_pr(pr), force(pr) / force(1.0), 1e-12) << pr;
    EXPECT_NEAR(m.pr_of_capacity(m.capacity_of_pr(pr)), pr, 1e-12) << pr;
  }
}

TEST(SettlingModel, InverseOfEq56) {
  SettlingModel m;
  ASSERT_TRUE(m.init({}));
  for (double sq : {0.0, 0.01, 0.3, 0.9}) {
    const double a = 0.10 + 0.90 * std::exp(-7.0 * sq);
    EXPECT_NEAR(m.idle_of_pr(a), sq * m.max_settling_time_s(), 1e-6) << sq;
  }
  EXPECT_EQ(m.idle_of_pr(0.05), m.max_settling_time_s());  // below a_PR(1): fully settled
  EXPECT_EQ(m.idle_of_pr(1.0), 0.0);
}

// The forecast after h without motion is what the estimator shows after h.
TEST(IdleEstimator, ForecastMatchesWhatHappens) {
  Rig rig;
  rig.boot_with(2.0 * 86400.0);
  rig.sample(0.0);
  const double forecast = rig.est.predicted_capacity_fraction(5.0 * 86400.0);
  rig.idle_for(5.0 * 86400.0);
  EXPECT_NEAR(rig.est.estimate().capacity_fraction, forecast, 1e-12);
}

// Eq. 5.9 solved for ∫Q dt: (a − b)e^(−cV) = g·b. Displacing that volume
// leaves PR = b − g·b.
TEST(IdleEstimator, VolumeToCeilingBringsPrWithinTheGap) {
  Rig rig;
  rig.boot_with(0.25 * kYear);
  rig.sample(0.0);
  const double g = 0.01;
  const double v_m3 = rig.est.volume_to_ceiling_m3(g);
  const double sq = 0.25 * kYear / t_max_s();
  const double a = 0.10 + 0.90 * std::exp(-7.0 * sq), b = 0.605 + 0.395 * std::exp(-4.5 * sq);
  const double c = 5.474 * std::exp(-3.65 * sq);
  EXPECT_NEAR(v_m3, 1e-3 * std::log((b - a) / (g * b)) / c, 1e-12);
  rig.next(v_m3 / 0.01062);  // one sample moving exactly that volume
  // SQ of the tick-rounded T_max (see SingleEpisode): within 1e−10.
  EXPECT_NEAR(rig.est.estimate().participant_ratio, b - g * b, 1e-10);
  EXPECT_NEAR(rig.est.volume_to_ceiling_m3(g), 0.0, 1e-15);
}

TEST(IdleEstimator, RefusesBadConfiguration) {
  IdleEstimator est;
  IdleEstimatorConfig c;
  c.period_s = 0.0;
  EXPECT_FALSE(est.init(c));
  c = {};
  c.dead_band_m = -1.0;
  EXPECT_FALSE(est.init(c));
  c = {};
  c.model.pr.flow_area_m2 = 0.0;
  EXPECT_FALSE(est.init(c));
}

// ------------------------------------------------ the volume counter

// Small ambient motion is not lost against a large running total: with
// 100 m³ already credited (far more than a decade of ambient motion, 0.02 m³,
// plus 50 years of earthquakes and mixing), 1000 strokes of 1 µm each add
// 1000·1e−6 m·0.01062 m² = 1.062e−5 m³ to the counter. The 64-bit counter
// in 2^−40 m³ (9.1e−13 m³) keeps each 1.06e−11 m³ step within ½ count;
// the float sample of x (≤ 4e−9 m at 0.03 m) bounds each step's volume by
// ±4e−11 m³, unbiased over a back-and-forth stroke: 1000 steps ≤ 4e−8 m³
// in the worst case, 1e−8 is the bound used (errors alternate in sign).
template <class P>
void small_motion_counts_on_a_large_total() {
  using Sample = typename IdleArith<P>::Sample;
  BasicIdleEstimator<P> est;
  IdleEstimatorConfig c;
  c.dead_band_m = 0.0;
  ASSERT_TRUE(est.init(c));
  PersistedIdleState s;
  s.rtc_ms = 1700000000000;
  s.lifetime_volume = std::llround(100.0 / kVolumeCountM3);
  sim::MemoryStateStore store;
  ASSERT_EQ(store.save(encode_state(s)), hal::StoreStatus::kOk);
  est.boot(store, 0, 1700000000000, true);
  const double before = IdleArith<P>::vol_to_double(est.lifetime_volume());
  EXPECT_NEAR(before, 100.0, 1e-9);
  typename BasicIdleEstimator<P>::Input in;
  in.rtc_ms = 1700000000000;
  for (int k = 0; k <= 1000; ++k) {
    in.tick = static_cast<std::uint64_t>(k);
    const int up_down = k % 200 < 100 ? k % 200 : 200 - k % 200;  // 0 … 100 … 0: steps of 1 µm
    in.damper_disp_m = static_cast<Sample>(0.03 + 1e-6 * up_down);
    est.step(in);
  }
  const double added = IdleArith<P>::vol_to_double(est.lifetime_volume()) - before;
  EXPECT_NEAR(added, 1000.0 * 1e-6 * 0.01062, 1e-8) << P::kName;
  EXPECT_GT(added, 0.0);
}

TEST(IdleEstimator, FloatBuildCountsMicrometreStrokesOnAHundredCubicMetres) {
  small_motion_counts_on_a_large_total<num::Float32Policy>();
}
TEST(IdleEstimator, FixedPointBuildCountsMicrometreStrokesOnAHundredCubicMetres) {
  small_motion_counts_on_a_large_total<num::Fixed32Policy>();
}

// ------------------------------------------------ no heap in step()

TEST(IdleEstimator, StepDoesNotAllocate) {
  Rig rig;
  rig.boot_with(0.0);
  rig.sample(0.0);
  const long before = g_allocations.load();
  for (int k = 0; k < 100000; ++k) rig.next(0.01 * std::sin(0.003 * k));
  rig.idle_for(120.0);
  EXPECT_EQ(g_allocations.load(), before);
  EXPECT_GT(rig.est.model().episodes_closed(), 0u);
}

}  // namespace
}  // namespace mrd::fw
