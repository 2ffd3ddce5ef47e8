#pragma once
/// Pure delay or filter: the test that separates a `time_delay` from a
/// first-order low-pass of the force channel (an anti-alias filter, or the
/// compressibility of a fluid column in series), which the catalogue does
/// not have.
///
/// A first-order low-pass 1/(1 + τs) = e^(−τs) (1 + τ²s²/2 + O(τ³s³)): a
/// delay of τ plus a term in the force's second derivative, whose share
/// grows with frequency (phase atan ωτ against a delay's ωτ, and a gain
/// 1/√(1 + ω²τ²) a delay does not have). On a record with force content
/// well above 1/τ the two differ; below it they are the same within noise.
/// The test: the delay of the selected model is replaced by a low-pass, the
/// other effects held at their fitted values, and τ fitted (one parameter,
/// as the delay). The low-pass is the better description when
/// <pre>
///   n_eff ln(RSS_delay / RSS_lowpass) ≥ min_delta_bic   on the fit samples, and
///   RSS_lowpass < RSS_delay                             on the held-out samples
/// </pre>
/// (the same evidence an effect needs to join the model). The delay stands
/// for the force channel's lag, which is a transport delay behind the
/// acquisition's anti-alias filter: RSS_delay is the lower of the pure delay's
/// and that of the delay behind a first-order filter whose corner is at or
/// above a quarter of the sample rate (τ ≤ 2/(π f_s), 0.64 ms at 1 kHz; the
/// delay shortened by it), so that the acquisition's anti-alias filter is not
/// taken for a low-pass outside the catalogue. The delay's model
/// was fitted jointly with the other effects and the low-pass was not, so
/// the comparison leans towards the delay.

///
/// The same test against a series compliance of the force path (the fluid
/// column's or the mounting's stiffness k between the actuator and a damper
/// that follows the baseline law): F = k (x − y), F = F_baseline(ẏ), solved
/// implicitly per sample. At small compliance this too is close to a delay
/// (post-yield a Maxwell element lags by C/k), but after each reversal the
/// force builds along the spring, F ≈ k Δx, for as long as the damper is
/// pre-yield, which no delay and no low-pass does. It replaces the delay in
/// the same way, one parameter (1/k), with the same rule. The same spring
/// also looks like pre-yield hysteresis (the force built over a
/// displacement after each reversal), with one difference: a spring's
/// build-up length is the force it must carry over k, so it grows with the
/// current, while x_y is one length. So the compliance replaces a selected
/// time_delay or preyield_hysteresis. It is only tried on the Bingham
/// baseline without lost motion, with every selected effect left out (the
/// comparison leans towards the selected model, which has them).

#include <cstddef>
#include <span>
#include <vector>

#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/discrepancy/effects.hpp"

namespace mrd::discrepancy {

struct FilterCheck {
  bool checked = false;           ///< the model had a time_delay to compare
  double delay_s = 0.0;           ///< the model's fitted delay
  double tau_s = 0.0;             ///< the best low-pass time constant
  /// The anti-alias filter (τ ≤ 2/(π f_s)) behind which the delay fits
  /// best, s; 0 when the pure delay fits better.
  double anti_alias_s = 0.0;
  double delta_bic = 0.0;         ///< n_eff ln(RSS_delay / RSS_lowpass), fit samples
  double held_out_reduction = 0.0;  ///< 1 − RSS_lowpass / RSS_delay, held-out samples
  bool lowpass_better = false;
  bool compliance_checked = false;       ///< the baseline allowed the compliance test
  double compliance_m_per_n = 0.0;       ///< the best series compliance 1/k
  double compliance_delta_bic = 0.0;     ///< n_eff ln(RSS_selected / RSS_compliance), fit samples
  double compliance_held_out_reduction = 0.0;  ///< 1 − RSS_compliance / RSS_selected, held-out samples
  bool compliance_better = false;
};

/// Baseline force (no effects) through a series compliance of
/// `compliance_m_per_n`, N, at every sample, the baseline's force lag
/// applied. Requires the Bingham law of Eq. 4.4 without lost motion or transition time.
void series_compliance_force(const DamperModel& model, double compliance_m_per_n, std::vector<double>& force_n);

/// First-order low-pass y' = (u − y)/τ of `u` sampled at `time_s`, exact
/// for an input linear between samples; y starts at u[0].
void first_order_lowpass(std::span<const double> time_s, std::span<const double> u, double tau_s,
                         std::vector<double>& y);

/// The test above for `set` (which must contain time_delay) at `params`.
/// `fit_index`, `held_index`: samples of `measured_force_n`; `n_eff`: the
/// effective sample count of the model's residual.
[[nodiscard]] FilterCheck compare_delay_with_lowpass(const DamperModel& model, const EffectSet& set,
                                                     std::span<const double> params,
                                                     std::span<const double> measured_force_n,
                                                     std::span<const std::size_t> fit_index,
                                                     std::span<const std::size_t> held_index, double n_eff,
                                                     double min_delta_bic);

/// The compliance test above, when `set` holds time_delay or
/// preyield_hysteresis (fills the compliance fields of `out`; delay_s too).
void compare_with_compliance(const DamperModel& model, const EffectSet& set, std::span<const double> params,
                             std::span<const double> measured_force_n, std::span<const std::size_t> fit_index,
                             std::span<const std::size_t> held_index, double n_eff, double min_delta_bic,
                             FilterCheck& out);

}  // namespace mrd::discrepancy
