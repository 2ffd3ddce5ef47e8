#include "host_sim/discrepancy/workflow.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <thread>

#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/discrepancy/fit.hpp"

namespace mrd::discrepancy {
namespace {

/// A parameter within this fraction of its range of a bound counts as at it.
constexpr double kAtBoundFraction = 2e-3;
/// Candidates refitted from several starting points in rounds after the first.
constexpr std::size_t kRefitted = 2;
constexpr std::size_t kStarts = 3;
/// Round-1 effects (earned, best first, other than the round-1 winner) whose
/// pairs round 2 weighs as alternative models.
constexpr std::size_t kAlternativeSources = 3;

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

/// Parameters of effect `e` inside a packed vector for `set`.
std::vector<double> own_params(const EffectSet& set, std::span<const double> all, Effect e) {
  const auto off = set.offset(e);
  const std::size_t k = effect_info(e).params.size();
  return {all.begin() + static_cast<std::ptrdiff_t>(*off), all.begin() + static_cast<std::ptrdiff_t>(*off + k)};
}

/// Packed start values for `set` from a fitted vector of `from` (effects
/// missing there at their null values).
std::vector<double> carry_params(const EffectSet& set, const EffectSet& from, std::span<const double> from_params) {
  std::vector<double> p = set.null_params();
  for (const Effect e : set.effects) {
    if (const auto src = from.offset(e)) {
      const auto dst = set.offset(e);
      for (std::size_t i = 0; i < effect_info(e).params.size(); ++i) p[*dst + i] = from_params[*src + i];
    }
  }
  return p;
}

double gap_on_fit(const FitData& d, double rss) {
  double ss = 0.0;
  for (const std::size_t k : d.index) ss += d.measured_force_n[k] * d.measured_force_n[k];
  return ss > 0.0 ? std::sqrt(rss / ss) : 0.0;
}

/// Runs `job(i)` for i in [0, count) on up to `threads` threads.
template <typename Job>
void parallel_for(std::size_t count, unsigned threads, Job job) {
  const unsigned hw = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  const std::size_t workers = std::min<std::size_t>(hw, count);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) job(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> pool;
  pool.reserve(workers);
  for (std::size_t w = 0; w < workers; ++w) {
    pool.emplace_back([&] {
      for (std::size_t i = next++; i < count; i = next++) job(i);
    });
  }
  for (auto& t : pool) t.join();
}

/// A fitted trial model of one round.
struct Trial {
  Effect effect{};           ///< the effect it adds (for an alternative: its second effect)
  FitOutcome fit;
  bool alternative = false;  ///< a pair of round-1 effects replacing the model
  bool earned = false;
};

}  // namespace

std::string implausibility(Effect e, std::span<const double> params) {
  const auto& info = effect_info(e);
  bool all_null = true;
  for (std::size_t i = 0; i < info.params.size(); ++i) {
    const auto& p = info.params[i];
    const double range = p.upper - p.lower;
    const double v = params[i];
    if (std::fabs(v - p.null_value) > kAtBoundFraction * range) all_null = false;
    const bool at_lower = v - p.lower <= kAtBoundFraction * range;
    const bool at_upper = p.upper - v <= kAtBoundFraction * range;
    if (at_lower && p.lower != p.null_value) {
      return std::string(p.name) + " pinned at its lower physical bound " + fmt("%g", p.lower);
    }
    if (at_upper && !p.upper_bound_physical && p.upper != p.null_value) {
      return std::string(p.name) + " pinned at its upper physical bound " + fmt("%g", p.upper);
    }
  }
  if (all_null) return "not identified: the fit returns the effect's null value";
  return {};
}

DiscrepancyResult run_discrepancy(const MeasuredData& data, const DiscrepancyOptions& opt) {
  DiscrepancyResult res;
  const DamperModel model(model_input(data, opt.smoothing_half_window_s));
  res.velocity_derived = model.input().velocity_derived;
  const FitData fd = make_fit_data(model, data.force_n, opt.fit_samples);
  res.fit_samples = fd.index.size();
  res.fit_stride = fd.index.size() > 1 ? fd.index[1] - fd.index[0] : 1;

  EffectSet current;
  std::vector<double> current_params;
  ModelWorkspace ws;
  std::vector<double> base_residual;
  double current_rss = fit_rss(fd, current, current_params, ws, &base_residual);
  std::vector<double> fit_times(fd.index.size());
  for (std::size_t r = 0; r < fit_times.size(); ++r) fit_times[r] = data.time_s[fd.index[r]];
  res.n_eff_baseline = noise_effective_samples(fit_times, base_residual);

  // Forward selection.
  std::vector<Trial> first_round;
  while (current.effects.size() < opt.max_effects) {
    RoundResult round;
    round.model = current.effects;
    round.gap = gap_on_fit(fd, current_rss);
    std::vector<Effect> todo;
    for (const Effect e : opt.catalogue) {
      if (!current.contains(e)) todo.push_back(e);
    }
    if (todo.empty()) break;
    std::vector<FitOutcome> fits(todo.size());
    parallel_for(todo.size(), opt.threads, [&](std::size_t i) {
      EffectSet s = current;
      s.effects.push_back(todo[i]);
      fits[i] = fit_effects(fd, s, carry_params(s, current, current_params), &todo[i]);
    });
    // Next to effects already in the model, whose values may have absorbed
    // part of the new one, the valleys of two effects that act alike (such
    // as backlash and delay) hold local minima: the two best candidates are
    // fitted again from their three best starting points.
    if (!current.effects.empty()) {
      std::vector<std::size_t> order(todo.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::stable_sort(order.begin(), order.end(),
                       [&](std::size_t a, std::size_t b) { return fits[a].rss_n2 < fits[b].rss_n2; });
      order.resize(std::min<std::size_t>(order.size(), kRefitted));
      parallel_for(order.size(), opt.threads, [&](std::size_t j) {
        const std::size_t i = order[j];
        EffectSet s = current;
        s.effects.push_back(todo[i]);
        FitOutcome f = fit_effects(fd, s, carry_params(s, current, current_params), &todo[i], kStarts);
        if (f.rss_n2 < fits[i].rss_n2) fits[i] = std::move(f);
      });
    }
    std::vector<Trial> trials;
    for (std::size_t i = 0; i < todo.size(); ++i) trials.push_back({todo[i], std::move(fits[i]), false});

    // Round 2 also weighs pairs of the other effects earned in round 1: one
    // effect can mimic two others better than either alone (a delay looks
    // like free play plus a spring on a sine), and greedy addition would
    // then never reach the pair.
    if (current.effects.size() == 1 && !first_round.empty()) {
      std::vector<const Trial*> sources;
      for (const Trial& t : first_round) {
        if (t.earned && t.effect != current.effects[0] && sources.size() < kAlternativeSources) sources.push_back(&t);
      }
      std::vector<Trial> alts;
      for (std::size_t a = 0; a < sources.size(); ++a) {
        for (std::size_t b = a + 1; b < sources.size(); ++b) {
          EffectSet pair{{sources[a]->effect, sources[b]->effect}};
          std::vector<double> start = sources[a]->fit.params;
          start.insert(start.end(), sources[b]->fit.params.begin(), sources[b]->fit.params.end());
          alts.push_back({sources[b]->effect, FitOutcome{pair, start, 0.0, 0.0, 0, false}, true});
        }
      }
      parallel_for(alts.size(), opt.threads, [&](std::size_t i) {
        alts[i].fit = fit_effects(fd, alts[i].fit.set, alts[i].fit.params, nullptr);
      });
      for (auto& t : alts) trials.push_back(std::move(t));
    }

    // One effective sample count for the whole round, so that the scores
    // compare like with like: that of the best-fitting plausible candidate,
    // whose residual is the best available estimate of the noise.
    std::vector<std::string> why(trials.size());
    std::optional<std::size_t> lowest;
    for (std::size_t i = 0; i < trials.size(); ++i) {
      const FitOutcome& f = trials[i].fit;
      for (const Effect e : f.set.effects) {
        const std::string w = implausibility(e, own_params(f.set, f.params, e));
        if (w.empty()) continue;
        if (trials[i].alternative) {
          why[i] = std::string(effect_name(e)) + ": " + w;
        } else if (e == trials[i].effect) {
          why[i] = w;
        } else {
          why[i] = "makes " + std::string(effect_name(e)) + " implausible: " + w;
        }
        break;
      }
      if (why[i].empty() && (!lowest || f.rss_n2 < trials[*lowest].fit.rss_n2)) lowest = i;
    }
    const double n_eff = lowest ? trials[*lowest].fit.n_eff : res.n_eff_baseline;
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < trials.size(); ++i) {
      Trial& t = trials[i];
      const FitOutcome& f = t.fit;
      CandidateResult c;
      c.effect = t.effect;
      c.model = f.set.effects;
      c.alternative = t.alternative;
      c.all_params = f.params;
      c.params = own_params(f.set, f.params, t.effect);
      c.n_eff = n_eff;
      c.rss_reduction = current_rss > 0.0 ? 1.0 - f.rss_n2 / current_rss : 0.0;
      const double added_k =
          static_cast<double>(f.set.param_count()) - static_cast<double>(current.param_count());
      c.delta_bic = n_eff * std::log(std::max(current_rss, 1e-300) / std::max(f.rss_n2, 1e-300)) -
                    added_k * std::log(std::max(n_eff, 1.0));
      c.gap = gap_on_fit(fd, f.rss_n2);
      c.plausible = why[i].empty();
      const std::string prefix = t.alternative ? "alternative model " + f.set.label() + ": " : "";
      if (!c.plausible) {
        c.verdict = prefix + "implausible: " + why[i];
      } else if (c.delta_bic < opt.min_delta_bic) {
        c.verdict = prefix + "not earned: delta BIC " + fmt("%.1f", c.delta_bic) + " < " + fmt("%g", opt.min_delta_bic);
      } else if (c.rss_reduction < opt.min_rss_reduction) {
        c.verdict = prefix + "not earned: removes " + fmt("%.1f", 100.0 * c.rss_reduction) +
                    " % of the residual power, < " + fmt("%g", 100.0 * opt.min_rss_reduction) + " %";
      } else {
        c.verdict = prefix + "earned";
        t.earned = true;
        if (!best || c.delta_bic > round.candidates[*best].delta_bic) best = round.candidates.size();
      }
      round.candidates.push_back(std::move(c));
    }
    if (current.effects.empty()) {
      // Round 1's fits, best first, are the sources of round 2's alternatives.
      first_round = std::move(trials);
      std::stable_sort(first_round.begin(), first_round.end(),
                       [](const Trial& a, const Trial& b) { return a.fit.rss_n2 < b.fit.rss_n2; });
    }
    if (!best) {
      res.rounds.push_back(std::move(round));
      break;
    }
    CandidateResult& win = round.candidates[*best];
    win.chosen = true;
    win.verdict = win.alternative ? "chosen: alternative model " + EffectSet{win.model}.label() : "chosen";
    round.chosen = win.effect;
    round.model_after = win.model;
    current.effects = win.model;
    current_params = win.all_params;
    current_rss = fit_rss(fd, current, current_params, ws);
    res.rounds.push_back(std::move(round));
  }

  // Backward check: drop an effect the others make unnecessary.
  while (current.effects.size() >= 2) {
    std::optional<std::size_t> weakest;
    double weakest_score = 0.0;
    FitOutcome weakest_fit;
    std::vector<double> resid;
    (void)fit_rss(fd, current, current_params, ws, &resid);
    const double n_eff = noise_effective_samples(fit_times, resid);
    for (std::size_t i = 0; i < current.effects.size(); ++i) {
      EffectSet s = current;
      s.effects.erase(s.effects.begin() + static_cast<std::ptrdiff_t>(i));
      FitOutcome f = fit_effects(fd, s, carry_params(s, current, current_params));
      const double k = static_cast<double>(effect_info(current.effects[i]).params.size());
      const double score = n_eff * std::log(std::max(f.rss_n2, 1e-300) / std::max(current_rss, 1e-300)) -
                           k * std::log(std::max(n_eff, 1.0));
      const double reduction = f.rss_n2 > 0.0 ? 1.0 - current_rss / f.rss_n2 : 0.0;
      const bool earned = score >= opt.min_delta_bic && reduction >= opt.min_rss_reduction;
      if (!earned && (!weakest || score < weakest_score)) {
        weakest = i;
        weakest_score = score;
        weakest_fit = std::move(f);
      }
    }
    if (!weakest) break;
    res.dropped.push_back(current.effects[*weakest]);
    current = weakest_fit.set;
    current_params = weakest_fit.params;
    current_rss = weakest_fit.rss_n2;
  }

  res.effects = current.effects;
  res.params = current_params;

  // Full-rate traces, gaps and localization.
  model.simulate(EffectSet{}, {}, ws, res.baseline_force_n);
  model.simulate(current, current_params, ws, res.updated_force_n);
  res.gap_before = normalized_rms_gap(data.force_n, res.baseline_force_n);
  res.gap_after = normalized_rms_gap(data.force_n, res.updated_force_n);
  res.disp_m = model.input().disp_m;
  res.vel_m_s = model.input().vel_m_s;
  res.coil_current_a = model.baseline_current_a();
  const ResidualTraces tr{data.time_s,  res.disp_m,          res.vel_m_s,           data.current_cmd_a,
                          res.coil_current_a, data.force_n, res.baseline_force_n, res.updated_force_n};
  res.regions = localize_regions(tr, model.params().bingham.v_tf_m_s);
  res.windows = localize_time(tr);
  return res;
}

}  // namespace mrd::discrepancy
