// `mrd schedule`: output files and fields, the requirement on the default
// world, the options, help, and bad input (exit status 2, one-line error,
// nothing half-written).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

class ScheduleCli : public ::testing::Test {
 protected:
  TempDir scratch_;
  TempDir out_;
};

const nlohmann::json& policy(const nlohmann::json& j, const std::string& name) {
  for (const auto& p : j["policies"]) {
    if (p["name"] == name) return p;
  }
  throw std::runtime_error("no policy " + name);
}

// Ten years of the default world: the three policies with their fields, the
// CSV files and the plot. The estimator keeps the threshold at every moment
// with fewer cycles than the longest fixed interval that does (the daily
// ambient volume varies, log-normal with σ = 1: the fixed interval must
// cover the calmest stretch, the estimator credits the windy days).
TEST_F(ScheduleCli, WritesSummaryCsvAndPlot) {
  const auto r = run_mrd("schedule --years 10 --seed 1 --out " + out_.path().string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  for (const char* key : {"years", "seed", "threshold", "actuator", "earthquakes_per_year", "earthquakes",
                          "max_settling_time_days", "threshold_idle_days", "mixing_plan", "fixed_interval_days",
                          "fixed_interval_source", "policies", "estimator_meets_threshold",
                          "estimator_fewer_cycles_than_fixed"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  ASSERT_EQ(j["policies"].size(), 3u);
  std::set<std::string> names;
  for (const auto& p : j["policies"]) {
    names.insert(p["name"].get<std::string>());
    for (const char* key : {"mixing_cycles_per_year", "min_capacity_fraction", "min_capacity_fraction_any_time",
                            "mean_capacity_fraction", "meets_threshold", "mixing_cycles", "aborted_cycles",
                            "maintenance_requests_per_year", "earthquakes_met"}) {
      EXPECT_TRUE(p.contains(key)) << p["name"] << " " << key;
    }
  }
  EXPECT_EQ(names, (std::set<std::string>{"none", "fixed-interval", "estimator"}));

  const double threshold = j["threshold"].get<double>();
  EXPECT_DOUBLE_EQ(threshold, 0.8);
  const auto& none = policy(j, "none");
  const auto& fixed = policy(j, "fixed-interval");
  const auto& est = policy(j, "estimator");
  EXPECT_EQ(none["mixing_cycles_per_year"].get<double>(), 0.0);
  EXPECT_EQ(j["fixed_interval_source"], "search");
  EXPECT_TRUE(fixed["meets_threshold"].get<bool>());
  EXPECT_TRUE(est["meets_threshold"].get<bool>());
  EXPECT_GE(est["min_capacity_fraction_any_time"].get<double>(), threshold);
  if (!est["min_capacity_fraction"].is_null()) {
    EXPECT_GE(est["min_capacity_fraction"].get<double>(), threshold);
  }
  EXPECT_LT(est["mixing_cycles_per_year"].get<double>(), fixed["mixing_cycles_per_year"].get<double>());
  EXPECT_TRUE(j["estimator_meets_threshold"].get<bool>());
  EXPECT_TRUE(j["estimator_fewer_cycles_than_fixed"].get<bool>());
  // The capacity an earthquake meets is one of the capacities the fluid had.
  if (!est["min_capacity_fraction"].is_null()) {
    EXPECT_GE(est["min_capacity_fraction"].get<double>(), est["min_capacity_fraction_any_time"].get<double>());
  }
  // Thesis cycle: ±76.2 mm at 0.2 Hz.
  EXPECT_DOUBLE_EQ(j["mixing_plan"]["amplitude_m"].get<double>(), 0.0762);
  EXPECT_DOUBLE_EQ(j["mixing_plan"]["frequency_hz"].get<double>(), 0.2);

  // capacity.csv: one row per day (10 years = 3653 days), a column per policy.
  const std::string csv = slurp(out_.path() / "capacity.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "time_years,none_capacity_fraction,fixed-interval_capacity_fraction,estimator_capacity_fraction");
  EXPECT_EQ(count_lines(csv), 1 + 3653);
  const std::string quakes = slurp(out_.path() / "earthquakes.csv");
  EXPECT_EQ(count_lines(quakes), 1 + j["earthquakes"].get<int>());
  if (r.err.find("plot not written") == std::string::npos) {
    EXPECT_GT(fs::file_size(out_.path() / "capacity.png"), 1000u);
  }
  EXPECT_NE(r.out.find("estimator"), std::string::npos);
}

// A given interval is used as is: 5 days over 3 years is 365.25/5 = 73.05
// cycles a year (± one cycle at the end of the run).
TEST_F(ScheduleCli, IntervalOptionIsUsedAsGiven) {
  const auto r = run_mrd("schedule --years 3 --interval-days 5 --out " + out_.path().string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_EQ(j["fixed_interval_source"], "option");
  EXPECT_DOUBLE_EQ(j["fixed_interval_days"].get<double>(), 5.0);
  const auto& fixed = policy(j, "fixed-interval");
  EXPECT_DOUBLE_EQ(fixed["interval_days"].get<double>(), 5.0);
  EXPECT_NEAR(fixed["mixing_cycles_per_year"].get<double>(), 73.05, 1.0 / 3.0);
}

// Without an actuator every cycle is a technician's visit that a
// maintenance request asked for.
TEST_F(ScheduleCli, NoActuatorMeansMaintenanceRequests) {
  const auto r = run_mrd("schedule --years 2 --actuator no --out " + out_.path().string(), scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_EQ(j["actuator"], "no");
  const auto& est = policy(j, "estimator");
  EXPECT_GT(est["maintenance_requests_per_year"].get<double>(), 0.0);
  EXPECT_GE(est["min_capacity_fraction_any_time"].get<double>(), 0.8);
  const auto& fixed = policy(j, "fixed-interval");
  EXPECT_DOUBLE_EQ(fixed["maintenance_requests_per_year"].get<double>(), fixed["mixing_cycles_per_year"].get<double>());
}

TEST_F(ScheduleCli, HelpDocumentsFieldsAndUnits) {
  const auto r = run_mrd("schedule --help", scratch_.path());
  EXPECT_EQ(r.exit_code, 0);
  for (const char* key : {"--years", "--threshold", "--interval-days", "--seed", "--earthquakes-per-year",
                          "--actuator", "--out", "mixing_cycles_per_year", "min_capacity_fraction", "capacity.csv",
                          "capacity.png", "days", "Eq. 5.4", "0 is refused, not a search"}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  }
}

struct BadCase {
  const char* name;
  const char* args;
  const char* must_mention;
};

class ScheduleCliBadInput : public ScheduleCli, public ::testing::WithParamInterface<BadCase> {};

TEST_P(ScheduleCliBadInput, OneLineErrorExitTwoNothingWritten) {
  const auto& c = GetParam();
  const auto summary = out_.path() / "summary.json";
  { std::ofstream(summary) << "{\"earlier\": true}\n"; }
  { std::ofstream(out_.path() / ".mrd-result") << "an mrd result\n"; }
  const std::string years = std::string(c.args).find("--years") == std::string::npos ? "--years 1 " : "";
  const auto r = run_mrd("schedule " + years + c.args + " --out " + out_.path().string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(c.must_mention), std::string::npos) << r.err;
  EXPECT_EQ(slurp(summary), "{\"earlier\": true}\n");
  for (const auto& e : fs::directory_iterator(out_.path())) {
    EXPECT_TRUE(e.path().filename() == "summary.json" || e.path().filename() == ".mrd-result")
        << "left behind: " << e.path();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ScheduleCliBadInput,
    ::testing::Values(BadCase{"ZeroYears", "--years 0", "--years"}, BadCase{"NegativeYears", "--years -2", "--years"},
                      BadCase{"NaNYears", "--years nan", "--years"},
                      BadCase{"TooManyYears", "--years 5000", "--years"},
                      BadCase{"ThresholdAboveOne", "--threshold 1.5", "--threshold"},
                      BadCase{"ThresholdZero", "--threshold 0", "--threshold"},
                      BadCase{"ThresholdTooHigh", "--threshold 0.995", "--threshold"},
                      BadCase{"NegativeInterval", "--interval-days -3", "--interval-days"},
                      BadCase{"ZeroInterval", "--interval-days 0", "--interval-days"},
                      BadCase{"TinyInterval", "--interval-days 0.001", "--interval-days"},
                      BadCase{"NegativeRate", "--earthquakes-per-year -1", "--earthquakes-per-year"},
                      BadCase{"ActuatorMaybe", "--actuator maybe", "--actuator"},
                      BadCase{"NumericQuad", "--numeric quad", "--numeric"},
                      BadCase{"NumericEmpty", "--numeric ''", "--numeric"},
                      BadCase{"SeedNotANumber", "--seed abc", "abc"},
                      BadCase{"NegativeSeed", "--seed -1", "--seed"},
                      BadCase{"SeedAboveTwoToThe64", "--seed 18446744073709551616", "--seed"},
                      BadCase{"NegativeAmbient", "--ambient-litres-per-day -0.1", "--ambient-litres-per-day"},
                      BadCase{"UnknownOption", "--frobnicate", "frobnicate"}),
    [](const auto& p) { return std::string(p.param.name); });

// --numeric picks the build the estimator policy runs and is recorded in
// summary.json; the fixed-point build keeps the threshold like the double one.
TEST_F(ScheduleCli, NumericBuildIsUsedAndRecorded) {
  const auto r = run_mrd("schedule --years 2 --seed 1 --interval-days 5 --numeric fixed --out " + out_.path().string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("numeric fixed"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(slurp(out_.path() / "summary.json"));
  EXPECT_EQ(j["numeric"], "fixed");
  EXPECT_TRUE(j["estimator_meets_threshold"].get<bool>());
}

TEST_F(ScheduleCli, UnwritableOutIsAnError) {
  const auto file = out_.path() / "a-file";
  { std::ofstream(file) << "x"; }
  const auto r = run_mrd("schedule --years 1 --out " + (file / "sub").string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace mrd::test
