#include "constant_current_damper.hpp"

#include <cmath>

#include "tests/independent_synth/damper_physics.hpp"

namespace ibuild {

double coil_current_a(double command_a, double t_s) {
  if (t_s <= 0.0) return 0.0;
  return command_a * (1.0 - indep::kCoilWeightSlow * std::exp(-t_s / indep::kCoilTauSlow_s) -
                      indep::kCoilWeightFast * std::exp(-t_s / indep::kCoilTauFast_s));
}

double damper_force_n(double velocity_m_s, double current_a) {
  // Fully mixed: participant ratio 1 (Eq. 5.10–5.11 reduce to Eq. 4.2–4.3).
  constexpr double kFullyMixed = 1.0;
  const double sgn = velocity_m_s > 0.0 ? 1.0 : (velocity_m_s < 0.0 ? -1.0 : 0.0);
  return indep::transition_factor(velocity_m_s) * (indep::yield_force_n(current_a, kFullyMixed) * sgn +
                                                   indep::viscous_coeff_n_s_m(current_a, kFullyMixed) * velocity_m_s);
}

}  // namespace ibuild
