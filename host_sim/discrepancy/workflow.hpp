#pragma once
/// The model-discrepancy workflow: baseline (chapter-4 model), localization
/// of the gap, and greedy forward selection of named effects with a BIC
/// penalty, physical plausibility checks and a final backward check.
///
/// Selection, per round: every catalogue effect not yet in the model is
/// added to it and all parameters (old and new) are refitted jointly. Its
/// score is
/// <pre>
///   ΔBIC = n_eff ln(RSS_model / RSS_model+effect) − k_effect ln(n_eff)
/// </pre>
/// with n_eff the effective sample count of the noise (noise_effective_samples) in the
/// residual of the round's best-fitting plausible candidate, the same for all
/// candidates of the round. The best-scoring candidate joins the model when
/// its fit is physically plausible, ΔBIC ≥ min_delta_bic and it removes at
/// least min_rss_reduction of the residual power; otherwise the round names
/// none and the search stops. Afterwards each chosen effect is dropped again
/// if the others explain the data without it. Round 2 also weighs, as
/// alternatives to the round-1 winner plus one more, the pairs of the other
/// effects round 1 found earned (up to three of them): one effect can mimic
/// two others better than either alone, and pure forward addition would then
/// never reach the pair.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "host_sim/discrepancy/baseline.hpp"
#include "host_sim/discrepancy/effects.hpp"
#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/regions.hpp"

namespace mrd::discrepancy {

struct DiscrepancyOptions {
  std::vector<Effect> catalogue{kAllEffects.begin(), kAllEffects.end()};
  /// "Very strong" evidence on the Kass–Raftery scale.
  double min_delta_bic = 10.0;
  /// An effect must remove at least this fraction of the residual power.
  double min_rss_reduction = 0.05;
  std::size_t max_effects = 3;
  /// Samples used by the fits (every stride-th); the gaps are computed at full rate.
  std::size_t fit_samples = 4000;
  /// Threads for the candidate fits; 0 = hardware concurrency.
  unsigned threads = 0;
  double smoothing_half_window_s = kDefaultSmoothingHalfWindow_s;
  /// The damper model the record is compared with (`mrd discrepancy --baseline`).
  Baseline baseline = thesis_baseline();
};

/// One candidate fit in one round.
struct CandidateResult {
  Effect effect{};
  std::vector<Effect> model;       ///< every effect of the fitted model (model so far + effect)
  /// Round 2 only: a pair of other round-1 effects that would replace the
  /// model (`model` holds the pair, `effect` its second member).
  bool alternative = false;
  std::vector<double> params;      ///< the candidate's own parameters, physical
  std::vector<double> all_params;  ///< model + candidate, packed
  double delta_bic = 0.0;
  double rss_reduction = 0.0;      ///< 1 − RSS_with / RSS_without
  double n_eff = 0.0;             ///< the round's effective sample count
  double gap = 0.0;                ///< normalized RMS gap on the fit samples with the candidate
  bool plausible = false;
  bool chosen = false;
  std::string verdict;             ///< why it was or was not chosen
};

struct RoundResult {
  std::vector<Effect> model;       ///< effects already in the model
  double gap = 0.0;                ///< its normalized RMS gap on the fit samples
  std::vector<CandidateResult> candidates;
  std::optional<Effect> chosen;
  std::vector<Effect> model_after;  ///< the model after the round (when one was chosen)
};

struct DiscrepancyResult {
  std::vector<Effect> effects;     ///< named effects, in the order they were added
  std::vector<double> params;      ///< their parameters, packed in that order
  std::vector<Effect> dropped;     ///< chosen, then removed by the backward check
  double gap_before = 0.0;         ///< normalized RMS force error of the baseline, full rate
  double gap_after = 0.0;          ///< the same for the updated model
  std::vector<RoundResult> rounds;
  std::vector<RegionStat> regions;
  std::vector<TimeWindowStat> windows;
  double n_eff_baseline = 0.0;
  std::size_t fit_stride = 1;
  std::size_t fit_samples = 0;
  bool velocity_derived = false;
  // Traces at the record's samples, for reports and plots.
  std::vector<double> disp_m, vel_m_s, coil_current_a, baseline_force_n, updated_force_n;

  [[nodiscard]] EffectSet effect_set() const { return EffectSet{effects}; }
};

[[nodiscard]] DiscrepancyResult run_discrepancy(const MeasuredData& data, const DiscrepancyOptions& options = {});

/// Physical plausibility of fitted parameters of one effect: empty when
/// plausible, else the reason (at its null value, or pinned at a bound).
[[nodiscard]] std::string implausibility(Effect e, std::span<const double> params, double force_ratio = 1.0);

}  // namespace mrd::discrepancy
