#include "host_sim/run/closed_loop.hpp"

#include <algorithm>
#include <cmath>

#include "mrd/units.hpp"
#include "host_sim/run/controller.hpp"

namespace mrd::run {

ClosedLoopSummary run_closed_loop(const ClosedLoopSpec& spec, const std::vector<double>& ground_accel_m_s2,
                                  Controller& controller, ClosedLoopRecord* record) {
  structure::DiscreteBuilding building;
  building.init(spec.building, spec.step_s);

  ClosedLoopSummary s;
  s.sq = physics::settling_quotient(units::years_to_s(spec.idle_years),
                                    physics::max_settling_time_s(spec.settling));
  physics::MrDamper damper(spec.damper, spec.step_s, s.sq);
  controller.reset();

  const std::size_t n = ground_accel_m_s2.size();
  s.duration_s = static_cast<double>(n) * spec.step_s;
  if (record) {
    for (auto* v : {&record->time_s, &record->ground_accel_m_s2, &record->base_disp_m, &record->base_vel_m_s,
                    &record->damper_force_n, &record->desired_force_n, &record->command_a, &record->current_a,
                    &record->pr, &record->roof_accel_m_s2, &record->peak_floor_accel_m_s2}) {
      v->clear();
      v->reserve(n);
    }
  }

  control::ControllerInput in;
  structure::Vector6 accel = building.abs_accel_m_s2();
  for (std::size_t k = 0; k < n; ++k) {
    const double ag = ground_accel_m_s2[k];
    const double xb = building.base_disp_m();
    const double vb = building.base_vel_m_s();
    // 1. sensors at t_k
    const double force_n = damper.force_n(vb);
    in.tick = k;
    in.damper_disp_m = static_cast<float>(xb);
    in.damper_force_n = static_cast<float>(force_n);
    in.ground_accel_m_s2 = static_cast<float>(ag);
    in.base_accel_m_s2 = static_cast<float>(accel(0));
    in.coil_current_a = static_cast<float>(damper.current_a());
    // 2. controller
    const control::ControllerOutput out = controller.step(in);
    const double command_a = out.drive_enable ? static_cast<double>(out.current_command_a) : 0.0;
    // 3. damper state (coil current, participant ratio) to t_{k+1}
    const double current_now_a = damper.current_a();
    const double pr_now = damper.participant_ratio();
    damper.step(command_a, vb);
    // 4. structure to t_{k+1} with a_g and F held
    building.step(ag, force_n);

    s.peak_base_displacement_m = std::max(s.peak_base_displacement_m, std::fabs(xb));
    s.peak_damper_force_n = std::max(s.peak_damper_force_n, std::fabs(force_n));
    s.peak_current_a = std::max(s.peak_current_a, std::fabs(current_now_a));
    accel = building.abs_accel_m_s2();
    const double floor_peak = accel.tail<structure::kDofs - 1>().cwiseAbs().maxCoeff();
    s.peak_superstructure_accel_m_s2 = std::max(s.peak_superstructure_accel_m_s2, floor_peak);
    s.peak_base_accel_m_s2 = std::max(s.peak_base_accel_m_s2, std::fabs(accel(0)));

    if (record) {
      record->time_s.push_back(static_cast<double>(k) * spec.step_s);
      record->ground_accel_m_s2.push_back(ag);
      record->base_disp_m.push_back(xb);
      record->base_vel_m_s.push_back(vb);
      record->damper_force_n.push_back(force_n);
      record->desired_force_n.push_back(out.desired_force_n);
      record->command_a.push_back(command_a);
      record->current_a.push_back(current_now_a);
      record->pr.push_back(pr_now);
      record->roof_accel_m_s2.push_back(accel(structure::kDofs - 1));
      record->peak_floor_accel_m_s2.push_back(floor_peak);
    }
  }
  // The last state reached (after the final step) counts too.
  s.peak_base_displacement_m = std::max(s.peak_base_displacement_m, std::fabs(building.base_disp_m()));
  s.final_participant_ratio = damper.participant_ratio();
  return s;
}

}  // namespace mrd::run
