#include "host_sim/plant/plant.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrd::plant {

const char* plant_kind_name(PlantKind k) noexcept { return k == PlantKind::kHardware ? "hardware" : "thesis"; }

physics::MrDamperParams hardware_damper_params(physics::MrDamperParams thesis) noexcept {
  thesis.coil.tau_fast_s = kPassThroughTau_s;
  return thesis;
}

int structural_substeps(const structure::BuildingParams& building, double step_s) {
  if (building.isolators.empty()) return 1;
  structure::IsolatorBank bank;
  bank.init(building);
  constexpr double kMaxSubstep_s = 2.0e-4;
  constexpr double kMaxPhase_rad = 0.1;
  const double omega0 = std::sqrt(bank.initial_stiffness_n_m() / building.mass_kg[structure::kBaseDof]);
  const double h_max = std::min(kMaxSubstep_s, kMaxPhase_rad / omega0);
  return std::max(1, static_cast<int>(std::ceil(step_s / h_max - 1e-9)));
}

void Plant::init(const PlantSpec& spec) {
  spec_ = spec;
  const structure::BuildingParams& b = spec.building;
  structure::validate(b);
  if (b.dampers.empty()) throw std::invalid_argument("building: the plant needs at least one damper");
  substeps_ = structural_substeps(b, spec.step_s);
  building_.init(b, spec.step_s / substeps_);
  isolators_.init(b);
  first_story_ = b.base == structure::BaseKind::kFixed ? 0 : 1;

  const std::vector<int>& elements = building_.force_elements();
  auto slot_of = [&](int e) {
    return static_cast<int>(std::lower_bound(elements.begin(), elements.end(), e) - elements.begin());
  };
  damper_slot_.clear();
  damper_first_on_slot_.clear();
  for (const structure::DamperPlacement& d : b.dampers) {
    const int slot = slot_of(static_cast<int>(d.element));
    damper_first_on_slot_.push_back(std::find(damper_slot_.begin(), damper_slot_.end(), slot) == damper_slot_.end());
    damper_slot_.push_back(slot);
  }
  isolator_slot_ = isolators_.empty() ? -1 : slot_of(structure::kBaseDof);
  element_force_n_.assign(elements.size(), 0.0);
  damper_force_n_.assign(b.dampers.size(), 0.0);

  s_ = PlantSummary{};
  s_.sq = physics::settling_quotient_after_idle(spec.idle_time_s, spec.settling);
  const bool hardware = spec.kind == PlantKind::kHardware;
  dampers_.assign(b.dampers.size(), physics::MrDamper{});
  for (physics::MrDamper& d : dampers_) {
    d.init(hardware ? hardware_damper_params(spec.damper) : spec.damper, spec.step_s, s_.sq);
  }
  thermal_.init(spec.damper.coil_heat, spec.step_s);
  figures_ = CoilFigureCounter{spec.damper.rating.current_a};
  if (hardware) {
    drive_.init(spec.hardware.drive, coil_params(spec.damper.coil_heat.resistance_ohm, spec.damper.coil_inductance));
    sensors_.init(spec.hardware.sensors);
  }
  accel_.assign(static_cast<std::size_t>(b.dofs()), 0.0);
  building_.abs_accel_m_s2(accel_.data());
  floor_peak_m_s2_ = 0.0;
  isolator_force_n_ = 0.0;
  state_ = PlantState{};
}

PlantSensors Plant::sense(double ground_accel_m_s2) noexcept {
  const int sensed = static_cast<int>(spec_.building.dampers.front().element);
  const double x0 = building_.base_disp_m();
  state_.ground_accel_m_s2 = ground_accel_m_s2;
  state_.base_disp_m = sensed == structure::kBaseDof ? x0 : building_.element_deformation_m(sensed);
  state_.base_vel_m_s = building_.element_rate_m_s(sensed);
  // Each damper at its element's deformation rate and deformation (its stroke).
  state_.damper_force_n = dampers_.front().force_n(state_.base_vel_m_s, state_.base_disp_m);
  damper_force_n_.front() = state_.damper_force_n;
  for (std::size_t d = 1; d < dampers_.size(); ++d) {
    const int e = static_cast<int>(spec_.building.dampers[d].element);
    damper_force_n_[d] = dampers_[d].force_n(building_.element_rate_m_s(e), building_.element_deformation_m(e));
  }
  state_.base_accel_m_s2 = accel_[0];
  state_.participant_ratio = dampers_.front().participant_ratio();
  s_.peak_base_displacement_m = std::max(s_.peak_base_displacement_m, std::fabs(x0));
  if (spec_.kind == PlantKind::kHardware) {
    state_.coil_current_a = drive_.current_a();
    return sensors_.measure(state_, spec_.hardware.stroke_offset_m);
  }
  state_.coil_current_a = dampers_.front().current_a();
  return sensor_stage(state_);
}

void Plant::advance(const CoilDrive& drive) noexcept {
  const auto& placements = spec_.building.dampers;
  auto step_dampers = [&](double current_a) {
    // The structure is still at t_n: the rates and strokes sense() used.
    dampers_.front().step(current_a, state_.base_vel_m_s, state_.base_disp_m);
    for (std::size_t d = 1; d < dampers_.size(); ++d) {
      const int e = static_cast<int>(placements[d].element);
      dampers_[d].step(current_a, building_.element_rate_m_s(e), building_.element_deformation_m(e));
    }
  };
  if (spec_.kind == PlantKind::kHardware) {
    // Drive and coil over the step, then the field (the dampers' current)
    // and participant ratios to t_{n+1}.
    thermal_.step(drive_.step(drive, spec_.step_s));
    step_dampers(drive_.current_a());
  } else {
    // Damper states (coil current, participant ratio) to t_{n+1}.
    step_dampers(command_stage_a(drive));
    thermal_.step(state_.coil_current_a * state_.coil_current_a);
  }
  figures_.add(state_.coil_current_a, command_stage_a(drive), thermal_.rise_k());

  // Element forces held over the tick: count × one damper's force per placement.
  double dampers_on_base = 0.0;
  for (std::size_t d = 0; d < placements.size(); ++d) {
    const int slot = damper_slot_[d];
    const double f = placements[d].count == 1 ? damper_force_n_[d] : placements[d].count * damper_force_n_[d];
    element_force_n_[slot] = damper_first_on_slot_[d] ? f : element_force_n_[slot] + f;
    if (slot == isolator_slot_) dampers_on_base = element_force_n_[slot];
  }
  if (isolator_slot_ < 0) {
    // Structure to t_{n+1} with a_g and the forces held: one exact step.
    building_.step(state_.ground_accel_m_s2, element_force_n_.data());
  } else {
    for (int k = 0; k < substeps_; ++k) {
      const double u0 = building_.base_disp_m();
      element_force_n_[isolator_slot_] = dampers_on_base + isolators_.hysteretic_force_n(building_.base_vel_m_s());
      building_.step(state_.ground_accel_m_s2, element_force_n_.data());
      isolators_.advance(building_.base_disp_m() - u0);
    }
  }

  s_.peak_damper_stroke_m = std::max(s_.peak_damper_stroke_m, std::fabs(state_.base_disp_m));
  s_.peak_damper_force_n = std::max(s_.peak_damper_force_n, std::fabs(state_.damper_force_n));
  s_.peak_base_velocity_m_s = std::max(s_.peak_base_velocity_m_s, std::fabs(state_.base_vel_m_s));
  s_.peak_current_a = std::max(s_.peak_current_a, std::fabs(state_.coil_current_a));
  add_peaks_after_advance();
  ++s_.ticks;
}

void Plant::add_peaks_after_advance() noexcept {
  building_.abs_accel_m_s2(accel_.data());
  const int n = building_.dofs();
  floor_peak_m_s2_ = 0.0;
  for (int i = first_story_; i < n; ++i) floor_peak_m_s2_ = std::max(floor_peak_m_s2_, std::fabs(accel_[i]));
  s_.peak_superstructure_accel_m_s2 = std::max(s_.peak_superstructure_accel_m_s2, floor_peak_m_s2_);
  s_.peak_base_accel_m_s2 = std::max(s_.peak_base_accel_m_s2, std::fabs(accel_[0]));
  double below = first_story_ == 0 ? 0.0 : building_.disp_m(0);
  for (int i = first_story_; i < n; ++i) {
    const double x = building_.disp_m(i);
    s_.peak_story_drift_m = std::max(s_.peak_story_drift_m, std::fabs(x - below));
    below = x;
  }
  if (!isolators_.empty()) {
    isolator_force_n_ = isolators_.total_force_n(building_.base_disp_m(), building_.base_vel_m_s());
    s_.peak_isolator_force_n = std::max(s_.peak_isolator_force_n, std::fabs(isolator_force_n_));
  }
}

PlantSummary Plant::summary() const noexcept {
  PlantSummary s = s_;
  s.duration_s = static_cast<double>(s_.ticks) * spec_.step_s;
  // The last state reached (after the final step) counts too.
  s.peak_base_displacement_m = std::max(s.peak_base_displacement_m, std::fabs(building_.base_disp_m()));
  const int sensed = static_cast<int>(spec_.building.dampers.front().element);
  s.peak_damper_stroke_m = std::max(s.peak_damper_stroke_m, std::fabs(building_.element_deformation_m(sensed)));
  s.final_participant_ratio = dampers_.front().participant_ratio();
  s.coil = figures_.figures(spec_.step_s);
  return s;
}

}  // namespace mrd::plant
