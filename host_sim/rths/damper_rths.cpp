#include "host_sim/rths/damper_rths.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "host_sim/plant/stages.hpp"
#include "host_sim/rths/numerical_building.hpp"
#include "host_sim/rths/thesis_actuator.hpp"
#include "host_sim/structure/discrete_building.hpp"
#include "mrd/physics/mr_damper.hpp"

namespace mrd::rths {

DamperRthsResult run_damper_rths(const DamperRthsSpec& spec, const std::vector<double>& ground_accel_m_s2,
                                 run::Controller& controller, DamperRthsRecord* record) {
  const structure::BuildingParams& b = spec.plant.building;
  if (b.dampers.size() != 1) throw std::invalid_argument("run_damper_rths: one damper placement");
  if (spec.plant.kind != plant::PlantKind::kThesis) throw std::invalid_argument("run_damper_rths: thesis plant only");
  if (!(spec.delay_s >= 0.0 && spec.lag_s >= 0.0)) throw std::invalid_argument("run_damper_rths: negative delay or lag");
  const double t = spec.plant.step_s;
  NumericalBuilding numerical;  // the closed loop's stepping, isolators in sub-steps
  numerical.init(b, t);
  const structure::DiscreteBuilding& building = numerical.linear();
  physics::MrDamper damper;
  damper.init(spec.plant.damper, t, physics::settling_quotient_after_idle(spec.plant.idle_time_s, spec.plant.settling));
  controller.reset();
  DelayedServo servo(spec.delay_s, spec.lag_s, t);
  // The compensator's model of the specimen, driven by what the laboratory
  // knows (the measured stroke and rate and the commanded current).
  physics::MrDamper model = damper;
  const int element = static_cast<int>(b.dampers.front().element);
  // The command made at tick n from the state at t_{n+1} arrives at the
  // servo at t_{n+1+D} (D whole steps of delay): the numerical building's
  // own prediction over it (DamperCommandPredictor, thesis_actuator.hpp).
  const double count = b.dampers.front().count;
  std::optional<DamperCommandPredictor> predictor;
  std::optional<IsolatedCommandPredictor> isolated_predictor;
  if (b.isolators.empty())
    predictor.emplace(b, building, spec.delay_s, spec.lag_s, spec.model_force_scale);
  else
    isolated_predictor.emplace(b, numerical, t, spec.delay_s, spec.lag_s, spec.model_force_scale);

  std::vector<double> forces(building.force_elements().size(), 0.0);
  const auto& elements = building.force_elements();
  const std::size_t slot =
      static_cast<std::size_t>(std::lower_bound(elements.begin(), elements.end(), element) - elements.begin());
  std::vector<double> accel(static_cast<std::size_t>(b.dofs()), 0.0);

  DamperRthsResult r;
  double e2 = 0.0, x2 = 0.0, ev2 = 0.0, v2 = 0.0;
  for (std::size_t n = 0; n < ground_accel_m_s2.size(); ++n) {
    const double target_m = building.element_deformation_m(element);
    const double x_a = servo.position_m();
    const double v_a = servo.velocity_m_s();
    const double f = damper.force_n(v_a, x_a);
    building.abs_accel_m_s2(accel.data());
    control::ControllerInput in;
    in.tick = n;
    in.damper_disp_m = static_cast<float>(x_a);
    in.damper_force_n = static_cast<float>(f);
    in.ground_accel_m_s2 = static_cast<float>(ground_accel_m_s2[n]);
    in.base_accel_m_s2 = static_cast<float>(accel[0]);
    in.coil_current_a = static_cast<float>(damper.current_a());
    const control::ControllerOutput out = controller.step(in);
    const double current_a =
        plant::command_stage_a(plant::CoilDrive{static_cast<double>(out.current_command_a), out.drive_enable});
    damper.step(current_a, v_a, x_a);
    model.step(current_a, v_a, x_a);
    forces[slot] = count * f;
    const double base_before_m = building.base_disp_m();
    r.peak_base_displacement_m = std::max(r.peak_base_displacement_m, std::fabs(base_before_m));
    r.peak_damper_force_n = std::max(r.peak_damper_force_n, std::fabs(f));
    r.peak_tracking_error_m = std::max(r.peak_tracking_error_m, std::fabs(x_a - target_m));
    e2 += (x_a - target_m) * (x_a - target_m);
    x2 += target_m * target_m;
    const double target_rate_m_s = building.element_rate_m_s(element);
    ev2 += (v_a - target_rate_m_s) * (v_a - target_rate_m_s);
    v2 += target_rate_m_s * target_rate_m_s;
    numerical.step(ground_accel_m_s2[n], forces.data());
    const ServoCommand c =
        !spec.compensate ? ServoCommand{building.element_deformation_m(element), building.element_rate_m_s(element)}
        : predictor      ? predictor->predict(building, ground_accel_m_s2, n + 1, model, current_a)
                         : isolated_predictor->predict(numerical, ground_accel_m_s2, n + 1, model, current_a);
    servo.step(c.position_m, c.rate_m_s);
    if (record != nullptr) {
      record->time_s.push_back(static_cast<double>(n) * t);
      record->target_m.push_back(target_m);
      record->actuator_m.push_back(x_a);
      record->actuator_velocity_m_s.push_back(v_a);
      record->command_m.push_back(c.position_m);
      record->force_n.push_back(f);
      record->current_a.push_back(current_a);
      record->base_displacement_m.push_back(base_before_m);
    }
  }
  // The last state reached counts too (as in the closed loop's summary).
  r.peak_base_displacement_m = std::max(r.peak_base_displacement_m, std::fabs(building.base_disp_m()));
  r.rms_tracking_error_pct = x2 > 0.0 ? 100.0 * std::sqrt(e2 / x2) : 0.0;
  r.rms_velocity_error_pct = v2 > 0.0 ? 100.0 * std::sqrt(ev2 / v2) : 0.0;
  return r;
}

}  // namespace mrd::rths
