#include "host_sim/risk/fragility_fit.hpp"

#include <cmath>

#include "host_sim/risk/stochastic_motion.hpp"
#include "mrd/units.hpp"

namespace mrd::risk {

std::vector<LimitState> default_limit_states(double isolation_gap_m, double floor_accel_g) {
  return {
      {"stroke", Metric::kBaseDisplacement, kDamperStroke_m, "peak base displacement reaches the damper stroke"},
      {"isolation_gap", Metric::kBaseDisplacement, isolation_gap_m, "peak base displacement reaches the isolation gap"},
      {"floor_accel", Metric::kFloorAccel, floor_accel_g * units::kStandardGravity_m_s2,
       "peak absolute floor acceleration (floors 1-5) reaches the threshold"},
  };
}

LimitState story_drift_limit_state(double story_drift_m) {
  return {"story_drift", Metric::kStoryDrift, story_drift_m, "peak story drift (any story) reaches the threshold",
          true};
}

LimitState bearing_capacity_limit_state(double capacity_m) {
  return {"bearing_capacity", Metric::kBaseDisplacement, capacity_m,
          "peak isolator displacement reaches the bearings' displacement capacity (building file)", true};
}

double metric_value(const RunMetrics& m, Metric metric) noexcept {
  switch (metric) {
    case Metric::kBaseDisplacement:
      return m.peak_base_displacement_m;
    case Metric::kFloorAccel:
      return m.peak_floor_accel_m_s2;
    case Metric::kStoryDrift:
      return m.peak_story_drift_m;
  }
  return 0.0;
}

namespace {

/// Each limit state's rank among the states of its kind (opt-in or not), and
/// the number of states that are not opt-in (the base states: the thesis's
/// three in a study of `mrd fragility`).
struct SeedRanks {
  std::vector<std::size_t> rank;
  std::size_t base_states = 0;
};

SeedRanks seed_ranks(const std::vector<LimitState>& limit_states) {
  SeedRanks r;
  std::size_t opt_in = 0;
  for (const auto& l : limit_states) r.rank.push_back(l.opt_in ? opt_in++ : r.base_states++);
  return r;
}

/// The seed index of the curve (m, k, s) (fragility_fit.hpp: base states
/// first in (mode, idle, state) order, then each opt-in state's block).
std::size_t seed_index(const FragilityPlan& plan, const std::vector<LimitState>& limit_states, const SeedRanks& r,
                       std::size_t m, std::size_t k, std::size_t s) {
  const std::size_t modes = plan.modes.size(), idles = plan.idle_years.size();
  const std::size_t mode_idle = m * idles + k;
  if (!limit_states[s].opt_in) return mode_idle * r.base_states + r.rank[s];
  return modes * idles * (r.base_states + r.rank[s]) + mode_idle;
}

}  // namespace

std::vector<FragilityCurve> fit_fragilities(const FragilityPlan& plan, const std::vector<RunMetrics>& runs,
                                            const std::vector<LimitState>& limit_states,
                                            const BootstrapOptions& bootstrap) {
  std::vector<double> eval;
  const double lo = std::log(plan.pga_g.front() / 2.0), hi = std::log(plan.pga_g.back() * 2.0);
  for (int i = 0; i < bootstrap.eval_points; ++i) {
    eval.push_back(std::exp(lo + (hi - lo) * i / std::max(1, bootstrap.eval_points - 1)));
  }
  std::vector<FragilityCurve> curves;
  const std::size_t n_rec = plan.records.size();
  const SeedRanks ranks = seed_ranks(limit_states);
  for (std::size_t m = 0; m < plan.modes.size(); ++m) {
    for (std::size_t k = 0; k < plan.idle_years.size(); ++k) {
      for (std::size_t s = 0; s < limit_states.size(); ++s) {
        FragilityCurve c;
        c.mode = m;
        c.idle = k;
        c.limit_state = s;
        ExceedanceTable table(plan.pga_g.size(), std::vector<std::uint8_t>(n_rec, 0));
        for (std::size_t j = 0; j < plan.pga_g.size(); ++j) {
          LevelCounts level{plan.pga_g[j], static_cast<unsigned>(n_rec), 0};
          for (std::size_t r = 0; r < n_rec; ++r) {
            const RunMetrics& run = runs[plan.index({m, k, j, r})];
            const bool exceeded = metric_value(run, limit_states[s].metric) >= limit_states[s].threshold;
            table[j][r] = exceeded;
            level.exceed += exceeded;
          }
          c.levels.push_back(level);
        }
        c.fit = fit_lognormal_mle(c.levels);
        const std::size_t seed_at = seed_index(plan, limit_states, ranks, m, k, s);
        c.band = bootstrap_band(plan.pga_g, table, eval, bootstrap.resamples,
                                record_seed(bootstrap.seed ^ 0x626f6f74ULL, seed_at));
        curves.push_back(std::move(c));
      }
    }
  }
  return curves;
}

}  // namespace mrd::risk
