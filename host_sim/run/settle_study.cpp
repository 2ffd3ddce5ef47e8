#include "host_sim/run/settle_study.hpp"

#include "mrd/units.hpp"

namespace mrd::run {

SettleSummary settle_study(double idle_years, const physics::SettlingParams& sp,
                           const physics::ParticipantRatioParams& pp) {
  SettleSummary s;
  s.idle_years = idle_years;
  s.settling_velocity_m_s = physics::stokes_velocity_m_s(sp);
  s.hindered_settling_velocity_m_s = physics::hindered_velocity_m_s(sp);
  s.settled_layer_height_m = physics::settled_layer_height_m(sp);
  const double t_max_s = physics::max_settling_time_s(sp);
  s.max_settling_time_years = units::s_to_years(t_max_s);
  s.sq = physics::settling_quotient(units::years_to_s(idle_years), t_max_s);
  s.pr = physics::pr_coefficients(pp, s.sq);
  return s;
}

}  // namespace mrd::run
