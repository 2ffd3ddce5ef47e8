// The firmware loop's deadlines and overrun counting, on a manual clock.
#include <gtest/gtest.h>

#include "firmware/app/periodic_schedule.hpp"
#include "firmware/platform/sim/manual_clock.hpp"

namespace mrd::app {
namespace {

constexpr std::int64_t kPeriod = 1'000'000;  // 1 ms

TEST(PeriodicSchedule, DeadlinesStayOnTheGridWhenTicksFit) {
  sim::ManualClock clock;
  clock.advance_ns(5'000);  // start at an arbitrary time
  PeriodicSchedule s(kPeriod, clock.now_ns());
  for (int k = 1; k <= 1000; ++k) {
    clock.advance_ns(300'000);  // the tick takes 0.3 ms
    const std::int64_t d = s.after_tick(clock.now_ns());
    EXPECT_EQ(d, 5'000 + k * kPeriod);
    clock.sleep_until_ns(d);
  }
  EXPECT_EQ(s.overruns(), 0u);
  EXPECT_EQ(clock.now_ns(), 5'000 + 1000 * kPeriod) << "no drift after 1000 ticks";
}

TEST(PeriodicSchedule, ALongTickCountsEveryMissedPeriodAndDoesNotBurst) {
  sim::ManualClock clock;
  PeriodicSchedule s(kPeriod, 0);
  clock.advance_ns(500'000);
  clock.sleep_until_ns(s.after_tick(clock.now_ns()));  // tick 0 ends at 0.5 ms; sleeps to 1 ms
  clock.advance_ns(2'500'000);                          // tick 1 runs from 1 ms to 3.5 ms
  const std::int64_t d = s.after_tick(clock.now_ns());
  // Its deadline was 2 ms: 1.5 ms late, so the 2 ms and 3 ms starts are
  // missed (2 overruns) and the next tick starts at 4 ms.
  EXPECT_EQ(s.overruns(), 2u);
  EXPECT_EQ(s.worst_late_ns(), 1'500'000);
  EXPECT_EQ(d, 4 * kPeriod);
  clock.sleep_until_ns(d);
  clock.advance_ns(100'000);
  EXPECT_EQ(s.after_tick(clock.now_ns()), 5 * kPeriod) << "back on the grid";
  EXPECT_EQ(s.overruns(), 2u);
}

TEST(PeriodicSchedule, EndingExactlyOnTheDeadlineIsNotAnOverrun) {
  PeriodicSchedule s(kPeriod, 0);
  EXPECT_EQ(s.after_tick(kPeriod), kPeriod);
  EXPECT_EQ(s.overruns(), 0u);
}

}  // namespace
}  // namespace mrd::app
