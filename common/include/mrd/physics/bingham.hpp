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

/// Coulomb (yield) force f_c(I, PR), Eq. 5.10; with PR = 1 it is Eq. 4.2.
/// The laws depend on the magnitude |I| of the coil current: a back-driven
/// (negative) current magnetizes the fluid just as a positive one does.
inline double coulomb_force_n(const BinghamParams& p, double current_a,
                              double participant_ratio = 1.0) noexcept {
  const double i = std::fabs(current_a);
  const double b = participant_ratio * p.fc_b_n;
  return b + (p.fc_a_n - b) * std::exp(-p.fc_c_per_a * i);
}

/// Viscous coefficient c_0(I, PR), Eq. 5.11; with PR = 1 it is Eq. 4.3.
inline double viscous_coeff_ns_m(const BinghamParams& p, double current_a,
                                 double participant_ratio = 1.0) noexcept {
  const double i = std::fabs(current_a);
  const double b = participant_ratio * p.c0_b_ns_m;
  return b + (p.c0_a_ns_m - b) * std::exp(-p.c0_c_per_a * i);
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
