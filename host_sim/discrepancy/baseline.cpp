#include "host_sim/discrepancy/baseline.hpp"

#include <algorithm>
#include <cmath>

#include "mrd/physics/bingham.hpp"
#include "mrd/physics/damper_laws.hpp"

namespace mrd::discrepancy {

const char* gap_basis_name(GapBasis basis) noexcept {
  switch (basis) {
    case GapBasis::calibration_records: return "calibration_records";
    case GapBasis::check_records: return "check_records";
    case GapBasis::left_out_motions: return "left_out_motions";
  }
  return "calibration_records";
}

const char* gap_basis_phrase(GapBasis basis) noexcept {
  switch (basis) {
    case GapBasis::calibration_records: return "the records it was calibrated on";
    case GapBasis::check_records: return "the records it was calibrated on and the check records";
    case GapBasis::left_out_motions:
      return "the records it was calibrated on and each of their motions left out of a fit to the others";
  }
  return "the records it was calibrated on";
}

const char* base_law_name(BaseLaw law) noexcept {
  switch (law) {
    case BaseLaw::bouc_wen: return "bouc_wen";
    case BaseLaw::spencer: return "spencer";
    case BaseLaw::bingham: break;
  }
  return "bingham";
}

std::string baseline_form_name(const Baseline& b) {
  return std::string(base_law_name(b.law)) + (b.has_tanh_transition() ? "_tanh" : "") +
         (b.has_transition_time() ? "+transition_time" : "") +
         (b.has_viscous_lost_motion() ? "+viscous_lost_motion" : (b.has_lost_motion() ? "+lost_motion" : "")) +
         (b.has_current_exponent() ? "+current_exponent" : "") + (b.has_bingham_stiffness() ? "+stiffness" : "") + (b.has_viscous_exponent() ? "+viscous_exponent" : "") +
         (b.has_series_compliance() ? "+series_compliance" : "");
}

double CurrentLaw::at(double current_a, double participant_ratio) const noexcept {
  const double b = participant_ratio * limit;
  const double i = std::fabs(current_a);
  return b + (at_zero - b) * physics::current_law_decay(rate_per_a, i, current_exponent);
}

double Baseline::force_scale_n() const noexcept {
  if (law == BaseLaw::spencer) {
    const double f = std::fabs(physics::spencer_yield_force_n(spencer.at(range.current_max_a)));
    return std::isfinite(f) ? f : 0.0;
  }
  return std::fabs(yield_n.at(range.current_max_a));
}

physics::SpencerParams published_lab_spencer() {
  physics::SpencerParams p;
  p.k0_n_m = 1.501e-4 * 1e3;
  p.k1_n_m = 1.2388 * 1e3;
  p.x0_m = 2.309e-3 * 1e-3;
  p.alpha_n_m = 15.221 * 1e3;
  p.alpha_per_a_n_m = 41.508 * 1e3;
  p.alpha_per_a2_n_m = -38.152 * 1e3;
  p.gamma_per_m_pow_n = 1.8941 * 1e6;
  p.gamma_rate_per_a = 3.6561;
  p.beta_over_gamma = 1.0;
  p.c0_ns_m = 0.9249 * 1e3;
  p.c0_per_a_ns_m = 7.626 * 1e3;
  p.c1_ns_m = 9.867 * 1e3;
  p.c1_per_a_ns_m = 78.337 * 1e3;
  p.a = 300.0;
  p.n = 2.0;
  return p;
}

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
