#pragma once
/// Bingham-plastic MR damper force with exponential current laws and the
/// velocity transition function (thesis chapter 4), extended by the
/// participant ratio of chapter 5.
///
/// All functions are pure, allocation-free and exception-free.

#include <cmath>

#include "mrd/units.hpp"

namespace mrd::physics {

/// Table 4.1, converted to SI. Subscript a: value at 0 A; b: value the law
/// tends to at high current (the thesis calls it "the value at 2.5 A", but
/// Eq. 4.2–4.3 only approach it); c: exponential rate in 1/A.
struct BinghamParams {
  double fc_a_n = units::kn_to_n(4.1);                        ///< f_c,a = 4.1 kN
  double fc_b_n = units::kn_to_n(170.0);                      ///< f_c,b = 170 kN
  double fc_c_per_a = 0.7;                                    ///< f_c,c = 0.7 1/A
  double c0_a_ns_m = 0.0825 * units::kNsPerM_per_kNsPerMm;    ///< c_0,a = 0.0825 kN·s/mm
  double c0_b_ns_m = 0.365 * units::kNsPerM_per_kNsPerMm;     ///< c_0,b = 0.365 kN·s/mm
  double c0_c_per_a = 1.15;                                   ///< c_0,c = 1.15 1/A
  /// Transition velocity of Eq. 4.4: 10 mm/s.
  double v_tf_m_s = units::mm_to_m(10.0);
};

/// How a calibrated damper (`mrd calibrate`, host_sim/discrepancy/
/// baseline.hpp) shapes the thesis's law; every default leaves Eq. 4.1–4.4
/// and 5.10–5.12 as they are, to the bit:
/// <pre>
///   f_c(I) = b + (a − b) exp(−c |I|^q_y),   c_0(I) likewise with q_c        current exponents (1: Eq. 4.2–4.3)
///   c_0 v  → c_0 v_r (|v| / v_r)^m sgn v                                     viscous exponent m (1: linear)
///   F     += k x                                                              spring beside the law (0: none)
///   v_TF   → v_TF + τ |a|                                                     transition time τ (0: Eq. 4.4's band)
///   F_law  → F_law ((1 − r) + r e) + (1 − e) f_c tanh(v / v_p)               lost motion (λ = 0 or r = 0: none)
///   F_law  = F_law(v − Ḟ_law / k_s)                                          series compliance (1/k_s = 0: rigid)
/// </pre>
/// q > 1 is a force that rises slowly at low current and then saturates; m < 1
/// a fluid that thins past yield (Herschel–Bulkley); k the accumulator's gas
/// charge; τ the time the fluid's chains and the valve's pressure take to
/// form again after a reversal. The lost motion holds up a share r of the
/// law's force (not the spring's) until the stroke has moved through a play
/// of width λ |f_c(I, PR = 1)| after a reversal: e is the engagement of that
/// play, 0 inside it and 1 past it (inside it the force may instead grow
/// over the band v_p; v_p = 0: none), baseline.hpp's "lost motion". The
/// current exponents and the lost motion act on every law but Spencer's; m,
/// k, τ and the series compliance on the Bingham laws (Eq. 4.4's and the
/// tanh transition), as in the calibration. The series compliance is the
/// fluid's and the body's give between piston and valve: the law acts on the
/// fluid's velocity, so the force's lag behind the motion grows with the
/// force (series_compliance.hpp).
struct LawShape {
  double yield_current_exponent = 1.0;    ///< q_y of f_c(I)
  double viscous_current_exponent = 1.0;  ///< q_c of c_0(I)
  double viscous_exponent = 1.0;          ///< m; acts only with viscous_ref_m_s > 0
  double viscous_ref_m_s = 0.0;           ///< v_r: the velocity at which c_0 is the slope, m/s
  double stiffness_n_m = 0.0;             ///< k, N/m
  double transition_time_s = 0.0;         ///< τ, s
  double lost_motion_m_per_n = 0.0;       ///< λ: the play's width per newton of f_c(I, PR = 1), m/N
  double lost_motion_share = 0.0;         ///< r: the share of the law's force held up, [0, 1]
  double lost_motion_band_m_s = 0.0;      ///< v_p: the band of the force inside the play, m/s (0: none)
  /// 1/k_s: a compliance in series with a Bingham law's force (its lost
  /// motion included, the spring not), m/N (0: rigid; series_compliance.hpp)
  double series_compliance_m_per_n = 0.0;

  [[nodiscard]] bool has_viscous_exponent() const noexcept { return viscous_ref_m_s > 0.0 && viscous_exponent != 1.0; }
  [[nodiscard]] bool has_lost_motion() const noexcept { return lost_motion_m_per_n > 0.0 && lost_motion_share > 0.0; }
  /// True when any term differs from the thesis's law.
  [[nodiscard]] bool bends() const noexcept {
    return yield_current_exponent != 1.0 || viscous_current_exponent != 1.0 || has_viscous_exponent() ||
           stiffness_n_m != 0.0 || transition_time_s != 0.0 || has_lost_motion() || series_compliance_m_per_n != 0.0;
  }
  bool operator==(const LawShape&) const = default;
};

/// exp(−rate |I|^q) of a current law, |I| raised only when q ≠ 1 (so that q = 1
/// is Eq. 4.2–4.3's exp(−rate |I|) to the bit); discrepancy::CurrentLaw::at
/// evaluates its laws with it too.
inline double current_law_decay(double rate_per_a, double abs_current_a, double exponent) noexcept {
  return std::exp(-rate_per_a * (exponent == 1.0 ? abs_current_a : std::pow(abs_current_a, exponent)));
}

/// Coulomb (yield) force f_c(I, PR), Eq. 5.10; with PR = 1 it is Eq. 4.2.
/// The laws depend on the magnitude |I| of the coil current: a back-driven
/// (negative) current magnetizes the fluid just as a positive one does.
/// `current_exponent` q bends the law as LawShape says (1: Eq. 4.2).
inline double coulomb_force_n(const BinghamParams& p, double current_a, double participant_ratio = 1.0,
                              double current_exponent = 1.0) noexcept {
  const double i = std::fabs(current_a);
  const double b = participant_ratio * p.fc_b_n;
  return b + (p.fc_a_n - b) * current_law_decay(p.fc_c_per_a, i, current_exponent);
}

/// Viscous coefficient c_0(I, PR), Eq. 5.11; with PR = 1 it is Eq. 4.3.
/// `current_exponent` q bends the law as LawShape says (1: Eq. 4.3).
inline double viscous_coeff_ns_m(const BinghamParams& p, double current_a, double participant_ratio = 1.0,
                                 double current_exponent = 1.0) noexcept {
  const double i = std::fabs(current_a);
  const double b = participant_ratio * p.c0_b_ns_m;
  return b + (p.c0_a_ns_m - b) * current_law_decay(p.c0_c_per_a, i, current_exponent);
}

/// Transition function, Eq. 4.4: |v|/v_TF below v_TF, 1 above.
inline double transition_factor(const BinghamParams& p, double velocity_m_s) noexcept {
  const double s = std::fabs(velocity_m_s);
  return s <= p.v_tf_m_s ? s / p.v_tf_m_s : 1.0;
}

/// Damper force, Eq. 4.1 (PR = 1) or Eq. 5.12, multiplied by the transition
/// function Eq. 4.4. Sign: positive when the damper resists positive velocity.
inline double damper_force_n(const BinghamParams& p, double current_a, double velocity_m_s,
                             double participant_ratio = 1.0) noexcept {
  const double sgn = velocity_m_s > 0.0 ? 1.0 : (velocity_m_s < 0.0 ? -1.0 : 0.0);
  const double bingham = coulomb_force_n(p, current_a, participant_ratio) * sgn +
                         viscous_coeff_ns_m(p, current_a, participant_ratio) * velocity_m_s;
  return transition_factor(p, velocity_m_s) * bingham;
}

}  // namespace mrd::physics
