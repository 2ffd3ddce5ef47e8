// Lognormal fragility by maximum likelihood (Baker 2015) and its bootstrap bands.
#include <gtest/gtest.h>

#include <cmath>

#include "host_sim/risk/lognormal_fit.hpp"

namespace mrd::risk {
namespace {

// Hand calculation. Two PGA levels and two parameters: the likelihood
// Σ z ln Φ(u_j) + (n − z) ln Φ(−u_j) is largest when each Φ(u_j) equals the
// observed fraction z_j/n_j (the saturated binomial fit), so
//   (ln x_j − ln θ)/β = Φ⁻¹(z_j/n_j).
// x_1 = 0.1 g with 5 of 20 exceeding (1/4), x_2 = 0.4 g with 15 of 20 (3/4):
//   Φ⁻¹(1/4) = −0.6744897501960817, Φ⁻¹(3/4) = +0.6744897501960817 (tables)
//   ln θ = (ln 0.1 + ln 0.4)/2            → θ = √0.04 = 0.2 g
//   β = (ln 0.4 − ln 0.1)/(2·0.6744897502) = 1.3862943611/1.3489795004 = 1.0276615476
TEST(RiskLognormalFit, TwoLevelsReproduceTheObservedFractions) {
  const LognormalFit fit = fit_lognormal_mle({{0.1, 20, 5}, {0.4, 20, 15}});
  ASSERT_EQ(fit.status, FitStatus::kFitted);
  EXPECT_NEAR(fit.median_im, 0.2, 1e-9);
  EXPECT_NEAR(fit.beta, 1.0276615476, 1e-8);
  EXPECT_NEAR(fit.probability(0.1), 0.25, 1e-9);
  EXPECT_NEAR(fit.probability(0.4), 0.75, 1e-9);
}

// Symmetry: levels θ/2, θ, 2θ with fractions 2/10, 5/10, 8/10. Reflecting
// ln x about ln 0.2 and swapping exceedances with non-exceedances maps the
// data onto themselves, and the likelihood onto itself with θ ↦ 0.04/θ; the
// maximum is unique, so it is at θ = 0.2 g. β is checked where an
// independent finite difference of the likelihood in β is zero.
TEST(RiskLognormalFit, SymmetricLevelsGiveTheMiddleAsMedian) {
  const std::vector<LevelCounts> levels{{0.1, 10, 2}, {0.2, 10, 5}, {0.4, 10, 8}};
  const LognormalFit fit = fit_lognormal_mle(levels);
  EXPECT_NEAR(fit.median_im, 0.2, 1e-9);
  const double h = 1e-5;
  const double d = (log_likelihood(levels, 0.2, fit.beta + h) - log_likelihood(levels, 0.2, fit.beta - h)) / (2 * h);
  EXPECT_NEAR(d, 0.0, 1e-5);
  // No other β or θ nearby does better.
  for (double db : {-0.05, 0.05}) {
    EXPECT_LT(log_likelihood(levels, 0.2, fit.beta + db), log_likelihood(levels, 0.2, fit.beta));
  }
  for (double dm : {-0.01, 0.01}) {
    EXPECT_LT(log_likelihood(levels, 0.2 + dm, fit.beta), log_likelihood(levels, 0.2, fit.beta));
  }
}

TEST(RiskLognormalFit, DegenerateDataAreNamed) {
  const LognormalFit none = fit_lognormal_mle({{0.1, 5, 0}, {0.2, 5, 0}});
  EXPECT_EQ(none.status, FitStatus::kNoneExceeded);
  EXPECT_EQ(none.probability(10.0), 0.0);
  const LognormalFit all = fit_lognormal_mle({{0.1, 5, 5}, {0.2, 5, 5}});
  EXPECT_EQ(all.status, FitStatus::kAllExceeded);
  EXPECT_EQ(all.probability(0.01), 1.0);
  // Perfect separation: the likelihood grows as β → 0; the search ends at a
  // β of a few hundredths (never below the floor) with θ between the last
  // level without and the first with exceedances.
  const LognormalFit sep = fit_lognormal_mle({{0.1, 5, 0}, {0.2, 5, 0}, {0.4, 5, 5}});
  EXPECT_EQ(sep.status, FitStatus::kFitted);
  EXPECT_GE(sep.beta, kMinBeta);
  EXPECT_LT(sep.beta, 0.03);
  EXPECT_GT(sep.median_im, 0.2);
  EXPECT_LT(sep.median_im, 0.4);
  EXPECT_THROW(fit_lognormal_mle({{0.0, 5, 1}}), std::invalid_argument);
  EXPECT_THROW(fit_lognormal_mle({{0.1, 5, 6}}), std::invalid_argument);
}

// Φ against tabulated values (Abramowitz & Stegun, Table 26.1).
TEST(RiskLognormalFit, NormalCdfMatchesTables) {
  EXPECT_NEAR(normal_cdf(0.0), 0.5, 1e-15);
  EXPECT_NEAR(normal_cdf(1.0), 0.8413447460685429, 1e-13);
  EXPECT_NEAR(normal_cdf(-1.96), 0.0249978951482204, 1e-13);
}

// Bootstrap: same seed, same band; the band holds the full-sample fit; the
// percentiles are ordered.
TEST(RiskLognormalFit, BootstrapBandIsSeededAndHoldsTheFit) {
  // 8 records at 4 levels; record r exceeds at level j when r < 2(j+1) - 1.
  const std::vector<double> im{0.1, 0.2, 0.4, 0.8};
  ExceedanceTable table(4, std::vector<std::uint8_t>(8, 0));
  std::vector<LevelCounts> levels;
  for (int j = 0; j < 4; ++j) {
    unsigned z = 0;
    for (int r = 0; r < 8; ++r) {
      table[j][r] = r < 2 * (j + 1) - 1;
      z += table[j][r];
    }
    levels.push_back({im[j], 8, z});
  }
  const std::vector<double> eval{0.1, 0.3, 0.8};
  const FragilityBand a = bootstrap_band(im, table, eval, 300, 7);
  const FragilityBand b = bootstrap_band(im, table, eval, 300, 7);
  const FragilityBand c = bootstrap_band(im, table, eval, 300, 8);
  EXPECT_EQ(a.p_low, b.p_low);
  EXPECT_EQ(a.p_high, b.p_high);
  EXPECT_NE(a.p_low, c.p_low);
  const LognormalFit fit = fit_lognormal_mle(levels);
  for (std::size_t k = 0; k < eval.size(); ++k) {
    EXPECT_LE(a.p_low[k], fit.probability(eval[k]) + 1e-12);
    EXPECT_GE(a.p_high[k], fit.probability(eval[k]) - 1e-12);
    EXPECT_LT(a.p_low[k], a.p_high[k]);
  }
  EXPECT_LE(a.median_low, fit.median_im);
  EXPECT_GE(a.median_high, fit.median_im);
}

}  // namespace
}  // namespace mrd::risk
