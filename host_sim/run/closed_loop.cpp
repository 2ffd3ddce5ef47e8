#include "host_sim/run/closed_loop.hpp"

#include "host_sim/run/controller.hpp"

namespace mrd::run {
namespace {

void start_record(ClosedLoopRecord& record, std::size_t n, const plant::Plant& plant) {
  for (auto* v : {&record.time_s, &record.ground_accel_m_s2, &record.base_disp_m, &record.base_vel_m_s,
                  &record.damper_force_n, &record.desired_force_n, &record.command_a, &record.current_a, &record.pr,
                  &record.roof_accel_m_s2, &record.peak_floor_accel_m_s2, &record.isolator_force_n}) {
    v->clear();
  }
  for (auto* v : {&record.time_s, &record.ground_accel_m_s2, &record.base_disp_m, &record.base_vel_m_s,
                  &record.damper_force_n, &record.desired_force_n, &record.command_a, &record.current_a, &record.pr,
                  &record.roof_accel_m_s2, &record.peak_floor_accel_m_s2}) {
    v->reserve(n);
  }
  record.story_elements.clear();
  for (int e = plant.first_story(); e < plant.building().dofs(); ++e) record.story_elements.push_back(e);
  record.story_drift_m.assign(record.story_elements.size(), {});
  for (auto& v : record.story_drift_m) v.reserve(n);
}

}  // namespace

control::ControllerOutput closed_loop_tick(plant::Plant& plant, Controller& controller, double ground_accel_m_s2,
                                           std::size_t tick) {
  const plant::PlantSensors sensors = plant.sense(ground_accel_m_s2);
  control::ControllerInput in;
  in.tick = tick;
  in.damper_disp_m = static_cast<float>(sensors.damper_disp_m);
  in.damper_force_n = static_cast<float>(sensors.damper_force_n);
  in.ground_accel_m_s2 = static_cast<float>(sensors.ground_accel_m_s2);
  in.base_accel_m_s2 = static_cast<float>(sensors.base_accel_m_s2);
  in.coil_current_a = static_cast<float>(sensors.coil_current_a);
  const control::ControllerOutput out = controller.step(in);
  plant.advance(coil_drive(out));
  return out;
}

plant::PlantSummary run_closed_loop(const plant::PlantSpec& spec, const std::vector<double>& ground_accel_m_s2,
                                    Controller& controller, ClosedLoopRecord* record) {
  plant::Plant plant;
  plant.init(spec);
  controller.reset();

  const std::size_t n = ground_accel_m_s2.size();
  const bool isolated = !spec.building.isolators.empty();
  if (record) {
    start_record(*record, n, plant);
    if (isolated) record->isolator_force_n.reserve(n);
  }

  for (std::size_t k = 0; k < n; ++k) {
    const control::ControllerOutput out = closed_loop_tick(plant, controller, ground_accel_m_s2[k], k);

    if (record) {
      const plant::PlantState& s = plant.state();
      record->time_s.push_back(static_cast<double>(k) * spec.step_s);
      record->ground_accel_m_s2.push_back(s.ground_accel_m_s2);
      record->base_disp_m.push_back(s.base_disp_m);
      record->base_vel_m_s.push_back(s.base_vel_m_s);
      record->damper_force_n.push_back(s.damper_force_n);
      record->desired_force_n.push_back(out.desired_force_n);
      record->command_a.push_back(plant::command_stage_a(coil_drive(out)));
      record->current_a.push_back(s.coil_current_a);
      record->pr.push_back(s.participant_ratio);
      record->roof_accel_m_s2.push_back(plant.roof_accel_m_s2());
      record->peak_floor_accel_m_s2.push_back(plant.peak_floor_accel_m_s2());
      if (isolated) record->isolator_force_n.push_back(plant.isolator_force_n());
      for (std::size_t st = 0; st < record->story_elements.size(); ++st) {
        record->story_drift_m[st].push_back(plant.element_deformation_m(record->story_elements[st]));
      }
    }
  }
  return plant.summary();
}

}  // namespace mrd::run
