// The validity warnings of closed-loop runs against the limits of Table 3.1
// (±0.2921 m stroke, 0.2491 m/s), Table 4.1 (0–2.5 A) and the 200 kN rating.
#include <gtest/gtest.h>

#include "host_sim/run/validity.hpp"

namespace mrd::run {
namespace {

TEST(Validity, InsideTheModelNoWarning) {
  // A coil overshoot to 2.52 A is within the 2 % tolerance on the 2.5 A rating.
  EXPECT_TRUE(validity_warnings(ValidityPeaks{0.29, 0.249, 2.52, 199.0e3}).empty());
}

TEST(Validity, EachLimitNamesItsPeakAndLimit) {
  const auto w = validity_warnings(ValidityPeaks{0.30, 0.26, 2.6, 210.0e3});
  ASSERT_EQ(w.size(), 4u);
  EXPECT_NE(w[0].find("0.3 m"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("0.2921"), std::string::npos) << w[0];
  EXPECT_NE(w[1].find("0.2491"), std::string::npos) << w[1];
  EXPECT_NE(w[2].find("2.6 A"), std::string::npos) << w[2];
  EXPECT_NE(w[3].find("2e+05"), std::string::npos) << w[3];
}

TEST(Validity, ManyRunsSayHowMany) {
  const auto w = validity_warnings(std::vector<ValidityPeaks>{{0.1, 0.1, 1.0, 1e5}, {0.35, 0.1, 1.0, 1e5}});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("0.35"), std::string::npos) << w[0];
}

}  // namespace
}  // namespace mrd::run
