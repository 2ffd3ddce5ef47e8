#pragma once
/// What a force residual looks like: the residual is regressed, on the
/// samples the fits use, onto simple signals that each stand for one kind of
/// model error, and every regression is judged on the held-out samples. The
/// share of the held-out residual power a signature removes says how much
/// of the residual has that shape; all signatures together give the share
/// that is structure rather than noise (noise, white or coloured, is
/// uncorrelated with every signature, so its held-out share is near zero).
///
/// Signatures (x, v, a: rod motion; F: model force; TF: Eq. 4.4's factor):
/// <pre>
///   offset               1                          a constant force
///   drift                t                          a slow drift over the record
///   stiffness            x                          a force proportional to displacement
///   lag                  dF/dt                      the measured force late (or early) against the model
///   force_scale          F                          the model too strong or too weak
///   asymmetry            F·[v > 0]                  extension and compression differ
///   low_velocity_loop    −sgn(a)·w(v)               a loop at low velocity (pre-yield hysteresis)
///   transition_shape     sgn(v)·w(v)                the force rising with velocity otherwise than Eq. 4.4
///   current_law          F·i/i_max                  the force depending on current otherwise than the law
///   inertia              a                          a force in phase with acceleration (mass, compressibility)
///   filter_shape         d²F/dt²                    a filter (low-pass, compliance) rather than a pure delay
///   current_lag_short    F·(i_0.1s − i)/i_max       the force late after current changes: a slower coil
///   current_lag_long     F·(i_1s − i)/i_max         the same, slower still
///   volume_recovery_short F·exp(−S / 0.03 m)        a deficit recovering with displaced volume (settling)
///   volume_recovery_long F·exp(−S / 0.3 m)          the same, over more volume
///   heating              F·E / E_end                a change growing with dissipated energy (fade)
///   w(v) = max(0, 1 − |v| / (3 v_band)); i_τ: the current through a further
///   first-order lag τ (∂F/∂i taken ∝ F); S = ∫|v| dt, the rod's travel since
///   the record's start (displaced volume over the flow area); E = ∫|F v| dt,
///   the energy dissipated so far.
/// </pre>
/// And one signature without a form, state_map: the mean residual in each
/// cell of the damper's state (velocity in 12 quantile bins × displacement
/// in 4 × sign of acceleration × current in 3), learnt on the training
/// samples. Any error that is a function of the state repeats in its cell
/// and carries to the held-out samples; noise, white or coloured, averages
/// out in a cell (its held-out share is about −1/(samples per cell)).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace mrd::discrepancy {

struct SignatureStat {
  std::string name;
  std::string looks_like;      ///< one sentence
  double held_out_share = 0.0;  ///< share of the held-out residual power it removes (≤ 0: none)
  double coefficient = 0.0;    ///< fitted on the training samples (unit: N per unit of the signal)
};

struct SignatureAnalysis {
  std::vector<SignatureStat> signatures;  ///< largest held-out share first
  /// Held-out share of the residual power that is structure: the largest of
  /// all form signatures together, any one of them and the state map.
  double structured_share = 0.0;
};

/// Inputs at the record's samples.
struct SignatureInput {
  std::span<const double> time_s;
  std::span<const double> disp_m;
  std::span<const double> vel_m_s;
  std::span<const double> current_a;
  std::span<const double> model_force_n;
  std::span<const double> residual_n;  ///< measured − model
  double low_velocity_band_m_s = 0.01;
  /// The model already carries a coil lag, a settling or a fade: the
  /// history signatures of that physics (current_lag_*, volume_recovery_*,
  /// heating) are then reported but not counted in structured_share. What the
  /// named effect leaves in its own shape is a detail of its form (one coil
  /// time constant or two, a deficit recovering at another rate), not a
  /// further effect.
  bool model_has_coil_lag = false;
  bool model_has_settling = false;
  bool model_has_fade = false;
  /// The residual's mean wanders from span to span of the record (the slow
  /// part of coloured noise, workflow.hpp's offset_wander): the offset
  /// signature is then reported but not counted in structured_share, as a
  /// force_offset that wanders is not earned (the caller also takes the
  /// residual's mean out).
  bool offset_wanders = false;
};

/// Fits on `train` and judges on `held_out` (sample indices).
[[nodiscard]] SignatureAnalysis analyse_residual(const SignatureInput& in, std::span<const std::size_t> train,
                                                 std::span<const std::size_t> held_out);

/// A residual counts as structured when the signatures together remove at
/// least this share of its held-out power.
inline constexpr double kStructuredShare = 0.15;

}  // namespace mrd::discrepancy
