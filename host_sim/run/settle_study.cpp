#include "host_sim/run/settle_study.hpp"

namespace mrd::run {

SettleSummary settle_study(double idle_time_s, const physics::SettlingParams& sp,
                           const physics::ParticipantRatioParams& pp) {
  SettleSummary s;
  s.idle_time_s = idle_time_s;
  s.settling_velocity_m_s = physics::stokes_velocity_m_s(sp);
  s.hindered_settling_velocity_m_s = physics::hindered_velocity_m_s(sp);
  s.settled_layer_height_m = physics::settled_layer_height_m(sp);
  s.max_settling_time_s = physics::max_settling_time_s(sp);
  s.sq = physics::settling_quotient_after_idle(idle_time_s, sp);
  s.pr = physics::pr_coefficients(pp, s.sq);
  return s;
}

}  // namespace mrd::run
