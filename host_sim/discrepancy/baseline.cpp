#include "host_sim/discrepancy/baseline.hpp"

#include <algorithm>
#include <cmath>

#include "mrd/physics/damper_laws.hpp"

namespace mrd::discrepancy {

const char* base_law_name(BaseLaw law) noexcept { return law == BaseLaw::bouc_wen ? "bouc_wen" : "bingham"; }

std::string baseline_form_name(const Baseline& b) {
  return std::string(base_law_name(b.law)) + (b.has_tanh_transition() ? "_tanh" : "") +
         (b.has_transition_time() ? "+transition_time" : "") +
         (b.has_viscous_lost_motion() ? "+viscous_lost_motion" : (b.has_lost_motion() ? "+lost_motion" : ""));
}

double CurrentLaw::at(double current_a, double participant_ratio) const noexcept {
  const double b = participant_ratio * limit;
  return b + (at_zero - b) * std::exp(-rate_per_a * std::fabs(current_a));
}

double Baseline::force_scale_n() const noexcept { return std::fabs(yield_n.at(range.current_max_a)); }

Baseline thesis_baseline() {
  Baseline b;
  b.range.current_min_a = 0.0;
  b.range.current_max_a = 2.5;         // drive rating, §3.1
  b.range.velocity_max_m_s = 0.2491;   // Table 3.1
  b.range.force_peak_n = 200.0e3;      // the damper's rating
  return b;
}

double thesis_force_scale_n() { return thesis_baseline().force_scale_n(); }

double bouc_wen_step(double z, double v_m_s, double dt_s, double yield_disp_m) noexcept {
  // The closed loop's law over the stroke increment v·dt (one source for both).
  return physics::bouc_wen_z_after(z, v_m_s * dt_s, yield_disp_m);
}

}  // namespace mrd::discrepancy
