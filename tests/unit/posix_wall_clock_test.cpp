// The board's wall clock (CLOCK_REALTIME): it agrees with the C++ library's
// system clock, and a clock before 2020 counts as unset.
#include "firmware/platform/linux/posix_clock.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace mrd::posix {
namespace {

TEST(PosixWallClock, AgreesWithTheSystemClock) {
  PosixWallClock rtc;
  double unix_s = 0.0;
  ASSERT_TRUE(rtc.now_s(unix_s)) << "this machine's clock is set (after 2020)";
  const double lib_s =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  EXPECT_NEAR(unix_s, lib_s, 1.0);
}

TEST(PosixWallClock, TheEarliestValidTimeIs2020) {
  // 50 years of 365 days plus the 12 leap days of 1972–2016: 18262 days.
  EXPECT_EQ(PosixWallClock::kEarliestValidUnixS, 18262.0 * 86400.0);
}

}  // namespace
}  // namespace mrd::posix
