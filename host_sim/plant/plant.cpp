#include "host_sim/plant/plant.hpp"

#include <algorithm>
#include <cmath>

namespace mrd::plant {

void Plant::init(const PlantSpec& spec) {
  spec_ = spec;
  building_.init(spec.building, spec.step_s);
  s_ = PlantSummary{};
  s_.sq = physics::settling_quotient_after_idle(spec.idle_time_s, spec.settling);
  damper_.init(spec.damper, spec.step_s, s_.sq);
  accel_ = building_.abs_accel_m_s2();
  floor_peak_m_s2_ = 0.0;
  state_ = PlantState{};
}

PlantSensors Plant::sense(double ground_accel_m_s2) noexcept {
  state_.ground_accel_m_s2 = ground_accel_m_s2;
  state_.base_disp_m = building_.base_disp_m();
  state_.base_vel_m_s = building_.base_vel_m_s();
  state_.damper_force_n = damper_.force_n(state_.base_vel_m_s);
  state_.base_accel_m_s2 = accel_(0);
  state_.coil_current_a = damper_.current_a();
  state_.participant_ratio = damper_.participant_ratio();
  return sensor_stage(state_);
}

void Plant::advance(const CoilDrive& drive) noexcept {
  // Damper state (coil current, participant ratio) to t_{n+1}.
  damper_.step(command_stage_a(drive), state_.base_vel_m_s);
  // Structure to t_{n+1} with a_g and F held.
  building_.step(state_.ground_accel_m_s2, state_.damper_force_n);

  s_.peak_base_displacement_m = std::max(s_.peak_base_displacement_m, std::fabs(state_.base_disp_m));
  s_.peak_damper_force_n = std::max(s_.peak_damper_force_n, std::fabs(state_.damper_force_n));
  s_.peak_current_a = std::max(s_.peak_current_a, std::fabs(state_.coil_current_a));
  accel_ = building_.abs_accel_m_s2();
  floor_peak_m_s2_ = accel_.tail<structure::kDofs - 1>().cwiseAbs().maxCoeff();
  s_.peak_superstructure_accel_m_s2 = std::max(s_.peak_superstructure_accel_m_s2, floor_peak_m_s2_);
  s_.peak_base_accel_m_s2 = std::max(s_.peak_base_accel_m_s2, std::fabs(accel_(0)));
  ++s_.ticks;
}

PlantSummary Plant::summary() const noexcept {
  PlantSummary s = s_;
  s.duration_s = static_cast<double>(s_.ticks) * spec_.step_s;
  // The last state reached (after the final step) counts too.
  s.peak_base_displacement_m = std::max(s.peak_base_displacement_m, std::fabs(building_.base_disp_m()));
  s.final_participant_ratio = damper_.participant_ratio();
  return s;
}

}  // namespace mrd::plant
