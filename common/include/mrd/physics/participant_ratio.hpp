#pragma once
/// Participant ratio PR of the MR particles (thesis §5.3): its limits and
/// rate as functions of the settling quotient (Eq. 5.6–5.8, Table 5.6), its
/// recovery with displaced volume (Eq. 5.9), as a stateful block.
///
/// ∫Q dt in Eq. 5.9 is the displaced volume, ∫|v|·A dt. The thesis gives
/// neither the area A nor the unit in which c_PR multiplies the volume; both
/// are parameters here (`flow_area_m2`, `volume_unit_m3`). Only their ratio
/// matters. We count ∫Q dt in litres and use an effective mixing area of
/// 0.01062 m², fitted to the six rise times of Table 5.2 (`mrd sine
/// --calibrate` reproduces the fit; RMS log error 0.18, see README). It is
/// 41 % of the piston annulus (0.0312 − 0.00503 m², Table 5.4 (b)).

#include <cmath>

namespace mrd::physics {

/// Table 5.6 plus the two choices behind ∫Q dt.
struct ParticipantRatioParams {
  double a_initial = 1.0;
  double b_initial = 0.10;
  double c_initial = 7.0;
  double a_final = 1.0;
  double b_final = 0.605;
  double c_final = 4.5;
  double a_rise = 5.474;
  double b_rise = 0.0;
  double c_rise = 3.650;
  /// Effective area that turns |velocity| into flow rate Q, m² (fitted).
  double flow_area_m2 = 0.01062;
  /// Volume that counts as one unit of ∫Q dt in Eq. 5.9, m³: one litre.
  double volume_unit_m3 = 1.0e-3;
};

/// The three SQ-dependent coefficients of Eq. 5.9.
struct PrCoefficients {
  double a_pr = 1.0;  ///< PR before any mixing, Eq. 5.6
  double b_pr = 1.0;  ///< PR after unlimited mixing, Eq. 5.7
  double c_pr = 0.0;  ///< rate per unit of ∫Q dt, Eq. 5.8
};

/// Eq. 5.6–5.8 for SQ given as a fraction (0 = fully mixed, 1 = fully settled).
inline PrCoefficients pr_coefficients(const ParticipantRatioParams& p, double sq) noexcept {
  PrCoefficients c;
  c.a_pr = p.b_initial + (p.a_initial - p.b_initial) * std::exp(-p.c_initial * sq);
  c.b_pr = p.b_final + (p.a_final - p.b_final) * std::exp(-p.c_final * sq);
  c.c_pr = p.b_rise + (p.a_rise - p.b_rise) * std::exp(-p.c_rise * sq);
  return c;
}

/// Eq. 5.9: PR = b_PR + (a_PR − b_PR)·exp(−c_PR·∫Q dt), with ∫Q dt in units
/// of `volume_unit_m3`.
inline double participant_ratio(const PrCoefficients& c, double displaced_units) noexcept {
  return c.b_pr + (c.a_pr - c.b_pr) * std::exp(-c.c_pr * displaced_units);
}

/// Stateful participant ratio: set the settling quotient once at the start of
/// an episode, then feed damper velocity (or displaced volume directly).
class ParticipantRatio {
 public:
  ParticipantRatio() = default;
  ParticipantRatio(const ParticipantRatioParams& p, double sq) noexcept { init(p, sq); }

  void init(const ParticipantRatioParams& p, double sq) noexcept {
    p_ = p;
    reset(sq);
  }

  /// Starts a new episode after an idle period with settling quotient `sq`.
  void reset(double sq) noexcept {
    sq_ = sq;
    coeff_ = pr_coefficients(p_, sq);
    displaced_m3_ = 0.0;
    update();
  }

  /// Accumulates |v|·A·dt (velocity held over dt) and returns the new PR.
  double step(double velocity_m_s, double dt_s) noexcept {
    if (velocity_m_s != 0.0) {
      displaced_m3_ += std::fabs(velocity_m_s) * p_.flow_area_m2 * dt_s;
      update();
    }
    return pr_;
  }

  /// Credits displaced volume from elsewhere (e.g. a mixing cycle), m³.
  void add_displaced_volume_m3(double volume_m3) noexcept {
    if (volume_m3 > 0.0) {
      displaced_m3_ += volume_m3;
      update();
    }
  }

  /// Present participant ratio, Eq. 5.9.
  double pr() const noexcept { return pr_; }
  double displaced_volume_m3() const noexcept { return displaced_m3_; }
  double sq() const noexcept { return sq_; }
  const PrCoefficients& coefficients() const noexcept { return coeff_; }
  const ParticipantRatioParams& params() const noexcept { return p_; }

 private:
  ParticipantRatioParams p_{};
  PrCoefficients coeff_{};
  double sq_ = 0.0;
  double displaced_m3_ = 0.0;
  double pr_ = 1.0;

  void update() noexcept { pr_ = participant_ratio(coeff_, displaced_m3_ / p_.volume_unit_m3); }
};

}  // namespace mrd::physics
