// `mrd risk`'s combination: fragility.csv read back, equivalent idle times of
// a capacity, interpolation in idle time, and the per-policy frequencies.
#include <gtest/gtest.h>

#include <cmath>

#include "host_sim/io/usage_error.hpp"
#include "host_sim/risk/fragility_report.hpp"
#include "host_sim/risk/lifetime_risk.hpp"

namespace mrd::risk {
namespace {

std::string fragility_error_of(const std::string& text) {
  try {
    (void)parse_fragility_csv(text, "f.csv");
  } catch (const io::UsageError& e) {
    return e.what();
  }
  return "";
}

const std::string kHeader = std::string(kFragilityCsvHeader) + "\n";

TEST(RiskCombine, ReadsFragilityCsvAndNamesBadFields) {
  const auto rows = parse_fragility_csv(kHeader +
                                            "semi-active,stroke,0.2921,0.5,fitted,0.8,0.4,0.7,0.9,0.3,0.5,80,12\n"
                                            "semi-active,stroke,0.2921,1,none_exceeded,inf,nan,inf,inf,nan,nan,80,0\n",
                                        "f.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].control, "semi-active");
  EXPECT_DOUBLE_EQ(rows[0].fit.median_im, 0.8);
  EXPECT_DOUBLE_EQ(rows[0].fit.beta, 0.4);
  EXPECT_EQ(rows[1].fit.status, FitStatus::kNoneExceeded);
  EXPECT_EQ(fragility_error_of("a,b\n"),
            "f.csv:1: expected the header of mrd fragility's fragility.csv "
            "('control,limit_state,threshold,idle_years...')");
  EXPECT_EQ(fragility_error_of(kHeader + "m,s,1,0,fitted,x,0.4,,,,,1,1\n"),
            "f.csv:2: field 'median_pga_g': expected a number, got 'x'");
  EXPECT_EQ(fragility_error_of(kHeader + "m,s,1,0,fitted,0.5,-1,,,,,1,1\n"),
            "f.csv:2: field 'beta': expected a log-standard deviation > 0");
  EXPECT_EQ(fragility_error_of(kHeader + "m,s,1,-2,fitted,0.5,1,,,,,1,1\n"),
            "f.csv:2: field 'idle_years': expected an idle time >= 0 years");
  EXPECT_EQ(fragility_error_of(kHeader + "m,s,1,0,maybe,0.5,1,,,,,1,1\n"),
            "f.csv:2: field 'status': expected fitted, none_exceeded or all_exceeded, got 'maybe'");
  EXPECT_EQ(fragility_error_of(kHeader + "m,s,1\n"), "f.csv:2: expected 13 fields, got 3");
  EXPECT_EQ(fragility_error_of(kHeader), "f.csv: no fragility curves");
}

// λ(τ) between τ_k: linear; outside: the end values.
TEST(RiskCombine, FrequencyIsInterpolatedLinearlyInIdleTime) {
  const std::vector<double> tau{0.0, 0.5, 1.0}, f{1e-3, 2e-3, 4e-3};
  EXPECT_DOUBLE_EQ(frequency_at(tau, f, 0.25), 1.5e-3);
  EXPECT_DOUBLE_EQ(frequency_at(tau, f, 0.75), 3e-3);
  EXPECT_DOUBLE_EQ(frequency_at(tau, f, 2.0), 4e-3);
  EXPECT_DOUBLE_EQ(frequency_at(tau, f, -1.0), 1e-3);
}

// The equivalent idle time inverts the settling model's capacity: the
// capacity of τ, mapped back, gives τ (up to T_max), and the threshold's
// idle time is what `mrd schedule` reports for it.
TEST(RiskCombine, EquivalentIdleInvertsTheCapacity) {
  fw::SettlingModel m;
  ASSERT_TRUE(m.init(fw::IdleModelConfig{}));
  for (double days : {10.0, 60.0, 200.0}) {
    const double tau_s = days * 86400.0;
    const double c = m.capacity_of_pr(m.pr_of_idle(tau_s));
    EXPECT_NEAR(equivalent_idle_s(m, c), tau_s, 1.0) << days;
  }
  EXPECT_EQ(equivalent_idle_s(m, 0.0), m.max_settling_time_s());
}

// Two idle times; each limit state's frequency at an idle time is the
// closed form k0 θ^−k exp(k²β²/2) of the power-law site (see the hazard test):
// θ = 0.4 g, β = 0.5 at τ = 0 → 2.24209e-3 per year. The reference (always
// fully mixed) is that; a never-mixed damper idles longer, so with a weaker
// curve at the longer idle time its frequency is higher.
TEST(RiskCombine, PoliciesSitBetweenTheCurvesOfTheirIdleTimes) {
  std::vector<FragilityRow> rows(2);
  rows[0] = {"passive-on", "stroke", 0.2921, 0.0, {FitStatus::kFitted, 0.4, 0.5}};
  rows[1] = {"passive-on", "stroke", 0.2921, 1.0, {FitStatus::kFitted, 0.3, 0.5}};
  schedule::ScheduleOptions so;
  so.world.years = 5.0;
  const RiskResult r = compute_risk(rows, "", default_hazard_curve(), schedule::run_schedule(so));
  ASSERT_EQ(r.policies.size(), 4u);
  EXPECT_EQ(r.policies.back().name, "always-fully-mixed");
  const double ref = r.policies.back().annual_exceedance.at("stroke");
  EXPECT_NEAR(ref, 2.24209e-3, 2.24209e-3 * 2e-3);
  const double worst = r.frequency_at_idle.at("stroke")[1];
  for (std::size_t i = 0; i + 1 < r.policies.size(); ++i) {
    const double f = r.policies[i].annual_exceedance.at("stroke");
    EXPECT_GE(f, ref * (1 - 1e-12)) << r.policies[i].name;
    EXPECT_LE(f, worst * (1 + 1e-12)) << r.policies[i].name;
    double total = 0.0;
    for (const auto& b : r.policies[i].idle_fraction) total += b.fraction;
    EXPECT_NEAR(total, 1.0, 1e-12);
  }
  EXPECT_EQ(r.policies[0].name, "none");
  EXPECT_GT(r.policies[0].annual_exceedance.at("stroke"), r.policies[2].annual_exceedance.at("stroke"));
  EXPECT_THROW(compute_risk(rows, "semi-active", default_hazard_curve(), schedule::run_schedule(so)), io::UsageError);
}

// The PGA levels a curve was fitted over, when fragility.csv gives them.
TEST(RiskCombine, ReadsTheFittedPgaRangeWhenGiven) {
  const std::string header = std::string(kFragilityCsvHeader) + "," + kFragilityCsvRangeColumns + "\n";
  const auto rows = parse_fragility_csv(header + "m,stroke,0.2921,0,fitted,0.8,0.4,,,,,80,12,0.2,1.5\n", "f.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].pga_min_g, 0.2);
  EXPECT_EQ(rows[0].pga_max_g, 1.5);
  EXPECT_TRUE(std::isnan(parse_fragility_csv(kHeader + "m,s,1,0,fitted,0.5,1,,,,,1,1\n", "f.csv")[0].pga_min_g));
  EXPECT_EQ(fragility_error_of(header + "m,s,1,0,fitted,0.5,1,,,,,1,1\n"), "f.csv:2: expected 15 fields, got 13");
  EXPECT_EQ(fragility_error_of(header + "m,s,1,0,fitted,0.5,1,,,,,1,1,0,1\n"),
            "f.csv:2: field 'pga_g_min': expected the lowest PGA level, > 0 g");
  EXPECT_EQ(fragility_error_of(header + "m,s,1,0,fitted,0.5,1,,,,,1,1,0.5,0.2\n"),
            "f.csv:2: field 'pga_g_max': expected the highest PGA level, >= pga_g_min");
}

std::vector<FragilityRow> rows_fitted_over(double lo_g, double hi_g, FitStatus status = FitStatus::kFitted) {
  std::vector<FragilityRow> rows(2);
  rows[0] = {"passive-on", "stroke", 0.2921, 0.0, {status, 0.4, 0.5}, lo_g, hi_g};
  rows[1] = {"passive-on", "stroke", 0.2921, 1.0, {status, 0.3, 0.5}, lo_g, hi_g};
  return rows;
}

bool has_warning(const RiskResult& r, const std::string& text) {
  for (const auto& w : r.warnings) {
    if (w.find(text) != std::string::npos) return true;
  }
  return false;
}

// P ≡ 1 (every run exceeded) over a hazard with points at 0.05, 0.2, 1.5 and
// 5 g, λ = 0.1, 0.01, 0.001, 1e-4 per year, curves fitted over 0.2-1.5 g:
// λ_LS = λ(0.05) = 0.1 (the drops plus the tail), of which the fitted levels
// hold λ(0.2) − λ(1.5) = 0.009; extrapolated: 1 − 0.009/0.1 = 0.91.
TEST(RiskCombine, PartOfTheResultFromOutsideTheFittedLevels) {
  const HazardCurve hazard{"test site", {0.05, 0.2, 1.5, 5.0}, {0.1, 0.01, 1e-3, 1e-4}};
  schedule::ScheduleOptions so;
  so.world.years = 2.0;
  const RiskResult r =
      compute_risk(rows_fitted_over(0.2, 1.5, FitStatus::kAllExceeded), "", hazard, schedule::run_schedule(so));
  EXPECT_EQ(r.fitted_pga_min_g, 0.2);
  EXPECT_EQ(r.fitted_pga_max_g, 1.5);
  ASSERT_EQ(r.extrapolated_fraction_at_idle.at("stroke").size(), 2u);
  EXPECT_NEAR(r.extrapolated_fraction_at_idle.at("stroke")[0], 0.91, 1e-12);
  EXPECT_NEAR(r.policies.back().extrapolated_fraction.at("stroke"), 0.91, 1e-12);
  EXPECT_TRUE(has_warning(r,
                          "the hazard curve (0.05-5 g) reaches beyond the fragility's fitted PGA levels (0.2-1.5 g): "
                          "91 % of the annual exceedance of stroke"))
      << r.warnings.front();
  EXPECT_TRUE(has_warning(r, "rest mainly on extrapolated curves"));
}

// A hazard far below the fitted levels (0.001-0.01 g against 0.2-1.5 g): every
// part of λ_LS is extrapolated, and so is every ratio; a hazard within them
// (0.3-1.2 g) is not.
TEST(RiskCombine, WarnsWhenTheRatiosRestOnExtrapolatedCurves) {
  schedule::ScheduleOptions so;
  so.world.years = 2.0;
  const auto sched = schedule::run_schedule(so);
  const HazardCurve far{"far", {0.001, 0.01}, {1.0, 0.1}};
  const RiskResult r = compute_risk(rows_fitted_over(0.2, 1.5), "", far, sched);
  EXPECT_EQ(r.extrapolated_fraction_at_idle.at("stroke")[0], 1.0);
  EXPECT_TRUE(has_warning(r, "the hazard curve (0.001-0.01 g) reaches beyond"));
  EXPECT_TRUE(has_warning(r, "the ratios to always-fully-mixed for stroke rest mainly on extrapolated curves: none "));
  EXPECT_TRUE(has_warning(r, "against 100 % for always-fully-mixed"));
  const auto j = risk_summary(r);
  EXPECT_EQ(j["warnings"].size(), r.warnings.size());
  EXPECT_EQ(j["fitted_pga_g"]["max"], 1.5);

  const HazardCurve within{"within", {0.3, 1.2}, {1e-2, 1e-4}};
  const RiskResult in = compute_risk(rows_fitted_over(0.2, 1.5), "", within, sched);
  EXPECT_EQ(in.extrapolated_fraction_at_idle.at("stroke")[0], 0.0);
  EXPECT_FALSE(has_warning(in, "extrapolat"));
}

// A fragility.csv without the range columns: said, not guessed.
TEST(RiskCombine, FragilityWithoutItsPgaLevelsIsNamed) {
  schedule::ScheduleOptions so;
  so.world.years = 2.0;
  std::vector<FragilityRow> rows(1);
  rows[0] = {"passive-on", "stroke", 0.2921, 0.0, {FitStatus::kFitted, 0.4, 0.5}};
  const RiskResult r = compute_risk(rows, "", default_hazard_curve(), schedule::run_schedule(so));
  EXPECT_TRUE(has_warning(r, "fragility.csv does not give the PGA levels its curves were fitted over"));
  EXPECT_TRUE(r.extrapolated_fraction_at_idle.empty());
}

}  // namespace
}  // namespace mrd::risk
