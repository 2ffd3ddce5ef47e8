#pragma once
/// Fitting the parameters of a set of effects to a measured force by bounded
/// nonlinear least squares (Ceres, Levenberg–Marquardt), and the statistics
/// the selection uses: residual sum of squares, effective sample count and
/// the Bayesian information criterion.

#include <cstddef>
#include <span>
#include <vector>

#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/discrepancy/effects.hpp"

namespace mrd::discrepancy {

/// A record to fit: the model, the measured force at full rate, and the
/// samples the fit uses (every `stride`-th).
struct FitData {
  const DamperModel* model = nullptr;
  std::span<const double> measured_force_n;
  std::vector<std::size_t> index;  ///< ascending
  double force_scale_n = 1.0;      ///< residuals are divided by this (RMS measured force)
};

/// Every `stride`-th sample, stride chosen so that about `target` remain.
[[nodiscard]] FitData make_fit_data(const DamperModel& model, std::span<const double> measured_force_n,
                                    std::size_t target);

/// Every `stride`-th of the samples `candidates` (ascending), about `target`
/// of them; target 0 keeps them all.
[[nodiscard]] FitData make_fit_data(const DamperModel& model, std::span<const double> measured_force_n,
                                    std::span<const std::size_t> candidates, std::size_t target);

/// The samples `range` of a record (its moving_span) cut into kSplitBlocks
/// blocks of equal duration; the blocks
/// whose index modulo 10 is 2, 5 or 8 (30 % of the record, spread over its
/// whole length so that effects that act early, such as settling, or late,
/// such as a thermal fade, are seen on both sides) are held out of every fit
/// and only judge it.
///
/// With the velocity given: what happens only at reversals (free play, the
/// force's build-up through a reversal) must be judged too. A slow motion
/// reverses a few times a record (a 0.2 Hz sine eight times in 20 s), and
/// the samples just after its reversals can all fall in fitted blocks. When
/// the record reverses kMinSplitReversals times or more and the held-out
/// blocks hold less than kMinHeldReversalShare of the samples within
/// kReversalZone_s after a reversal, the pattern turns (index modulo 10 is
/// 2, 5, 8 plus a shift) to the shift whose held-out share of them is
/// nearest the held-out share of the record, 30 % (the smallest such shift).
/// The choice reads the motion only, never the force it judges.
inline constexpr std::size_t kSplitBlocks = 40;
inline constexpr double kHeldOutShare = 0.3;
inline constexpr std::size_t kMinSplitReversals = 3;
inline constexpr double kMinHeldReversalShare = 0.1;
/// The time after a reversal in which a free play of about a millimetre is
/// taken up at the slowest motions the workflow meets: from rest at the
/// acceleration ω²X of a 0.2 Hz, 50 mm sine (0.08 m/s²), t = √(2 play / a) = 0.16 s.
inline constexpr double kReversalZone_s = 0.2;
struct SampleSplit {
  std::vector<std::size_t> train;     ///< ascending
  std::vector<std::size_t> held_out;  ///< ascending
  std::size_t pattern_shift = 0;      ///< the held-out blocks' index modulo 10 is 2, 5, 8 plus this
};
[[nodiscard]] SampleSplit split_samples(std::span<const double> time_s, SampleRange range,
                                        std::span<const double> velocity_m_s = {});
/// The whole record split.
[[nodiscard]] SampleSplit split_samples(std::span<const double> time_s);

struct FitOutcome {
  EffectSet set;
  std::vector<double> params;     ///< physical, packed in set order
  double rss_n2 = 0.0;            ///< Σ (F_meas − F_model)² over the fit samples, N²
  double n_eff = 0.0;             ///< noise_effective_samples of the residual
  int iterations = 0;
  bool converged = false;
};

/// Fits `set`. `start` holds physical starting values for the effects in
/// `set` (packed). Where `grid_effect` is in the set, its init grid (the
/// other effects held at `start`) supplies further starting points, and the
/// local fit runs from the best `max_starts` of them, keeping the best end.
/// Ceres LM on parameters normalized to [0, 1] by their bounds; forward
/// differences. Deterministic.
[[nodiscard]] FitOutcome fit_effects(const FitData& data, const EffectSet& set, std::vector<double> start,
                                     const Effect* grid_effect = nullptr, std::size_t max_starts = 1);

/// Residual sum of squares of `set` at `params` over the fit samples, N².
[[nodiscard]] double fit_rss(const FitData& data, const EffectSet& set, std::span<const double> params,
                             ModelWorkspace& ws, std::vector<double>* residual_n = nullptr);

/// n / τ_int, τ_int the integrated autocorrelation time of `residual`
/// (Geyer's initial positive sequence of lag-pair sums, lags up to n/8, at
/// most 1000). Correlated residuals count as fewer independent samples, so a
/// noise-level improvement is not taken for evidence. In [1, n].
[[nodiscard]] double effective_sample_count(std::span<const double> residual);

/// Effective sample count of the noise in a fit residual: that of the
/// residual minus its quartic local fit over ±75 ms (smooth_motion), so that
/// slow structure an effect not yet in the model leaves behind is not
/// mistaken for correlated noise. `time_s` are the residual's sample times.
[[nodiscard]] double noise_effective_samples(std::span<const double> time_s, std::span<const double> residual);

/// BIC = n_eff ln(RSS / n) + k ln(n_eff).
[[nodiscard]] double bic(double rss, std::size_t n, double n_eff, std::size_t k);

}  // namespace mrd::discrepancy
