#include "host_sim/discrepancy/workflow.hpp"

#include <algorithm>
#include <cmath>

#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/discrepancy/fit.hpp"
#include "host_sim/discrepancy/parallel.hpp"
#include "host_sim/io/text.hpp"

namespace mrd::discrepancy {
namespace {

/// A parameter within this fraction of its range of a bound counts as at it.
constexpr double kAtBoundFraction = 2e-3;
/// A parameter within this fraction of its range of its null value counts as
/// null. Finer than kAtBoundFraction: a free play's range is 10 mm and a play
/// of 15 µm, resolved by a 1 µm displacement sensor, is a real finding (at
/// 2e-3 it would read as 20 µm of nothing); whether a small value earns its
/// place is the BIC's and the held-out samples' judgement.
constexpr double kNullFraction = 1e-4;
/// Candidates refitted from several starting points in rounds after the first.
constexpr std::size_t kRefitted = 2;
constexpr std::size_t kStarts = 3;
/// Effects whose other forms are fitted in a round: those of the best
/// fits in their first form (other_forms).
constexpr std::size_t kFormCandidates = 2;
/// Round-1 effects (earned, best first, other than the round-1 winner) whose
/// pairs round 2 weighs as alternative models.
constexpr std::size_t kAlternativeSources = 3;

using io::format_number;

/// Parameters of effect `e` inside a packed vector for `set`.
std::vector<double> own_params(const EffectSet& set, std::span<const double> all, Effect e) {
  const auto off = set.offset(e);
  const std::size_t k = set.params_of(e).size();
  return {all.begin() + static_cast<std::ptrdiff_t>(*off), all.begin() + static_cast<std::ptrdiff_t>(*off + k)};
}

/// Packed start values for `set` from a fitted vector of `from` (effects
/// missing there at their null values).
std::vector<double> carry_params(const EffectSet& set, const EffectSet& from, std::span<const double> from_params) {
  std::vector<double> p = set.null_params();
  for (const Effect e : set.effects) {
    if (const auto src = from.offset(e); src && from.form(e) == set.form(e)) {
      const auto dst = set.offset(e);
      for (std::size_t i = 0; i < set.params_of(e).size(); ++i) p[*dst + i] = from_params[*src + i];
    }
  }
  return p;
}

double gap_on_fit(const FitData& d, double rss) {
  double ss = 0.0;
  for (const std::size_t k : d.index) ss += d.measured_force_n[k] * d.measured_force_n[k];
  return ss > 0.0 ? std::sqrt(rss / ss) : 0.0;
}

/// A fitted trial model of one round.
struct Trial {
  Effect effect{};           ///< the effect it adds (for an alternative: its second effect)
  FitOutcome fit;
  bool alternative = false;  ///< a pair of round-1 effects replacing the model
  bool earned = false;
};

}  // namespace

std::string implausibility(Effect e, std::span<const double> params, const ParamScale& scale, std::size_t form) {
  const auto info_params = form_params(e, form);
  bool all_null = true;
  for (std::size_t i = 0; i < info_params.size(); ++i) {
    const ParamInfo p = scaled_param(info_params[i], scale);
    const double range = p.upper - p.lower;
    const double v = params[i];
    if (std::fabs(v - p.null_value) > kNullFraction * range) all_null = false;
    const bool at_lower = v - p.lower <= kAtBoundFraction * range;
    const bool at_upper = p.upper - v <= kAtBoundFraction * range;
    if (at_lower && p.lower != p.null_value) {
      return std::string(p.name) + " pinned at its lower physical bound " + format_number("%g", p.lower);
    }
    if (at_upper && !p.upper_bound_physical && p.upper != p.null_value) {
      return std::string(p.name) + " pinned at its upper physical bound " + format_number("%g", p.upper);
    }
  }
  if (all_null && form_has_null(e, form)) return "not identified: the fit returns the effect's null value";
  if (e == Effect::backlash && form == kBacklashImpactSpring && params.size() >= 2 &&
      params[1] > kMaxStopDeflectionPerPlay * params[0]) {
    return "the contact spring deflects " + format_number("%.3g", params[1]) + " m, more than " +
           format_number("%g", kMaxStopDeflectionPerPlay) + " times the free play of " +
           format_number("%.3g", params[0]) + " m: a compliance in series, not a free play";
  }
  return {};
}

std::vector<std::string> bound_flags(Effect e, std::span<const double> params, const ParamScale& scale,
                                     std::size_t form) {
  const auto info_params = form_params(e, form);
  std::vector<std::string> flags(info_params.size());
  for (std::size_t i = 0; i < info_params.size(); ++i) {
    const ParamInfo p = scaled_param(info_params[i], scale);
    const double range = p.upper - p.lower;
    const double v = params[i];
    if (v - p.lower <= kAtBoundFraction * range && p.lower != p.null_value) {
      flags[i] = "at its lower bound " + format_number("%g", p.lower);
    } else if (p.upper - v <= kAtBoundFraction * range && p.upper != p.null_value) {
      flags[i] = "at its upper bound " + format_number("%g", p.upper) +
                 (p.upper_bound_physical ? " (a physical state, accepted)" : "");
    }
  }
  return flags;
}

std::string offset_wander(std::span<const double> time_s, std::span<const double> residual_n, double offset_n) {
  const std::size_t n = std::min(time_s.size(), residual_n.size());
  if (n < 2 * kOffsetBlocks) return {};
  const double t0 = time_s[0];
  const double span_s = std::max(time_s[n - 1] - t0, 1e-12);
  std::vector<double> sum(kOffsetBlocks, 0.0), count(kOffsetBlocks, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const auto b = std::min(kOffsetBlocks - 1, static_cast<std::size_t>((time_s[k] - t0) / span_s * kOffsetBlocks));
    sum[b] += residual_n[k] + offset_n;
    count[b] += 1.0;
  }
  std::vector<double> means;
  for (std::size_t b = 0; b < kOffsetBlocks; ++b) {
    if (count[b] > 0.0) means.push_back(sum[b] / count[b]);
  }
  if (means.size() < 3) return {};
  const auto m = static_cast<double>(means.size());
  double mean = 0.0;
  for (const double x : means) mean += x / m;
  double var = 0.0;
  for (const double x : means) var += (x - mean) * (x - mean) / (m - 1.0);
  const double se = std::sqrt(var / m);
  if (std::fabs(offset_n) >= kOffsetBlockT * se) return {};
  return "offset " + format_number("%.4g", offset_n) + " N is within " + format_number("%g", kOffsetBlockT) +
         " standard errors (" + format_number("%.3g", se) + " N) of the means of " + std::to_string(means.size()) +
         " spans of the record, which wander: the slow part of the noise, not a zero offset";
}

const char* verdict_name(Verdict v) noexcept {
  switch (v) {
    case Verdict::none: return "none";
    case Verdict::explained: return "explained";
    case Verdict::unexplained: return "unexplained";
    case Verdict::baseline_mismatch: return "baseline_mismatch";
  }
  return "none";
}

namespace {

/// A model whose RMS force falls below this share of the baseline's has
/// collapsed: the effect has switched the damper off rather than changed it.
/// A tenth: the most settled damper of chapter 5 starts at PR = 0.101
/// (Eq. 5.6 at SQ = 1, b_initial = 0.1 of Table 5.6) and Y(i, PR) ≥ PR·Y(i, 1),
/// so a settled damper keeps at least a tenth of its force at every sample;
/// a weaker model is not a damper any catalogued effect describes.
constexpr double kCollapsedForceShare = 0.1;
/// Explained: the structure the effects leave on the held-out samples is at
/// most kLeftOverNoise of the noise there (the rest of the residual), or at
/// most kLeftOverRemoved of what they removed.
constexpr double kLeftOverNoise = 0.25;
constexpr double kLeftOverRemoved = 0.05;
/// A held-out gap within this factor of the baseline's expected gap is no discrepancy.
constexpr double kExpectedGapFactor = 1.25;
/// A residual whose RMS (N) on the fit samples is at least this factor above
/// that on the held-out samples is not noise: noise over thousands of samples
/// differs between the parts by a few per cent, and the error of a velocity
/// derived from a noisy LVDT, which gathers at reversals, gave 1.6× on a
/// clean 8 s record (mrd synth --seed 4); a structure nine times the noise's
/// power that the held-out blocks miss is well above both.
constexpr double kUnsampledRmsRatio = 3.0;

/// The model the selection has reached: its effects, their fitted
/// parameters (packed) and its RSS on the fit samples.
struct Selection {
  EffectSet set;
  std::vector<double> params;
  double rss = 0.0;
  double rss_held = 0.0;  ///< on the held-out samples
};

/// What every step of the selection reads.
struct SelectionContext {
  const FitData& fd;
  const FitData& held;                  ///< the held-out samples, full rate
  std::span<const double> fit_times_s;  ///< times of the fit samples
  const DiscrepancyOptions& opt;
  double n_eff_baseline = 0.0;
  double stroke_m = 0.0;                ///< peak-to-peak actuator displacement
  double baseline_rms_n = 0.0;          ///< RMS baseline force on the fit samples
};

/// Why a fitted model is rejected as a damper that is no longer there (empty when it is not).
std::string collapse_reason(const SelectionContext& ctx, const FitOutcome& f) {
  if (const auto off = f.set.offset(Effect::backlash)) {
    const double play_m = f.params[*off];
    if (play_m >= ctx.stroke_m) {
      return "collapses: free play " + format_number("%.3g", play_m) + " m is at least the record's stroke " +
             format_number("%.3g", ctx.stroke_m) + " m";
    }
  }
  ModelWorkspace ws;
  std::vector<double> resid;
  (void)fit_rss(ctx.fd, f.set, f.params, ws, &resid);
  double ss = 0.0;
  for (std::size_t r = 0; r < resid.size(); ++r) {
    const double model = ctx.fd.measured_force_n[ctx.fd.index[r]] - resid[r];
    ss += model * model;
  }
  const double rms = resid.empty() ? 0.0 : std::sqrt(ss / static_cast<double>(resid.size()));
  if (rms < kCollapsedForceShare * ctx.baseline_rms_n) {
    return "collapses: the model's RMS force " + format_number("%.3g", rms) + " N is below a tenth of the baseline's " +
           format_number("%.3g", ctx.baseline_rms_n) + " N";
  }
  return {};
}

/// An effect with several physical forms (EffectInfo::forms: a coil of one
/// time constant, a settled layer that recovers fully, ...) is fitted in
/// each of its other forms: in the first round always (a first form the
/// data do not follow may not fit at all, as Eq. 4.5's slow branch does not
/// a single lag of a third of its time constant), in later rounds when its
/// first form is among the kFormCandidates best fits of the round, from
/// the best start of its grid (runtime: a form adds one local fit). The form kept is the one with
/// the lower BIC (one effective sample count, that of the first form's
/// residual; a form with more parameters pays for them) among the plausible
/// ones (implausibility).
void other_forms(const SelectionContext& ctx, const Selection& current, const std::vector<Effect>& todo,
                 std::vector<FitOutcome>& fits) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < todo.size(); ++i) order.push_back(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return fits[a].rss_n2 < fits[b].rss_n2; });
  if (!current.set.effects.empty() && order.size() > kFormCandidates)
    order.erase(order.begin() + static_cast<std::ptrdiff_t>(kFormCandidates), order.end());
  struct Job {
    std::size_t trial;
    std::uint8_t form;
  };
  std::vector<Job> jobs;
  for (const std::size_t i : order) {
    const auto& forms = effect_info(todo[i]).forms;
    for (std::size_t f = 1; f < forms.size(); ++f) jobs.push_back({i, static_cast<std::uint8_t>(f)});
  }
  if (jobs.empty()) return;
  std::vector<FitOutcome> alt(jobs.size());
  parallel_for(jobs.size(), ctx.opt.threads, [&](std::size_t j) {
    EffectSet s = current.set;
    s.effects.push_back(todo[jobs[j].trial]);
    s.forms[static_cast<std::size_t>(todo[jobs[j].trial])] = jobs[j].form;
    alt[j] = fit_effects(ctx.fd, s, carry_params(s, current.set, current.params), &todo[jobs[j].trial]);
  });
  const auto n = static_cast<std::size_t>(ctx.fd.index.size());
  const ParamScale scale = ctx.fd.model->param_scale();
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    FitOutcome& now = fits[jobs[j].trial];
    // A form whose fit is implausible (a contact spring with no play to speak of) does not replace the first.
    const Effect e = todo[jobs[j].trial];
    if (!implausibility(e, own_params(alt[j].set, alt[j].params, e), scale, jobs[j].form).empty()) continue;
    const double n_eff = std::max(now.n_eff, 1.0);
    if (bic(alt[j].rss_n2, n, n_eff, alt[j].set.param_count()) < bic(now.rss_n2, n, n_eff, now.set.param_count()))
      now = std::move(alt[j]);
  }
}

/// Fits the model plus each effect of `todo`. In rounds after the first,
/// next to effects already in the model, whose values may have absorbed
/// part of the new one, the valleys of two effects that act alike (such as
/// backlash and delay) hold local minima: the two best candidates are
/// fitted again from their three best starting points.
std::vector<Trial> forward_trials(const SelectionContext& ctx, const Selection& current,
                                  const std::vector<Effect>& todo) {
  std::vector<FitOutcome> fits(todo.size());
  parallel_for(todo.size(), ctx.opt.threads, [&](std::size_t i) {
    EffectSet s = current.set;
    s.effects.push_back(todo[i]);
    fits[i] = fit_effects(ctx.fd, s, carry_params(s, current.set, current.params), &todo[i]);
  });
  if (!current.set.effects.empty()) {
    std::vector<std::size_t> order(todo.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return fits[a].rss_n2 < fits[b].rss_n2; });
    order.resize(std::min<std::size_t>(order.size(), kRefitted));
    parallel_for(order.size(), ctx.opt.threads, [&](std::size_t j) {
      const std::size_t i = order[j];
      EffectSet s = current.set;
      s.effects.push_back(todo[i]);
      FitOutcome f = fit_effects(ctx.fd, s, carry_params(s, current.set, current.params), &todo[i], kStarts);
      if (f.rss_n2 < fits[i].rss_n2) fits[i] = std::move(f);
    });
  }
  other_forms(ctx, current, todo, fits);
  std::vector<Trial> trials;
  for (std::size_t i = 0; i < todo.size(); ++i) trials.push_back({todo[i], std::move(fits[i]), false});
  return trials;
}

/// Round 2's alternatives: pairs of the effects other than the round-1
/// winner that round 1 found earned (up to kAlternativeSources, best
/// first). One effect can mimic two others better than either alone (a
/// delay looks like free play plus a spring on a sine), and greedy addition
/// would then never reach the pair.
std::vector<Trial> alternative_trials(const SelectionContext& ctx, const Selection& current,
                                      const std::vector<Trial>& first_round) {
  std::vector<const Trial*> sources;
  for (const Trial& t : first_round) {
    if (t.earned && t.effect != current.set.effects[0] && sources.size() < kAlternativeSources) sources.push_back(&t);
  }
  std::vector<Trial> alts;
  for (std::size_t a = 0; a < sources.size(); ++a) {
    for (std::size_t b = a + 1; b < sources.size(); ++b) {
      EffectSet pair{{sources[a]->effect, sources[b]->effect}};
      pair.forms[static_cast<std::size_t>(sources[a]->effect)] = sources[a]->fit.set.forms[static_cast<std::size_t>(sources[a]->effect)];
      pair.forms[static_cast<std::size_t>(sources[b]->effect)] = sources[b]->fit.set.forms[static_cast<std::size_t>(sources[b]->effect)];
      std::vector<double> start = sources[a]->fit.params;
      start.insert(start.end(), sources[b]->fit.params.begin(), sources[b]->fit.params.end());
      alts.push_back({sources[b]->effect, FitOutcome{pair, start, 0.0, 0.0, 0, false}, true});
    }
  }
  parallel_for(alts.size(), ctx.opt.threads, [&](std::size_t i) {
    alts[i].fit = fit_effects(ctx.fd, alts[i].fit.set, alts[i].fit.params, nullptr);
  });
  return alts;
}

/// Why each trial is implausible (empty when it is plausible): the first
/// effect of its model whose fitted parameters are.
std::vector<std::string> implausibility_reasons(const SelectionContext& ctx, const std::vector<Trial>& trials) {
  std::vector<std::string> why(trials.size());
  const ParamScale scale = ctx.fd.model->param_scale();
  for (std::size_t i = 0; i < trials.size(); ++i) {
    const FitOutcome& f = trials[i].fit;
    why[i] = collapse_reason(ctx, f);
    if (!why[i].empty()) continue;
    if (const auto off = f.set.offset(Effect::force_offset)) {
      ModelWorkspace ws;
      std::vector<double> resid;
      (void)fit_rss(ctx.fd, f.set, f.params, ws, &resid);
      const std::string w = offset_wander(ctx.fit_times_s, resid, f.params[*off]);
      if (!w.empty()) {
        if (trials[i].alternative) {
          why[i] = std::string("force_offset: ").append(w);
        } else if (trials[i].effect == Effect::force_offset) {
          why[i] = w;
        } else {
          why[i] = std::string("makes force_offset implausible: ").append(w);
        }
        continue;
      }
    }
    for (const Effect e : f.set.effects) {
      const std::string w = implausibility(e, own_params(f.set, f.params, e), scale, f.set.form(e));
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
  }
  return why;
}

/// One effective sample count for the whole round, so that the scores
/// compare like with like: that of the best-fitting plausible trial, whose
/// residual is the best available estimate of the noise (the baseline's
/// when no trial is plausible).
double round_n_eff(const std::vector<Trial>& trials, const std::vector<std::string>& why, double n_eff_baseline) {
  std::optional<std::size_t> lowest;
  for (std::size_t i = 0; i < trials.size(); ++i) {
    if (why[i].empty() && (!lowest || trials[i].fit.rss_n2 < trials[*lowest].fit.rss_n2)) lowest = i;
  }
  return lowest ? trials[*lowest].fit.n_eff : n_eff_baseline;
}

/// Scores a trial against the model so far (ΔBIC, share of the residual
/// power removed) and gives the verdict; marks the trial earned.
CandidateResult score_trial(const SelectionContext& ctx, const Selection& current, Trial& t, const std::string& why,
                            double n_eff) {
  const FitOutcome& f = t.fit;
  CandidateResult c;
  c.effect = t.effect;
  c.model = f.set.effects;
  c.forms = f.set.forms;
  c.alternative = t.alternative;
  c.all_params = f.params;
  c.params = own_params(f.set, f.params, t.effect);
  c.flags = bound_flags(t.effect, c.params, ctx.fd.model->param_scale(), f.set.form(t.effect));
  c.n_eff = n_eff;
  c.rss_reduction = current.rss > 0.0 ? 1.0 - f.rss_n2 / current.rss : 0.0;
  ModelWorkspace ws;
  const double rss_held = fit_rss(ctx.held, f.set, f.params, ws);
  c.held_out_reduction = current.rss_held > 0.0 ? 1.0 - rss_held / current.rss_held : 0.0;
  const double added_k = static_cast<double>(f.set.param_count()) - static_cast<double>(current.set.param_count());
  c.delta_bic = n_eff * std::log(std::max(current.rss, 1e-300) / std::max(f.rss_n2, 1e-300)) -
                added_k * std::log(std::max(n_eff, 1.0));
  c.gap = gap_on_fit(ctx.fd, f.rss_n2);
  c.plausible = why.empty();
  const std::string prefix = t.alternative ? "alternative model " + f.set.label() + ": " : "";
  const double min_bic = ctx.opt.min_delta_bic;
  const double min_reduction = ctx.opt.min_rss_reduction;
  if (!c.plausible) {
    c.verdict = prefix + "implausible: " + why;
  } else if (c.delta_bic < min_bic) {
    c.verdict = prefix + "not earned: delta BIC " + format_number("%.1f", c.delta_bic) + " < " +
                format_number("%g", min_bic);
  } else if (c.rss_reduction < min_reduction) {
    c.verdict = prefix + "not earned: removes " + format_number("%.1f", 100.0 * c.rss_reduction) +
                " % of the residual power, < " + format_number("%g", 100.0 * min_reduction) + " %";
  } else if (c.held_out_reduction < min_reduction) {
    c.verdict = prefix + "does not generalize: removes " + format_number("%.1f", 100.0 * c.held_out_reduction) +
                " % of the held-out residual power, < " + format_number("%g", 100.0 * min_reduction) + " %";
  } else {
    c.verdict = prefix + "earned";
    t.earned = true;
  }
  return c;
}

/// Scores every trial into `round.candidates`; the index of the earned
/// candidate with the highest ΔBIC, if any.
std::optional<std::size_t> score_round(const SelectionContext& ctx, const Selection& current,
                                       std::vector<Trial>& trials, RoundResult& round) {
  const std::vector<std::string> why = implausibility_reasons(ctx, trials);
  const double n_eff = round_n_eff(trials, why, ctx.n_eff_baseline);
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < trials.size(); ++i) {
    CandidateResult c = score_trial(ctx, current, trials[i], why[i], n_eff);
    if (trials[i].earned && (!best || c.delta_bic > round.candidates[*best].delta_bic)) best = round.candidates.size();
    round.candidates.push_back(std::move(c));
  }
  return best;
}

/// Greedy forward selection: one round per added effect, until no
/// candidate earns its parameters or max_effects is reached.
void forward_selection(const SelectionContext& ctx, Selection& current, ModelWorkspace& ws,
                       std::vector<RoundResult>& rounds) {
  std::vector<Trial> first_round;
  while (current.set.effects.size() < ctx.opt.max_effects) {
    RoundResult round;
    round.model = current.set.effects;
    round.gap = gap_on_fit(ctx.fd, current.rss);
    std::vector<Effect> todo;
    for (const Effect e : ctx.opt.catalogue) {
      if (!current.set.contains(e)) todo.push_back(e);
    }
    if (todo.empty()) break;
    std::vector<Trial> trials = forward_trials(ctx, current, todo);
    if (current.set.effects.size() == 1 && !first_round.empty()) {
      for (auto& t : alternative_trials(ctx, current, first_round)) trials.push_back(std::move(t));
    }
    const std::optional<std::size_t> best = score_round(ctx, current, trials, round);
    if (current.set.effects.empty()) {
      // Round 1's fits, best first, are the sources of round 2's alternatives.
      first_round = std::move(trials);
      std::stable_sort(first_round.begin(), first_round.end(),
                       [](const Trial& a, const Trial& b) { return a.fit.rss_n2 < b.fit.rss_n2; });
    }
    if (!best) {
      rounds.push_back(std::move(round));
      break;
    }
    CandidateResult& win = round.candidates[*best];
    win.chosen = true;
    win.verdict = win.alternative ? "chosen: alternative model " + EffectSet{win.model}.label() : "chosen";
    round.chosen = win.effect;
    round.model_after = win.model;
    current.set.effects = win.model;
    current.set.forms = win.forms;
    current.params = win.all_params;
    current.rss = fit_rss(ctx.fd, current.set, current.params, ws);
    current.rss_held = fit_rss(ctx.held, current.set, current.params, ws);
    rounds.push_back(std::move(round));
  }
}

/// Refits, once the forward selection has added effects beside it, the form
/// of each effect in the model that has several (EffectInfo::forms): its form
/// was chosen against the model of its own round, and an effect added later
/// may have taken up what told the forms apart (a gas spring's force at the
/// ends of the stroke beside free play, whose form was chosen without it).
/// Each other
/// form is fitted with the whole model, from the current values of the other
/// effects and the best start of its own grid; the form kept is the one with
/// the lower BIC (the current residual's effective sample count) among the
/// plausible ones. The backward check that follows then judges whether each
/// later effect still earns its place beside the refitted form.
void refit_forms(const SelectionContext& ctx, Selection& current, ModelWorkspace& ws,
                 std::vector<std::string>& findings) {
  if (current.set.effects.size() < 2) return;
  struct Job {
    Effect effect;
    std::uint8_t form;
  };
  std::vector<Job> jobs;
  for (const Effect e : current.set.effects) {
    const auto& forms = effect_info(e).forms;
    for (std::size_t f = 0; f < forms.size(); ++f) {
      if (f != current.set.form(e)) jobs.push_back({e, static_cast<std::uint8_t>(f)});
    }
  }
  if (jobs.empty()) return;
  std::vector<FitOutcome> alt(jobs.size());
  parallel_for(jobs.size(), ctx.opt.threads, [&](std::size_t j) {
    EffectSet s = current.set;
    s.forms[static_cast<std::size_t>(jobs[j].effect)] = jobs[j].form;
    alt[j] = fit_effects(ctx.fd, s, carry_params(s, current.set, current.params), &jobs[j].effect);
  });
  std::vector<double> resid;
  (void)fit_rss(ctx.fd, current.set, current.params, ws, &resid);
  const double n_eff = std::max(noise_effective_samples(ctx.fit_times_s, resid), 1.0);
  const auto n = static_cast<std::size_t>(ctx.fd.index.size());
  const ParamScale scale = ctx.fd.model->param_scale();
  double best_bic = bic(current.rss, n, n_eff, current.set.param_count());
  std::optional<std::size_t> best;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    const Effect e = jobs[j].effect;
    if (!implausibility(e, own_params(alt[j].set, alt[j].params, e), scale, jobs[j].form).empty()) continue;
    if (!collapse_reason(ctx, alt[j]).empty()) continue;
    const double b = bic(alt[j].rss_n2, n, n_eff, alt[j].set.param_count());
    if (b < best_bic) {
      best_bic = b;
      best = j;
    }
  }
  if (!best) return;
  const Effect e = jobs[*best].effect;
  findings.push_back(std::string(effect_name(e)) + " refitted beside the effects added after it: its " +
                     std::string(form_name(e, jobs[*best].form)) + " form fits the whole model better than its " +
                     std::string(form_name(e, current.set.form(e))) + " form (BIC lower by " +
                     format_number("%.1f", bic(current.rss, n, n_eff, current.set.param_count()) - best_bic) + ").");
  FitOutcome& f = alt[*best];
  current = Selection{f.set, f.params, f.rss_n2, fit_rss(ctx.held, f.set, f.params, ws)};
}

/// Backward check: drops, one at a time, the effect whose removal costs the
/// least when the others then explain the data without it (its ΔBIC or its
/// share of the residual power below the thresholds).
void backward_check(const SelectionContext& ctx, Selection& current, ModelWorkspace& ws,
                    std::vector<Effect>& dropped) {
  while (current.set.effects.size() >= 2) {
    std::optional<std::size_t> weakest;
    double weakest_score = 0.0;
    FitOutcome weakest_fit;
    std::vector<double> resid;
    (void)fit_rss(ctx.fd, current.set, current.params, ws, &resid);
    const double n_eff = noise_effective_samples(ctx.fit_times_s, resid);
    for (std::size_t i = 0; i < current.set.effects.size(); ++i) {
      EffectSet s = current.set;
      s.effects.erase(s.effects.begin() + static_cast<std::ptrdiff_t>(i));
      FitOutcome f = fit_effects(ctx.fd, s, carry_params(s, current.set, current.params));
      const double k = static_cast<double>(current.set.params_of(current.set.effects[i]).size());
      const double score = n_eff * std::log(std::max(f.rss_n2, 1e-300) / std::max(current.rss, 1e-300)) -
                           k * std::log(std::max(n_eff, 1.0));
      const double reduction = f.rss_n2 > 0.0 ? 1.0 - current.rss / f.rss_n2 : 0.0;
      const bool earned = score >= ctx.opt.min_delta_bic && reduction >= ctx.opt.min_rss_reduction;
      if (!earned && (!weakest || score < weakest_score)) {
        weakest = i;
        weakest_score = score;
        weakest_fit = std::move(f);
      }
    }
    if (!weakest) break;
    dropped.push_back(current.set.effects[*weakest]);
    current = Selection{weakest_fit.set, weakest_fit.params, weakest_fit.rss_n2,
                        fit_rss(ctx.held, weakest_fit.set, weakest_fit.params, ws)};
  }
}

/// A force_offset left in the model after the backward check is judged as
/// in the rounds (offset_wander): the effect it was chosen beside may have
/// held the slow part of the noise that made it look constant, and without
/// that effect it can wander again. A wandering offset is then dropped too,
/// the rest refitted.
void drop_wandering_offset(const SelectionContext& ctx, Selection& current, ModelWorkspace& ws,
                           std::vector<Effect>& dropped, std::vector<std::string>& findings) {
  const auto off = current.set.offset(Effect::force_offset);
  if (!off) return;
  std::vector<double> resid;
  (void)fit_rss(ctx.fd, current.set, current.params, ws, &resid);
  const std::string w = offset_wander(ctx.fit_times_s, resid, current.params[*off]);
  if (w.empty()) return;
  EffectSet s = current.set;
  s.effects.erase(std::find(s.effects.begin(), s.effects.end(), Effect::force_offset));
  FitOutcome f = fit_effects(ctx.fd, s, carry_params(s, current.set, current.params));
  dropped.push_back(Effect::force_offset);
  findings.push_back("force_offset dropped after the backward check: " + w + ".");
  current = Selection{f.set, f.params, f.rss_n2, fit_rss(ctx.held, f.set, f.params, ws)};
}

/// Contact lengths of actuator travel after the end of the play by which the
/// rod has taken up a compliant stop: e^(−5) = 0.7 % of the exponential
/// take-up (soft_contact_step) is left, and a contact spring's deflection has
/// settled to the force within the same travel.
constexpr double kTakeUpLengths = 5.0;
/// The same for a progressive stop (progressive_contact_step), whose share of
/// the velocity the rod lacks falls as ℓ/(2 s) with the travel s past the stop,
/// not exponentially: ℓ/(2 s) = e^(−5) at s = ½ e⁵ ℓ, 74 engagement lengths.
constexpr double kProgressiveTakeUpLengths = 74.0;
/// Least share of the fit samples with the rod engaged for the check to judge:
/// fewer, and a delay's trace there is too faint to tell either way.
constexpr double kMinEngagedShare = 0.1;

/// Fit samples at which the actuator has travelled, since its last reversal,
/// at least `take_up_m`: the rod has crossed the play and taken up its stop.
std::vector<std::size_t> engaged_samples(const SelectionContext& ctx, double take_up_m) {
  const ModelInput& in = ctx.fd.model->input();
  const std::size_t n = in.disp_m.size();
  std::vector<double> travel(n, 0.0);
  double since = 0.0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((in.vel_m_s[k] > 0.0) != (in.vel_m_s[k - 1] > 0.0)) since = 0.0;
    since += std::fabs(in.disp_m[k] - in.disp_m[k - 1]);
    travel[k] = since;
  }
  std::vector<std::size_t> out;
  for (const std::size_t k : ctx.fd.index) {
    if (travel[k] >= take_up_m) out.push_back(k);
  }
  return out;
}

/// A transport delay shifts the whole force; free play changes it only where
/// the rod is taking up the play at a reversal. A time_delay selected beside
/// a backlash is kept only if it also lowers the residual where the rod has
/// crossed the play and taken up its stop (the damper force's viscous and
/// current-driven changes, which a delay shifts too) by ΔBIC ≥ min_delta_bic
/// on those samples. One that helps only at the engagements is describing
/// how the rod engages (a smoother stop than the catalogue's), not a delay of
/// the force channel, and is dropped, the rest refitted.
void drop_engagement_delay(const SelectionContext& ctx, Selection& current, ModelWorkspace& ws,
                           std::vector<Effect>& dropped, std::vector<std::string>& findings) {
  if (!current.set.contains(Effect::backlash) || !current.set.contains(Effect::time_delay)) return;
  const std::vector<double> play = own_params(current.set, current.params, Effect::backlash);
  const std::size_t form = current.set.form(Effect::backlash);
  const double contact_m = form == kBacklashImpactSpring ? play[1] : play[1] * play[0];
  const double take_up_m =
      play[0] + (form == kBacklashProgressive ? kProgressiveTakeUpLengths : kTakeUpLengths) * contact_m;
  const std::vector<std::size_t> engaged = engaged_samples(ctx, take_up_m);
  if (static_cast<double>(engaged.size()) < kMinEngagedShare * static_cast<double>(ctx.fd.index.size())) return;
  EffectSet without = current.set;
  without.effects.erase(std::find(without.effects.begin(), without.effects.end(), Effect::time_delay));
  FitOutcome f = fit_effects(ctx.fd, without, carry_params(without, current.set, current.params));
  const FitData on_engaged = make_fit_data(*ctx.fd.model, ctx.fd.measured_force_n, engaged, 0);
  std::vector<double> resid;
  const double rss_with = fit_rss(on_engaged, current.set, current.params, ws, &resid);
  const double rss_without = fit_rss(on_engaged, f.set, f.params, ws);
  std::vector<double> times(engaged.size());
  for (std::size_t r = 0; r < engaged.size(); ++r) times[r] = ctx.fd.model->input().time_s[engaged[r]];
  const double n_eff = noise_effective_samples(times, resid);
  const double delta_bic = n_eff * std::log(std::max(rss_without, 1e-300) / std::max(rss_with, 1e-300)) -
                           std::log(std::max(n_eff, 1.0));
  if (delta_bic >= ctx.opt.min_delta_bic) return;
  const double delay_s = own_params(current.set, current.params, Effect::time_delay)[0];
  dropped.push_back(Effect::time_delay);
  findings.push_back("time_delay (" + format_number("%.3g", delay_s) +
                     " s) dropped beside backlash: where the rod has taken up the play and its stop (" +
                     std::to_string(engaged.size()) + " of " + std::to_string(ctx.fd.index.size()) +
                     " fit samples, at least " + format_number("%.3g", take_up_m * 1e3) +
                     " mm of travel after a reversal) it lowers the BIC by " + format_number("%.1f", delta_bic) +
                     " < " + format_number("%g", ctx.opt.min_delta_bic) +
                     ": it describes how the rod engages, not a delay of the force channel.");
  current = Selection{f.set, f.params, f.rss_n2, fit_rss(ctx.held, f.set, f.params, ws)};
}

/// Normalized RMS gap of `model` against the measured force over `index`.
double gap_over(std::span<const double> measured, std::span<const double> model, std::span<const std::size_t> index) {
  double se = 0.0;
  double ss = 0.0;
  for (const std::size_t k : index) {
    se += (measured[k] - model[k]) * (measured[k] - model[k]);
    ss += measured[k] * measured[k];
  }
  return ss > 0.0 ? std::sqrt(se / ss) : 0.0;
}

/// Full-rate traces of the baseline and the selected model, their gaps,
/// and where the gap concentrates.
void add_traces_and_regions(DiscrepancyResult& res, const DamperModel& model, const MeasuredData& data,
                            const Selection& current, const SampleSplit& split, ModelWorkspace& ws) {
  model.simulate(EffectSet{}, {}, ws, res.baseline_force_n);
  model.simulate(current.set, current.params, ws, res.updated_force_n);
  res.gap_before = gap_over(data.force_n, res.baseline_force_n, split.train);
  res.gap_after = gap_over(data.force_n, res.updated_force_n, split.train);
  res.gap_validation_before = gap_over(data.force_n, res.baseline_force_n, split.held_out);
  res.gap_validation_after = gap_over(data.force_n, res.updated_force_n, split.held_out);
  res.disp_m = model.input().disp_m;
  res.vel_m_s = model.input().vel_m_s;
  res.coil_current_a = model.baseline_current_a();
  const ResidualTraces tr{data.time_s,  res.disp_m,          res.vel_m_s,           data.current_cmd_a,
                          res.coil_current_a, data.force_n, res.baseline_force_n, res.updated_force_n};
  res.regions = localize_regions(tr, model.baseline().v_tf_m_s);
  res.windows = localize_time(tr);
}

/// `named`: the effects in the model whose residual this is (signatures.hpp: their own history
/// signatures are not counted as structure).
SignatureAnalysis signatures_of(const DiscrepancyResult& res, const MeasuredData& data,
                                std::span<const double> model_force_n, const SampleSplit& split, double v_band_m_s,
                                const EffectSet& named) {
  std::vector<double> resid(data.size());
  for (std::size_t k = 0; k < resid.size(); ++k) resid[k] = data.force_n[k] - model_force_n[k];
  SignatureInput in{data.time_s, res.disp_m, res.vel_m_s, res.coil_current_a, model_force_n, resid, v_band_m_s};
  in.model_has_coil_lag = named.contains(Effect::coil_lag);
  in.model_has_settling = named.contains(Effect::idle_settling);
  in.model_has_fade = named.contains(Effect::thermal_fade);
  // Whether the residual's mean over the moving samples wanders from span to span (offset_wander).
  std::vector<double> t_moving, r_moving;
  for (const std::size_t k : split.train) {
    t_moving.push_back(data.time_s[k]);
    r_moving.push_back(resid[k]);
  }
  double mean_n = 0.0;
  for (const double r : r_moving) mean_n += r / static_cast<double>(std::max<std::size_t>(r_moving.size(), 1));
  for (double& r : r_moving) r -= mean_n;
  in.offset_wanders = !offset_wander(t_moving, r_moving, mean_n).empty();
  // A mean that is not a zero offset is noise: taken out, so that no other
  // signature with a mean of its own (|F|, an asymmetry) stands in for it.
  if (in.offset_wanders) {
    for (double& r : resid) r -= mean_n;
  }
  return analyse_residual(in, split.train, split.held_out);
}

std::string percent(double fraction) { return format_number("%.1f", 100.0 * fraction) + " %"; }

/// Where the residual concentrates and what it looks like.
void describe_residual(DiscrepancyResult& res, const SignatureAnalysis& sig, bool after) {
  std::string where;
  for (const auto& r : res.regions) {
    if (!r.concentrated) continue;
    if (!where.empty()) where += "; ";
    where += r.name + " (" + percent(r.share_of_gap_before) + " of the baseline's squared gap in " +
             percent(r.fraction_of_time) + " of the time)";
  }
  if (!where.empty()) res.findings.push_back("The baseline's gap concentrates in: " + where + ".");
  std::string what;
  for (const auto& s : sig.signatures) {
    if (s.held_out_share < 0.05) break;
    if (!what.empty()) what += "; ";
    what += s.looks_like + " [" + s.name + ", " + percent(s.held_out_share) + "]";
  }
  const std::string whose = after ? "The updated model's residual" : "The residual";
  if (what.empty()) {
    res.findings.push_back(whose + " has no shape of the signatures above 5 % of its held-out power (together " +
                           percent(std::max(sig.structured_share, 0.0)) + ").");
  } else {
    res.findings.push_back(whose + " looks like " + what + " (shares of its held-out power; all signatures together " +
                           percent(std::max(sig.structured_share, 0.0)) + ").");
  }
}

/// Round-1 candidates that were not earned, with their reasons.
void describe_rejections(DiscrepancyResult& res) {
  if (res.rounds.empty()) return;
  std::string rejected;
  for (const auto& c : res.rounds.front().candidates) {
    if (c.chosen || c.alternative || c.verdict == "earned") continue;
    if (!rejected.empty()) rejected += "; ";
    rejected += std::string(effect_name(c.effect)) + ": " + c.verdict;
  }
  if (!rejected.empty()) res.findings.push_back("Candidates rejected in round 1: " + rejected + ".");
}

/// The forms the selection chose for effects that have several, in words
/// with their physical values; "" when every effect is in its first form.
std::string form_sentence(const EffectSet& set, std::span<const double> params, const DamperModel& model) {
  std::string s;
  for (const Effect e : set.effects) {
    if (effect_info(e).forms.size() < 2) continue;
    const std::vector<double> p = own_params(set, params, e);
    std::string what;
    if (e == Effect::coil_lag) {
      what = set.form(e) == kCoilSingleLag
                 ? "one first-order lag (an L/R coil) of time constant " +
                       format_number("%.3g", p[0] * model.coil_mean_delay_s()) + " s"
                 : "Eq. 4.5 with both time constants scaled by " + format_number("%.3g", p[0]);
    } else if (e == Effect::idle_settling) {
      what = set.form(e) == kSettlingFullRecovery
                 ? "a settled layer (SQ " + format_number("%.3g", p[0]) + ") recovering fully over " +
                       format_number("%.3g", p[1] * 1e3) + " L of displaced fluid"
                 : "Eq. 5.9 (SQ " + format_number("%.3g", p[0]) + "): a deficit that recovers at Eq. 5.8's rate";
    } else if (e == Effect::backlash) {
      what = "free play " + format_number("%.3g", p[0] * 1e3) + " mm" +
             (set.form(e) == kBacklashImpactSpring
                  ? " ending in a contact spring that deflects " + format_number("%.3g", p[1] * 1e3) +
                        " mm under the baseline's force scale " + format_number("%.3g", model.baseline().force_scale_n()) +
                        " N"
                  : set.form(e) == kBacklashProgressive
                        ? " taken up by a progressive stop over an engagement length of " +
                              format_number("%.3g", p[1] * 100.0) + " % of it"
                        : " taken up over " + format_number("%.3g", p[1] * 100.0) + " % of it");
    } else {
      what = std::string(form_name(e, set.form(e)));
    }
    if (!s.empty()) s += "; ";
    s += std::string(effect_name(e)) + " in its " + std::string(form_name(e, set.form(e))) + " form, " + what;
  }
  return s.empty() ? s : "Forms chosen by BIC: " + s + ".";
}

/// `n_fit`, `n_held`: the samples behind baseline.rss and baseline.rss_held.
void decide_verdict(DiscrepancyResult& res, const DamperModel& model, const Selection& current,
                    const Selection& baseline, std::size_t n_fit,
                    std::size_t n_held) {
  const double tolerance = kExpectedGapFactor * res.expected_gap;
  const double p_before = baseline.rss_held;
  const double p_after = current.rss_held;
  const SignatureAnalysis& sb = res.signatures_before;
  const SignatureAnalysis& sa = res.signatures_after;
  if (current.set.effects.empty()) {
    const bool structured = sb.structured_share >= kStructuredShare && res.gap_validation_before > tolerance;
    // Noise has the same power on both parts; a residual that lives where the
    // held-out blocks do not reach (reversals of a sine whose period is
    // commensurate with the blocks) does not, and the held-out judgement then
    // cannot say "noise".
    const double rms_fit_n = n_fit ? std::sqrt(baseline.rss / static_cast<double>(n_fit)) : 0.0;
    const double rms_held_n = n_held ? std::sqrt(baseline.rss_held / static_cast<double>(n_held)) : 0.0;
    const bool unsampled = res.gap_before > tolerance && rms_fit_n >= kUnsampledRmsRatio * rms_held_n;
    res.verdict = structured || unsampled ? Verdict::unexplained : Verdict::none;
    if (unsampled && !structured) {
      res.findings.push_back("The baseline's RMS residual on the fit samples, " + format_number("%.4g", rms_fit_n) +
                             " N, is " + format_number("%.2f", rms_fit_n / std::max(rms_held_n, 1e-300)) +
                             " times that on the held-out samples, " + format_number("%.4g", rms_held_n) +
                             " N (gaps " + percent(res.gap_before) + " and " + percent(res.gap_validation_before) +
                             "): the residual concentrates where the held-out blocks do not reach, so it is not "
                             "noise, and no catalogued effect explains it on both parts.");
      describe_residual(res, sb, false);
      describe_rejections(res);
    } else if (structured) {
      res.findings.push_back("No catalogued effect or pair shrinks the held-out gap enough, but " +
                             percent(sb.structured_share) +
                             " of the baseline's held-out residual power has a shape (signatures.hpp), beyond noise.");
      describe_residual(res, sb, false);
      describe_rejections(res);
    } else {
      const bool within = res.gap_validation_before <= tolerance;
      const std::string why = within ? "within 1.25 times its expected gap, " + percent(res.expected_gap) +
                                           " (the largest gap on " + gap_basis_phrase(res.expected_gap_basis) +
                                           "): the baseline's known model-form error, not a discrepancy of this record"
                                     : "without a shape (" + percent(std::max(sb.structured_share, 0.0)) +
                                           " structured, below " + percent(kStructuredShare) + "): noise";
      res.findings.push_back("No effect earned its parameters, and the baseline's held-out residual, " +
                             percent(res.gap_validation_before) + ", is " + why + ".");
    }
    return;
  }
  const double removed = std::max(p_before - p_after, 0.0);
  const double left = std::max(sa.structured_share, 0.0) * p_after;
  const double noise = p_after - left;
  const std::string label = EffectSet{current.set.effects}.label();
  const std::string numbers = "removes " + percent(p_before > 0.0 ? removed / p_before : 0.0) +
                              " of the held-out residual power; the structure it leaves is " +
                              percent(noise > 0.0 ? left / noise : 1.0) + " of the noise and " +
                              percent(removed > 0.0 ? left / removed : 1.0) + " of what it removed";
  const FilterCheck& fc = res.filter_check;
  if (fc.lowpass_better) {
    res.findings.push_back("The time_delay of " + format_number("%.3g", fc.delay_s) +
                           " s leaves a filter's shape: a first-order low-pass of the force channel with tau " +
                           format_number("%.3g", fc.tau_s) + " s in its place fits better (delta BIC " +
                           format_number("%.1f", fc.delta_bic) + ", held-out residual power " +
                           percent(fc.held_out_reduction) +
                           " lower). A filter or a compliance in the force path is not in the catalogue.");
  }
  if (fc.compliance_better) {
    res.findings.push_back(label + " leaves a spring's shape: the baseline through a series compliance of " +
                           format_number("%.3g", fc.compliance_m_per_n) + " m/N (k = " +
                           format_number("%.3g", fc.compliance_m_per_n > 0.0 ? 1.0 / fc.compliance_m_per_n : 0.0) +
                           " N/m) in its place fits better (delta BIC " + format_number("%.1f", fc.compliance_delta_bic) +
                           ", held-out residual power " + percent(fc.compliance_held_out_reduction) +
                           " lower). A compliance in the force path is not in the catalogue.");
  }
  const bool not_a_delay = fc.lowpass_better || fc.compliance_better;
  const std::string forms = form_sentence(current.set, current.params, model);
  if (!not_a_delay && (left <= kLeftOverNoise * noise || left <= kLeftOverRemoved * removed)) {
    res.verdict = Verdict::explained;
    res.findings.push_back(label + " " + numbers + ".");
    if (!forms.empty()) res.findings.push_back(forms);
    if (sa.structured_share >= kStructuredShare) describe_residual(res, sa, true);
    return;
  }
  res.rejected = res.effects;
  res.rejected_params = res.params;
  res.effects.clear();
  res.params.clear();
  res.findings.push_back(label + " was fitted and " + numbers + " (limits " + percent(kLeftOverNoise) + " and " +
                         percent(kLeftOverRemoved) + "): it is not the explanation.");
  if (!forms.empty()) res.findings.push_back(forms);
  // A calibrated baseline leaves a gap on the very records it was fitted to
  // and more on motions it was not (its model-form error, res.expected_gap,
  // the largest of them, Baseline::expected_gap_basis). A record
  // whose gap is within it has no discrepancy to explain, whatever shape the
  // residual has: that shape is the baseline's own, found on its calibration
  // records too. Only a gap beyond it is unexplained.
  // The expected gap is a whole-record gap (the calibration's record_gaps),
  // so the record's whole gap is what is compared with it; the held-out
  // blocks' gap, whose normalization differs, is reported beside it.
  const bool within_expected = res.expected_gap > 0.0 && res.gap_before <= tolerance;
  if (within_expected) {
    res.verdict = Verdict::none;
    res.findings.push_back(
        "The baseline's gap on this record, " + percent(res.gap_before) + " (held-out samples " +
        percent(res.gap_validation_before) + "), is within 1.25 times its expected gap, " + percent(res.expected_gap) +
        " (the largest gap on " + gap_basis_phrase(res.expected_gap_basis) +
        "): the residual is the baseline's known model-form error, not a discrepancy of this record. A baseline of "
        "another form may leave less (mrd calibrate --law).");
    describe_residual(res, sb, false);
    return;
  }
  res.verdict = Verdict::unexplained;
  describe_residual(res, sa, true);
  describe_rejections(res);
}

}  // namespace

DiscrepancyResult run_discrepancy(const MeasuredData& data, const DiscrepancyOptions& opt) {
  DiscrepancyResult res;
  const DamperModel model(model_input(data, opt.smoothing_half_window_s), opt.baseline);
  res.velocity_derived = model.input().velocity_derived;
  res.baseline_name = opt.baseline.name;
  res.expected_gap = opt.baseline.expected_gap;
  res.expected_gap_basis = opt.baseline.expected_gap_basis;
  const SampleSplit split =
      split_samples(data.time_s, moving_span(model.input().vel_m_s), model.input().vel_m_s);
  const FitData fd = make_fit_data(model, data.force_n, split.train, opt.fit_samples);
  const FitData held = make_fit_data(model, data.force_n, split.held_out, 0);
  res.fit_samples = fd.index.size();
  res.fit_stride = fd.index.size() > 1 ? fd.index[1] - fd.index[0] : 1;

  Selection current;
  ModelWorkspace ws;
  std::vector<double> base_residual;
  current.rss = fit_rss(fd, current.set, current.params, ws, &base_residual);
  current.rss_held = fit_rss(held, current.set, current.params, ws);
  const Selection baseline = current;
  std::vector<double> fit_times(fd.index.size());
  double base_ss = 0.0;
  for (std::size_t r = 0; r < fit_times.size(); ++r) {
    fit_times[r] = data.time_s[fd.index[r]];
    const double f = data.force_n[fd.index[r]] - base_residual[r];
    base_ss += f * f;
  }
  res.n_eff_baseline = noise_effective_samples(fit_times, base_residual);

  std::vector<double> base_force;
  model.simulate(EffectSet{}, {}, ws, base_force);
  std::vector<double> settled_force;
  const std::vector<double> fully_settled{1.0};  // SQ = 1, Eq. 5.5
  model.simulate(EffectSet{{Effect::idle_settling}}, fully_settled, ws, settled_force);
  res.baseline_check = check_baseline(opt.baseline, data.force_n, base_force, settled_force, model.input().vel_m_s,
                                      data.current_cmd_a);
  BaselineCheck& check = res.baseline_check;
  check.amplitude_m = half_range_m(model.input().disp_m);
  check.frequency_hz = dominant_frequency_hz(data.time_s, model.input().disp_m);
  check.outside_coverage =
      coverage_notes(opt.baseline.range, check.amplitude_m, check.frequency_hz, opt.baseline.expected_gap);
  for (std::string& note : coil_notes(opt.baseline, data.current_cmd_a, data.current_a))
    check.outside_coverage.push_back(std::move(note));
  if (!res.baseline_check.mismatch) {
    const double base_rms = fit_times.empty() ? 0.0 : std::sqrt(base_ss / static_cast<double>(fit_times.size()));
    const SelectionContext ctx{fd, held, fit_times, opt, res.n_eff_baseline, 2.0 * check.amplitude_m, base_rms};
    if (split.pattern_shift != 0) {
      res.findings.push_back("The held-out blocks are those whose index modulo 10 is " +
                             std::to_string((2 + split.pattern_shift) % 10) + ", " +
                             std::to_string((5 + split.pattern_shift) % 10) + ", " +
                             std::to_string((8 + split.pattern_shift) % 10) +
                             " (of 40), not 2, 5, 8: those held less than " +
                             format_number("%g", 100.0 * kMinHeldReversalShare) +
                             " % of the samples just after the record's reversals.");
    }
    forward_selection(ctx, current, ws, res.rounds);
    refit_forms(ctx, current, ws, res.findings);
    backward_check(ctx, current, ws, res.dropped);
    drop_wandering_offset(ctx, current, ws, res.dropped, res.findings);
    drop_engagement_delay(ctx, current, ws, res.dropped, res.findings);
    if (current.set.contains(Effect::time_delay) || current.set.contains(Effect::preyield_hysteresis)) {
      std::vector<double> resid;
      (void)fit_rss(fd, current.set, current.params, ws, &resid);
      const double n_eff = noise_effective_samples(fit_times, resid);
      res.filter_check = compare_delay_with_lowpass(model, current.set, current.params, data.force_n, fd.index,
                                                    held.index, n_eff, opt.min_delta_bic);
      compare_with_compliance(model, current.set, current.params, data.force_n, fd.index, held.index, n_eff,
                              opt.min_delta_bic, res.filter_check);
    }
  }
  res.effects = current.set.effects;
  res.params = current.params;
  res.forms = current.set.forms;
  add_traces_and_regions(res, model, data, current, split, ws);
  const double band = model.baseline().v_tf_m_s;
  res.signatures_before = signatures_of(res, data, res.baseline_force_n, split, band, EffectSet{});
  res.signatures_after = signatures_of(res, data, res.updated_force_n, split, band, current.set);
  if (res.baseline_check.mismatch) {
    res.verdict = Verdict::baseline_mismatch;
    if (res.baseline_check.force_scale_outside) {
      res.findings.push_back("The baseline (" + res.baseline_name +
                             ") does not describe this damper; no effect was fitted. Calibrate a baseline to it "
                             "(mrd calibrate) and pass it with --baseline.");
    } else {
      // The force scale agrees: the damper may be the one calibrated, driven
      // beyond what its characterization covered.
      res.findings.push_back("The record lies outside the range the baseline (" + res.baseline_name +
                             ") describes; no effect was fitted. Calibrate with records that cover it "
                             "(mrd calibrate) and pass the baseline with --baseline.");
    }
    for (const auto& r : res.baseline_check.reasons) res.findings.push_back(r);
  } else {
    decide_verdict(res, model, current, baseline, fd.index.size(), held.index.size());
  }
  for (const auto& r : res.baseline_check.outside_coverage) res.findings.push_back(r);
  return res;
}

}  // namespace mrd::discrepancy
