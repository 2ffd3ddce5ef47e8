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

// Two bearing groups stating 0.40 m and 0.30 m (and one stating none): the
// capacity is the smaller, 0.30 m; a peak of exactly 0.30 m does not exceed it.
TEST(Validity, BearingCapacityIsTheSmallestStatedAndNamesTheRuns) {
  structure::BuildingParams b;  // the thesis building: linear isolation, no bearings
  EXPECT_TRUE(bearing_capacity_warnings({5.0}, b).empty());
  structure::LeadRubberBearing lr;
  lr.count = 4;
  lr.characteristic_strength_n = 5.0e4;
  lr.post_yield_stiffness_n_m = 1.0e6;
  lr.yield_displacement_m = 0.01;
  lr.displacement_capacity_m = 0.40;
  b.isolators.push_back(lr);
  lr.displacement_capacity_m = 0.30;
  b.isolators.push_back(lr);
  lr.displacement_capacity_m = 0.0;
  b.isolators.push_back(lr);
  EXPECT_TRUE(bearing_capacity_warnings({0.30}, b).empty());
  const auto one = bearing_capacity_warnings({0.35}, b);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0], "peak isolator displacement 0.35 m exceeds the bearings' displacement capacity 0.3 m (building file)");
  const auto many = bearing_capacity_warnings({0.1, 0.31, 0.45, 0.2}, b);
  ASSERT_EQ(many.size(), 1u);
  EXPECT_EQ(many[0], "in 2 of 4 runs: peak isolator displacement up to 0.45 m exceeds the bearings' displacement "
                     "capacity 0.3 m (building file)");
}

}  // namespace
}  // namespace mrd::run
