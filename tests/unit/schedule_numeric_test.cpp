// `mrd schedule`'s estimator policy with the float and fixed-point builds of
// the mixing task against the double reference: over 50 years of three
// worlds (seeds 1, 2, 3), the same mixing cycles per year and a worst
// capacity within 0.5 % (the acceptance bound; the capacity an
// estimator run keeps depends on when it mixes, which the builds decide from
// forecasts that differ by < 1e−6, see idle_estimator_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "host_sim/schedule/service_life.hpp"

namespace mrd::schedule {
namespace {

PolicyResult estimator_run(std::uint64_t seed, NumericBuild numeric) {
  WorldConfig wc;
  wc.years = 50.0;
  wc.seed = seed;
  const World w = make_world(wc);
  ServiceConfig c;
  c.numeric = numeric;
  c.detail_s = 0.0;
  return simulate_policy(w, c, {PolicyKind::kEstimator, 0.0});
}

class NumericBuilds : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(NumericBuilds, FloatAndFixedMatchTheDoubleBuildOverFiftyYears) {
  const PolicyResult ref = estimator_run(GetParam(), NumericBuild::kDouble);
  ASSERT_GT(ref.mixing_cycles, 1000u);  // the world does ask for mixing (≈ 34 a year)
  for (NumericBuild b : {NumericBuild::kFloat, NumericBuild::kFixed}) {
    const PolicyResult r = estimator_run(GetParam(), b);
    EXPECT_EQ(r.mixing_cycles, ref.mixing_cycles) << numeric_build_name(b);
    EXPECT_DOUBLE_EQ(r.mixing_cycles_per_year, ref.mixing_cycles_per_year) << numeric_build_name(b);
    EXPECT_NEAR(r.min_capacity_any_time, ref.min_capacity_any_time, 0.005 * ref.min_capacity_any_time)
        << numeric_build_name(b);
    if (std::isfinite(ref.min_capacity_at_quakes)) {
      EXPECT_NEAR(r.min_capacity_at_quakes, ref.min_capacity_at_quakes, 0.005 * ref.min_capacity_at_quakes)
          << numeric_build_name(b);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, NumericBuilds, ::testing::Values(1u, 2u, 3u));

TEST(NumericBuildName, ParsesTheThreeAndRefusesOthers) {
  EXPECT_EQ(parse_numeric_build("double"), NumericBuild::kDouble);
  EXPECT_EQ(parse_numeric_build("float"), NumericBuild::kFloat);
  EXPECT_EQ(parse_numeric_build("fixed"), NumericBuild::kFixed);
  EXPECT_ANY_THROW(parse_numeric_build("quad"));
}

}  // namespace
}  // namespace mrd::schedule
