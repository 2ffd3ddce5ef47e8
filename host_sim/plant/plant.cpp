#include "host_sim/plant/plant.hpp"

#include <algorithm>
#include <cmath>

namespace mrd::plant {

const char* plant_kind_name(PlantKind k) noexcept { return k == PlantKind::kHardware ? "hardware" : "thesis"; }

physics::MrDamperParams hardware_damper_params(physics::MrDamperParams thesis) noexcept {
  thesis.coil.tau_fast_s = kPassThroughTau_s;
  return thesis;
}

void Plant::init(const PlantSpec& spec) {
  spec_ = spec;
  building_.init(spec.building, spec.step_s);
  s_ = PlantSummary{};
  s_.sq = physics::settling_quotient_after_idle(spec.idle_time_s, spec.settling);
  const bool hardware = spec.kind == PlantKind::kHardware;
  damper_.init(hardware ? hardware_damper_params(spec.damper) : spec.damper, spec.step_s, s_.sq);
  thermal_.init(spec.thermal, spec.step_s);
  figures_ = CoilFigureCounter{};
  if (hardware) {
    drive_.init(spec.hardware.drive, spec.hardware.coil);
    sensors_.init(spec.hardware.sensors);
  }
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
  state_.participant_ratio = damper_.participant_ratio();
  if (spec_.kind == PlantKind::kHardware) {
    state_.coil_current_a = drive_.current_a();
    return sensors_.measure(state_, spec_.hardware.stroke_offset_m);
  }
  state_.coil_current_a = damper_.current_a();
  return sensor_stage(state_);
}

void Plant::advance(const CoilDrive& drive) noexcept {
  if (spec_.kind == PlantKind::kHardware) {
    // Drive and coil over the step, then the field (the damper's current)
    // and participant ratio to t_{n+1}.
    thermal_.step(drive_.step(drive, spec_.step_s));
    damper_.step(drive_.current_a(), state_.base_vel_m_s);
  } else {
    // Damper state (coil current, participant ratio) to t_{n+1}.
    damper_.step(command_stage_a(drive), state_.base_vel_m_s);
    thermal_.step(state_.coil_current_a * state_.coil_current_a);
  }
  figures_.add(state_.coil_current_a, command_stage_a(drive), thermal_.rise_k());
  // Structure to t_{n+1} with a_g and F held.
  building_.step(state_.ground_accel_m_s2, state_.damper_force_n);

  s_.peak_base_displacement_m = std::max(s_.peak_base_displacement_m, std::fabs(state_.base_disp_m));
  s_.peak_damper_force_n = std::max(s_.peak_damper_force_n, std::fabs(state_.damper_force_n));
  s_.peak_base_velocity_m_s = std::max(s_.peak_base_velocity_m_s, std::fabs(state_.base_vel_m_s));
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
  s.coil = figures_.figures(spec_.step_s);
  return s;
}

}  // namespace mrd::plant
