#include "host_sim/discrepancy/fit.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

#include "host_sim/discrepancy/solver_options.hpp"

namespace mrd::discrepancy {
namespace {

struct Bound {
  double lower;
  double range;
};

std::vector<Bound> bounds_of(const EffectSet& set, const ParamScale& scale) {
  std::vector<Bound> b;
  for (const Effect e : set.effects) {
    for (const auto& info : set.params_of(e)) {
      const ParamInfo p = scaled_param(info, scale);
      b.push_back({p.lower, p.upper - p.lower});
    }
  }
  return b;
}

/// Residuals (F_model − F_meas)/scale at the fit samples as a function of the
/// normalized parameters u ∈ [0, 1]^k, with a forward-difference Jacobian.
class SetCost final : public ceres::CostFunction {
 public:
  SetCost(const FitData& data, const EffectSet& set)
      : data_(data), set_(set), bounds_(bounds_of(set, data.model->param_scale())) {
    set_num_residuals(static_cast<int>(data.index.size()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(bounds_.size()));
    model_.resize(data.index.size());
    phys_.resize(bounds_.size());
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* u = parameters[0];
    const std::size_t k = bounds_.size();
    const std::size_t m = data_.index.size();
    if (!residuals_at(u, residuals)) return false;
    if (jacobians == nullptr || jacobians[0] == nullptr) return true;
    std::vector<double> up(u, u + k);
    std::vector<double> rp(m);
    for (std::size_t j = 0; j < k; ++j) {
      // Step inward at the upper bound so that the model is evaluated inside.
      const double h = up[j] + kStep > 1.0 ? -kStep : kStep;
      up[j] = u[j] + h;
      if (!residuals_at(up.data(), rp.data())) return false;
      up[j] = u[j];
      for (std::size_t r = 0; r < m; ++r) jacobians[0][r * k + j] = (rp[r] - residuals[r]) / h;
    }
    return true;
  }

 private:
  static constexpr double kStep = 1e-5;

  bool residuals_at(const double* u, double* out) const {
    for (std::size_t j = 0; j < bounds_.size(); ++j) phys_[j] = bounds_[j].lower + u[j] * bounds_[j].range;
    data_.model->simulate_at(set_, phys_, ws_, data_.index, model_);
    const double inv = 1.0 / data_.force_scale_n;
    for (std::size_t r = 0; r < data_.index.size(); ++r) {
      out[r] = (model_[r] - data_.measured_force_n[data_.index[r]]) * inv;
      if (!std::isfinite(out[r])) return false;
    }
    return true;
  }

  const FitData& data_;
  EffectSet set_;
  std::vector<Bound> bounds_;
  mutable ModelWorkspace ws_;
  mutable std::vector<double> model_;
  mutable std::vector<double> phys_;
};

}  // namespace

FitData make_fit_data(const DamperModel& model, std::span<const double> measured_force_n, std::size_t target) {
  FitData d;
  d.model = &model;
  d.measured_force_n = measured_force_n;
  const std::size_t n = measured_force_n.size();
  const std::size_t stride = std::max<std::size_t>(1, target > 0 ? n / target : 1);
  for (std::size_t k = 0; k < n; k += stride) d.index.push_back(k);
  double ss = 0.0;
  for (const double f : measured_force_n) ss += f * f;
  d.force_scale_n = n > 0 && ss > 0.0 ? std::sqrt(ss / static_cast<double>(n)) : 1.0;
  return d;
}

FitData make_fit_data(const DamperModel& model, std::span<const double> measured_force_n,
                      std::span<const std::size_t> candidates, std::size_t target) {
  FitData d;
  d.model = &model;
  d.measured_force_n = measured_force_n;
  const std::size_t n = candidates.size();
  const std::size_t stride = std::max<std::size_t>(1, target > 0 ? n / target : 1);
  double ss = 0.0;
  for (std::size_t j = 0; j < n; j += stride) {
    d.index.push_back(candidates[j]);
    ss += measured_force_n[candidates[j]] * measured_force_n[candidates[j]];
  }
  const double m = static_cast<double>(d.index.size());
  d.force_scale_n = m > 0 && ss > 0.0 ? std::sqrt(ss / m) : 1.0;
  return d;
}

namespace {

/// Whether block b is held out under the pattern shifted by `shift`.
bool held_out_block(std::size_t block, std::size_t shift) {
  const std::size_t r = (block + 10 - shift % 10) % 10;
  return r == 2 || r == 5 || r == 8;
}

}  // namespace

SampleSplit split_samples(std::span<const double> time_s, SampleRange range, std::span<const double> velocity_m_s) {
  SampleSplit s;
  range.end = std::min(range.end, time_s.size());
  if (range.begin >= range.end) return s;
  const double t0 = time_s[range.begin];
  const double span_s = time_s[range.end - 1] - t0;
  const auto block_of = [&](std::size_t k) {
    const double u = span_s > 0.0 ? (time_s[k] - t0) / span_s : 0.0;
    return std::min(static_cast<std::size_t>(u * static_cast<double>(kSplitBlocks)), kSplitBlocks - 1);
  };
  // Samples within kReversalZone_s after a reversal (a sign change of the
  // velocity, as engaged_samples counts them; a velocity that chatters
  // through zero restarts the zone), per block, and the reversals themselves
  // (sign changes more than a zone after the one before).
  std::vector<double> zone(kSplitBlocks, 0.0);
  double zone_total = 0.0;
  std::size_t reversals = 0;
  if (velocity_m_s.size() >= range.end) {
    double last_s = -1e300;
    for (std::size_t k = range.begin + 1; k < range.end; ++k) {
      if ((velocity_m_s[k] > 0.0) != (velocity_m_s[k - 1] > 0.0)) {
        if (time_s[k] - last_s > kReversalZone_s) ++reversals;
        last_s = time_s[k];
      }
      if (time_s[k] - last_s <= kReversalZone_s) {
        zone[block_of(k)] += 1.0;
        zone_total += 1.0;
      }
    }
  }
  const auto held_share = [&](std::size_t shift) {
    double n = 0.0;
    for (std::size_t b = 0; b < kSplitBlocks; ++b) n += held_out_block(b, shift) ? zone[b] : 0.0;
    return n / zone_total;
  };
  if (reversals >= kMinSplitReversals && held_share(0) < kMinHeldReversalShare) {
    double best = std::fabs(held_share(0) - kHeldOutShare);
    for (std::size_t shift = 1; shift < 10; ++shift) {
      const double miss = std::fabs(held_share(shift) - kHeldOutShare);
      if (miss < best) {
        best = miss;
        s.pattern_shift = shift;
      }
    }
  }
  for (std::size_t k = range.begin; k < range.end; ++k) {
    (held_out_block(block_of(k), s.pattern_shift) ? s.held_out : s.train).push_back(k);
  }
  return s;
}

SampleSplit split_samples(std::span<const double> time_s) { return split_samples(time_s, {0, time_s.size()}); }

double fit_rss(const FitData& data, const EffectSet& set, std::span<const double> params, ModelWorkspace& ws,
               std::vector<double>* residual_n) {
  std::vector<double> model(data.index.size());
  data.model->simulate_at(set, params, ws, data.index, model);
  double rss = 0.0;
  if (residual_n) residual_n->resize(model.size());
  for (std::size_t r = 0; r < model.size(); ++r) {
    const double e = data.measured_force_n[data.index[r]] - model[r];
    rss += e * e;
    if (residual_n) (*residual_n)[r] = e;
  }
  return rss;
}

namespace {

struct LocalFit {
  std::vector<double> u;
  int iterations = 0;
  bool converged = false;
};

/// Levenberg–Marquardt from `u0` (normalized parameters, bounded to [0, 1]).
LocalFit local_fit(const FitData& data, const EffectSet& set, std::vector<double> u0) {
  LocalFit f;
  f.u = std::move(u0);
  const std::size_t k = f.u.size();
  if (k == 0) {
    f.converged = true;
    return f;
  }
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  problem.AddResidualBlock(new SetCost(data, set), nullptr, f.u.data());
  for (std::size_t j = 0; j < k; ++j) {
    problem.SetParameterLowerBound(f.u.data(), static_cast<int>(j), 0.0);
    problem.SetParameterUpperBound(f.u.data(), static_cast<int>(j), 1.0);
  }
  const ceres::Solver::Options so = lm_solver_options(60);
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  f.iterations = static_cast<int>(summary.iterations.size());
  f.converged = summary.termination_type == ceres::CONVERGENCE;
  return f;
}

}  // namespace

FitOutcome fit_effects(const FitData& data, const EffectSet& set, std::vector<double> start, const Effect* grid_effect,
                       std::size_t max_starts) {
  FitOutcome out;
  out.set = set;
  const ParamScale scale = data.model->param_scale();
  const std::vector<Bound> b = bounds_of(set, scale);
  const std::size_t k = b.size();
  ModelWorkspace ws;

  // Starting points: the given start (the new effect at its null value, so
  // the fit never ends worse than the model without it) and every point of
  // the new effect's init grid (the product of its parameters' grids), the
  // other effects held. The local fit runs from the best max_starts of them.
  std::vector<std::pair<double, std::vector<double>>> starts;
  starts.emplace_back(fit_rss(data, set, start, ws), start);
  if (grid_effect != nullptr) {
    if (const auto off = set.offset(*grid_effect)) {
      const auto params = set.params_of(*grid_effect);
      std::size_t combos = 1;
      for (std::size_t i = 0; i < params.size(); ++i) combos *= params[i].init_grid.size();
      std::vector<double> trial = start;
      for (std::size_t c = 0; c < combos; ++c) {
        std::size_t rest = c;
        for (std::size_t i = 0; i < params.size(); ++i) {
          trial[*off + i] = scaled_param(params[i], scale).init_grid[rest % params[i].init_grid.size()];
          rest /= params[i].init_grid.size();
        }
        starts.emplace_back(fit_rss(data, set, trial, ws), trial);
      }
    }
  }
  std::stable_sort(starts.begin(), starts.end(), [](const auto& a, const auto& c) { return a.first < c.first; });
  const std::size_t tries = std::clamp<std::size_t>(max_starts, 1, starts.size());

  double best_rss = 0.0;
  for (std::size_t s = 0; s < tries; ++s) {
    std::vector<double> u0(k);
    for (std::size_t j = 0; j < k; ++j) u0[j] = std::clamp((starts[s].second[j] - b[j].lower) / b[j].range, 0.0, 1.0);
    const LocalFit f = local_fit(data, set, std::move(u0));
    std::vector<double> p(k);
    for (std::size_t j = 0; j < k; ++j) p[j] = b[j].lower + std::clamp(f.u[j], 0.0, 1.0) * b[j].range;
    const double rss = fit_rss(data, set, p, ws);
    if (s == 0 || rss < best_rss) {
      best_rss = rss;
      out.params = std::move(p);
      out.iterations = f.iterations;
      out.converged = f.converged;
    }
  }
  std::vector<double> residual;
  out.rss_n2 = fit_rss(data, set, out.params, ws, &residual);
  std::vector<double> t(data.index.size());
  for (std::size_t r = 0; r < t.size(); ++r) t[r] = data.model->input().time_s[data.index[r]];
  out.n_eff = noise_effective_samples(t, residual);
  return out;
}

double noise_effective_samples(std::span<const double> time_s, std::span<const double> residual) {
  const std::vector<double> t(time_s.begin(), time_s.end());
  const std::vector<double> r(residual.begin(), residual.end());
  const SmoothedMotion slow = smooth_motion(t, r, kDefaultSmoothingHalfWindow_s);
  std::vector<double> fast(r.size());
  for (std::size_t k = 0; k < r.size(); ++k) fast[k] = r[k] - slow.displacement_m[k];
  return effective_sample_count(fast);
}

double effective_sample_count(std::span<const double> residual) {
  const std::size_t n = residual.size();
  if (n < 4) return static_cast<double>(std::max<std::size_t>(n, 1));
  double mean = 0.0;
  for (const double r : residual) mean += r;
  mean /= static_cast<double>(n);
  double c0 = 0.0;
  for (const double r : residual) c0 += (r - mean) * (r - mean);
  if (!(c0 > 0.0)) return static_cast<double>(n);
  const std::size_t max_lag = std::min<std::size_t>(n / 8, 1000);
  const auto rho = [&](std::size_t lag) {
    double c = 0.0;
    for (std::size_t i = 0; i + lag < n; ++i) c += (residual[i] - mean) * (residual[i + lag] - mean);
    return c / c0;
  };
  // τ_int = −1 + 2 Σ_m Γ_m, Γ_m = ρ(2m) + ρ(2m+1), summed while Γ_m > 0 (Geyer 1992).
  double tau = -1.0;
  for (std::size_t m = 0; 2 * m + 1 <= max_lag; ++m) {
    const double g = (m == 0 ? 1.0 : rho(2 * m)) + rho(2 * m + 1);
    if (!(g > 0.0)) break;
    tau += 2.0 * g;
  }
  tau = std::max(tau, 1.0);
  return std::clamp(static_cast<double>(n) / tau, 1.0, static_cast<double>(n));
}

double bic(double rss, std::size_t n, double n_eff, std::size_t k) {
  const double nn = static_cast<double>(std::max<std::size_t>(n, 1));
  return n_eff * std::log(std::max(rss, 1e-300) / nn) + static_cast<double>(k) * std::log(std::max(n_eff, 1.0));
}

}  // namespace mrd::discrepancy
