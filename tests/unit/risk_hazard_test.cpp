// Hazard curves: the file format and its errors, the default site, and the
// integral λ_LS = ∫ P(LS | IM) |dλ(IM)| against its closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "host_sim/io/usage_error.hpp"
#include "host_sim/risk/hazard_curve.hpp"
#include "host_sim/risk/lognormal_fit.hpp"

namespace mrd::risk {
namespace {

std::string hazard_error_of(const std::string& text) {
  try {
    (void)parse_hazard_csv(text, "site.csv");
  } catch (const io::UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(RiskHazard, ReadsTheDocumentedFormat) {
  const HazardCurve c =
      parse_hazard_csv("\xEF\xBB\xBF# site A\npga_g,annual_frequency\r\n0.1,0.02\n\n0.4,0.001\n", "a.csv");
  ASSERT_EQ(c.pga_g.size(), 2u);
  EXPECT_DOUBLE_EQ(c.pga_g[1], 0.4);
  EXPECT_DOUBLE_EQ(c.annual_frequency[0], 0.02);
  // Log-log interpolation: the slope is ln(0.001/0.02)/ln(4) = −2.161; at
  // 0.2 g, λ = 0.02·2^−2.161 = 0.02·0.2236 = 4.472e-3 (= √(0.02·0.001)).
  EXPECT_NEAR(c.frequency_at(0.2), std::sqrt(0.02 * 0.001), 1e-12);
}

TEST(RiskHazard, BadLinesNameFileLineAndField) {
  EXPECT_EQ(hazard_error_of("pga,rate\n"), "site.csv:1: expected the header 'pga_g,annual_frequency', got 'pga,rate'");
  EXPECT_EQ(hazard_error_of("pga_g,annual_frequency\n0.1,0.02\n0.2,x\n"),
            "site.csv:3: field 'annual_frequency': expected a number, got 'x'");
  EXPECT_EQ(hazard_error_of("pga_g,annual_frequency\n0.2,0.02\n0.1,0.01\n"),
            "site.csv:3: field 'pga_g': expected PGAs that increase from row to row");
  EXPECT_EQ(hazard_error_of("pga_g,annual_frequency\n0.1,0.02\n0.2,0.03\n"),
            "site.csv:3: field 'annual_frequency': expected frequencies that decrease as the PGA grows");
  EXPECT_EQ(hazard_error_of("pga_g,annual_frequency\n-0.1,0.02\n"), "site.csv:2: field 'pga_g': expected a PGA > 0 g");
  EXPECT_EQ(hazard_error_of("pga_g,annual_frequency\n0.1,0.02,3\n"),
            "site.csv:2: expected 2 fields (pga_g,annual_frequency), got 3");
  EXPECT_EQ(hazard_error_of("pga_g,annual_frequency\n0.1,0.02\n"), "site.csv: expected at least 2 points on the hazard curve");
  EXPECT_EQ(hazard_error_of(""), "site.csv: no header 'pga_g,annual_frequency'");
}

// The default site's anchor: 10 % in 50 years is λ = −ln(0.9)/50 =
// 2.10721e-3 per year at 0.3 g; k0 = λ·0.3^2.5 = 2.10721e-3·0.0492950 = 1.03875e-4.
TEST(RiskHazard, DefaultSiteIsThePowerLawOfItsAnchor) {
  EXPECT_NEAR(default_hazard_k0(), 1.03875e-4, 1e-9);
  const HazardCurve c = default_hazard_curve();
  EXPECT_NEAR(c.frequency_at(0.3), 2.10721e-3, 1e-8);
  EXPECT_NEAR(c.pga_g.front(), 0.01, 1e-12);
  EXPECT_NEAR(c.pga_g.back(), 5.0, 1e-12);
}

// Closed form (Cornell, Jalayer, Hamburger & Foutch 2002, J. Struct. Eng. 128(4), with a
// lognormal capacity): for λ(x) = k0 x^−k and P = Φ(ln(x/θ)/β),
//   λ_LS = k0 θ^−k exp(k²β²/2).
// θ = 0.4 g, β = 0.5, k = 2.5: 1.03875e-4 · 0.4^−2.5 · exp(0.78125)
//   = 1.03875e-4 · 9.88212 · 2.18420 = 2.24209e-3 per year.
TEST(RiskHazard, IntegralMatchesTheClosedFormForAPowerLaw) {
  const HazardCurve c = default_hazard_curve();
  LognormalFit fit;
  fit.median_im = 0.4;
  fit.beta = 0.5;
  const double lambda = limit_state_frequency(c, [&](double x) { return fit.probability(x); });
  EXPECT_NEAR(lambda, 2.24209e-3, 2.24209e-3 * 2e-3);
  // P ≡ 1 gives the frequency of the curve's first point.
  EXPECT_NEAR(limit_state_frequency(c, [](double) { return 1.0; }), c.annual_frequency.front(),
              c.annual_frequency.front() * 1e-12);
}

}  // namespace
}  // namespace mrd::risk
