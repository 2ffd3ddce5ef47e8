#pragma once
/// Outputs of `mrd fragility`: runs.csv (one row per run, in run order),
/// fragility.csv (one row per curve), fragility_curves.csv (each curve and its
/// bootstrap band at a grid of PGAs), one plot per control mode and limit
/// state (a curve per idle time), and summary.json. Numbers are written with
/// fixed printf formats ("%.9g"), so equal results give equal bytes.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host_sim/risk/fragility_fit.hpp"
#include "host_sim/risk/fragility_plan.hpp"

namespace mrd::risk {

/// Header of fragility.csv, read back by `mrd risk`.
inline constexpr const char* kFragilityCsvHeader =
    "control,limit_state,threshold,idle_years,status,median_pga_g,beta,median_pga_g_p05,median_pga_g_p95,"
    "beta_p05,beta_p95,runs,exceedances";
/// Columns fragility.csv has after kFragilityCsvHeader: the lowest and highest
/// PGA level the curves were fitted over, g (beyond them a curve is
/// extrapolated). `mrd risk` reads them when present.
inline constexpr const char* kFragilityCsvRangeColumns = "pga_g_min,pga_g_max";

std::string runs_csv(const FragilityPlan& plan, const std::vector<RunMetrics>& runs);
std::string fragility_csv(const FragilityPlan& plan, const std::vector<LimitState>& limit_states,
                          const std::vector<FragilityCurve>& curves);
std::string fragility_curves_csv(const FragilityPlan& plan, const std::vector<LimitState>& limit_states,
                                 const std::vector<FragilityCurve>& curves);

/// What summary.json says about the session beyond the plan and the curves.
struct FragilitySession {
  std::size_t computed = 0, resumed = 0;
  double wall_s = 0.0;
  std::size_t computed_rank0 = 0;  ///< runs rank 0 simulated
  double cpu_s_rank0 = 0.0;        ///< CPU time rank 0 spent on them, s
  int ranks = 1;
  unsigned threads_per_rank = 1;
  unsigned bootstrap = 0;
  bool synthetic = false;
  std::vector<std::string> warnings;  ///< fragility_warnings of the runs
};

/// Where the runs leave the model (run::validity_warnings over every run):
/// one sentence per limit, with the number of runs beyond it and the worst
/// peak. The runs keep the peak stroke (base displacement) and damper force;
/// the velocity and coil current are not recorded per run, so those limits
/// are not checked here.
std::vector<std::string> fragility_warnings(const std::vector<RunMetrics>& runs,
                                           const physics::DamperRating& rating = {});

nlohmann::json fragility_summary(const FragilityPlan& plan, const std::vector<LimitState>& limit_states,
                                 const std::vector<FragilityCurve>& curves, const FragilitySession& session);

/// Writes every file into `dir` (summary.json last), each atomically; returns
/// the reasons plots were not drawn.
std::vector<std::string> write_fragility_outputs(const std::filesystem::path& dir, const FragilityPlan& plan,
                                                 const std::vector<RunMetrics>& runs,
                                                 const std::vector<LimitState>& limit_states,
                                                 const std::vector<FragilityCurve>& curves,
                                                 const FragilitySession& session);

}  // namespace mrd::risk
