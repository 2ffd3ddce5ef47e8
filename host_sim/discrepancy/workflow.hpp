#pragma once
/// The model-discrepancy workflow: a baseline (the thesis's chapter-4 model
/// or one calibrated to the user's damper), a check that the record lies
/// inside what the baseline describes, localization of the gap, greedy
/// forward selection of named effects with a BIC penalty, physical
/// plausibility checks, a held-out judgement and a final backward check,
/// and a verdict.
///
/// Judged: the samples over which the actuator moves (moving_span,
/// damper_model.hpp); the standstill before and after is neither fitted nor
/// counted in a gap. Held out: 30 % of those (split_samples, fit.hpp) is
/// never fitted.
/// An effect joins the model only if it also removes at least
/// min_rss_reduction of the held-out residual power.
///
/// Verdict:
/// <pre>
///   baseline_mismatch  check_baseline() failed: no effect is fitted
///   none               no effect joined, and the held-out residual is not
///                      structured (signatures.hpp: < kStructuredShare) or
///                      within 1.25 × the baseline's expected gap, and the
///                      RMS residual (N) on the fit samples is below 3 ×
///                      the held-out one (else the residual lives where the
///                      held-out blocks do not reach: unexplained)
///   explained          effects joined, and the structure they leave on the
///                      held-out samples (signatures.hpp) is at most 25 % of
///                      the noise there or at most 5 % of the power they
///                      removed, and a time_delay among them is not better
///                      described as a low-pass (filter_check.hpp)
///   unexplained        otherwise; the effects that joined are then reported
///                      as rejected, with what the residual looks like
/// </pre>
///
/// Plausibility: a parameter pinned at a bound other than its null value is
/// flagged and its effect cannot be the explanation, except SQ = 1, the
/// fully settled state of Eq. 5.5 (idle ≥ T_max), which is a physical state
/// and not a limit of the fit; it is still flagged. A model whose force
/// collapses (free play at least the record's stroke, or an RMS force below
/// a tenth of the baseline's, less than the most settled damper of Eq. 5.6
/// keeps) is rejected. A force_offset that does not stand out of the
/// wander of the record's tenths (offset_wander) is rejected.
///
/// Confusable pairs and what separates them (each is a column of the
/// joint fit, and the independent study checks them):
/// <pre>
///   idle_settling / thermal_fade   settling's deficit shrinks with displaced volume (force grows
///                                  over the record); a fade grows with dissipated energy (force falls)
///   idle_settling / force_offset   settling scales the force (odd in v, vanishing at v = 0); an offset
///                                  is even and constant
///   thermal_fade / force_offset    a fade scales the force and grows; an offset is constant
///   time_delay / low-pass (not     a low-pass is a delay plus a term in d²F/dt², growing with frequency:
///   in the catalogue)              the delay replaced by a fitted first-order low-pass must not fit
///                                  better by ΔBIC ≥ min_delta_bic and on the held-out samples
///                                  (filter_check.hpp); if it does, the verdict is unexplained
///   time_delay / backlash          a delay shifts every part of the cycle alike; play flattens the
///                                  force only after reversals, for a displacement, not a time
///   gas_spring / time_delay        a spring is in phase with x at every frequency; a delay's
///                                  quadrature part scales with dF/dt
///   preyield_hysteresis / backlash both soften reversals; pre-yield keeps the force's sign through
///                                  the reversal (a loop), play drops it to zero
///   force_offset / coloured noise  an offset is the same in every tenth of the record; the slow part of
///                                  1/f noise gives the record a mean too, but one that wanders from
///                                  tenth to tenth (offset_wander): such an offset is implausible
/// </pre>
///
/// Signatures of the residual (signatures.hpp) also carry the physics of the
/// pairs: a deficit recovering with rod travel (settling, volume_recovery_*),
/// a change growing with dissipated energy (heating), the force late after
/// current steps (a slower coil, current_lag_*). A residual of those shapes
/// that no catalogued effect removes is unexplained, not noise.
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
#include "host_sim/discrepancy/baseline_check.hpp"
#include "host_sim/discrepancy/effects.hpp"
#include "host_sim/discrepancy/filter_check.hpp"
#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/regions.hpp"
#include "host_sim/discrepancy/signatures.hpp"

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
  EffectForms forms{};             ///< the forms of `model`'s effects (params packed by them)
  /// Round 2 only: a pair of other round-1 effects that would replace the
  /// model (`model` holds the pair, `effect` its second member).
  bool alternative = false;
  std::vector<double> params;      ///< the candidate's own parameters, physical
  std::vector<double> all_params;  ///< model + candidate, packed
  double delta_bic = 0.0;
  double rss_reduction = 0.0;      ///< 1 − RSS_with / RSS_without
  double held_out_reduction = 0.0; ///< the same on the held-out samples
  /// Per parameter of `params`: "" or why it is flagged (at a bound).
  std::vector<std::string> flags;
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

enum class Verdict { none, explained, unexplained, baseline_mismatch };
[[nodiscard]] const char* verdict_name(Verdict v) noexcept;

struct DiscrepancyResult {
  Verdict verdict = Verdict::none;
  /// Sentences that back the verdict: the numbers, where the residual
  /// concentrates, what it looks like, what was rejected and why.
  std::vector<std::string> findings;
  std::vector<Effect> effects;     ///< the explanation (empty unless explained), in the order added
  std::vector<double> params;      ///< their parameters, packed in that order (and by their forms)
  /// The forms of `effects` and of `rejected` (EffectInfo::forms): the
  /// selection fits each form of an effect that has several and keeps the one
  /// with the lower BIC.
  EffectForms forms{};
  /// Effects the selection took but the verdict does not accept (unexplained).
  std::vector<Effect> rejected;
  std::vector<double> rejected_params;
  std::vector<Effect> dropped;     ///< chosen, then removed by the backward check
  /// A selected time_delay against a first-order low-pass (filter_check.hpp).
  FilterCheck filter_check;
  BaselineCheck baseline_check;
  std::string baseline_name;
  double expected_gap = 0.0;       ///< the baseline's own
  GapBasis expected_gap_basis = GapBasis::calibration_records;  ///< the records it was taken on
  // Normalized RMS force gaps at full rate: on the samples the fits saw, and held out.
  double gap_before = 0.0;
  double gap_after = 0.0;
  double gap_validation_before = 0.0;
  double gap_validation_after = 0.0;
  SignatureAnalysis signatures_before;  ///< of the baseline's residual
  SignatureAnalysis signatures_after;   ///< of the updated model's residual
  std::vector<RoundResult> rounds;
  std::vector<RegionStat> regions;
  std::vector<TimeWindowStat> windows;
  double n_eff_baseline = 0.0;
  std::size_t fit_stride = 1;
  std::size_t fit_samples = 0;
  bool velocity_derived = false;
  /// Plausibility warnings about the record (plausibility.hpp), set by the
  /// caller that printed them; summary.json's `warnings`.
  std::vector<std::string> warnings;
  // Traces at the record's samples, for reports and plots.
  std::vector<double> disp_m, vel_m_s, coil_current_a, baseline_force_n, updated_force_n;

  [[nodiscard]] EffectSet effect_set() const { return EffectSet{effects, forms}; }
};

[[nodiscard]] DiscrepancyResult run_discrepancy(const MeasuredData& data, const DiscrepancyOptions& options = {});

/// Physical plausibility of fitted parameters of one effect: empty when
/// plausible, else the reason (at its null value, or pinned at a bound).
/// `scale`: DamperModel::param_scale() (force-valued bounds scale; an
/// assumed coil may be faster).
/// `form`: the effect's form (EffectInfo::forms), whose parameters `params` are.
/// Free play ending in a contact spring that deflects under the baseline's
/// force scale more than kMaxStopDeflectionPerPlay times the play is
/// implausible: the play is then a detail of a spring in series with the
/// damper (a compliance of the force path, or a low-pass of the force channel
/// it mimics, neither in the catalogue). Fits of such records gave 3–40 times
/// the play; of free play with a pad at its end, 0.2–1.4 times.
inline constexpr double kMaxStopDeflectionPerPlay = 2.0;
[[nodiscard]] std::string implausibility(Effect e, std::span<const double> params, const ParamScale& scale = {},
                                         std::size_t form = 0);

/// A fitted force_offset against the slow part of the noise. A load-cell
/// zero offset is the same in every part of the record; coloured noise
/// (1/f, a wandering zero) has a slow part that also gives the record a mean,
/// but one that differs from part to part. `residual_n` is the fitted
/// model's residual (the offset inside the model) at `time_s`: the record is
/// cut into kOffsetBlocks equal spans of time, and the offset must exceed
/// kOffsetBlockT standard errors of the spans' means of residual + offset.
/// Empty when it does, else the reason.
[[nodiscard]] std::string offset_wander(std::span<const double> time_s, std::span<const double> residual_n,
                                        double offset_n);
inline constexpr std::size_t kOffsetBlocks = 10;
/// Four standard errors: a mean of ten spans of noise without offset passes
/// with a chance of 0.3 % (Student's t, 9 degrees of freedom).
inline constexpr double kOffsetBlockT = 4.0;

/// Per parameter of effect `e`: "" or "at its lower/upper bound …".
[[nodiscard]] std::vector<std::string> bound_flags(Effect e, std::span<const double> params,
                                                   const ParamScale& scale = {}, std::size_t form = 0);

}  // namespace mrd::discrepancy
