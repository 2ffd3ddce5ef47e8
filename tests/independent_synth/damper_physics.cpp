#include "damper_physics.hpp"

#include <cmath>

namespace indep {
namespace {

/// One exponential law of Table 5.6: b + (a − b) exp(−c SQ).
double table_5_6(double a, double b, double c, double sq) { return b + (a - b) * std::exp(-c * sq); }

}  // namespace

PrLaw pr_law(double sq) {
  return PrLaw{
      table_5_6(1.0, 0.10, 7.0, sq),     // Eq. 5.6: a_initial, b_initial, c_initial
      table_5_6(1.0, 0.605, 4.5, sq),    // Eq. 5.7: a_final, b_final, c_final
      table_5_6(5.474, 0.0, 3.650, sq),  // Eq. 5.8: a_rise, b_rise, c_rise
  };
}

double participant_ratio(const PrLaw& law, double volume_l) {
  return law.b_pr + (law.a_pr - law.b_pr) * std::exp(-law.c_pr_per_l * volume_l);
}

double yield_force_n(double current_a, double pr) {
  return pr * kFcB_n + (kFcA_n - pr * kFcB_n) * std::exp(-kFcC_per_a * std::abs(current_a));
}

double viscous_coeff_n_s_m(double current_a, double pr) {
  return pr * kC0B_n_s_m + (kC0A_n_s_m - pr * kC0B_n_s_m) * std::exp(-kC0C_per_a * std::abs(current_a));
}

double transition_factor(double vel_m_s) {
  const double s = std::abs(vel_m_s);
  return s < kTransitionVelocity_m_s ? s / kTransitionVelocity_m_s : 1.0;
}

}  // namespace indep
