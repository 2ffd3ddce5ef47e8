#include "host_sim/peers/plant.hpp"

#include <algorithm>
#include <cmath>

#include "host_sim/excitation/ground_motion.hpp"
#include "mrd/units.hpp"

namespace mrd::peers {

void PlantModel::init(const PlantSpec& spec) {
  spec_ = spec;
  building_.init(spec.building, spec.step_s);
  s_ = PlantSummary{};
  s_.sq = physics::settling_quotient(units::years_to_s(spec.idle_years), physics::max_settling_time_s(spec.settling));
  damper_.init(spec.damper, spec.step_s, s_.sq);
  accel_ = building_.abs_accel_m_s2();
}

PlantSensors PlantModel::sense(double ground_accel_m_s2) noexcept {
  ag_ = ground_accel_m_s2;
  xb_ = building_.base_disp_m();
  vb_ = building_.base_vel_m_s();
  force_n_ = damper_.force_n(vb_);
  PlantSensors out;
  out.damper_disp_m = static_cast<float>(xb_);
  out.damper_force_n = static_cast<float>(force_n_);
  out.ground_accel_m_s2 = static_cast<float>(ag_);
  out.base_accel_m_s2 = static_cast<float>(accel_(0));
  out.coil_current_a = static_cast<float>(damper_.current_a());
  return out;
}

void PlantModel::advance(double command_a) noexcept {
  const double current_now_a = damper_.current_a();
  damper_.step(command_a, vb_);
  building_.step(ag_, force_n_);

  s_.peak_base_displacement_m = std::max(s_.peak_base_displacement_m, std::fabs(xb_));
  s_.peak_damper_force_n = std::max(s_.peak_damper_force_n, std::fabs(force_n_));
  s_.peak_current_a = std::max(s_.peak_current_a, std::fabs(current_now_a));
  accel_ = building_.abs_accel_m_s2();
  const double floor_peak = accel_.tail<structure::kDofs - 1>().cwiseAbs().maxCoeff();
  s_.peak_superstructure_accel_m_s2 = std::max(s_.peak_superstructure_accel_m_s2, floor_peak);
  s_.peak_base_accel_m_s2 = std::max(s_.peak_base_accel_m_s2, std::fabs(accel_(0)));
  ++s_.ticks;
}

PlantSummary PlantModel::summary() const noexcept {
  PlantSummary s = s_;
  s.duration_s = static_cast<double>(s_.ticks) * spec_.step_s;
  s.peak_base_displacement_m = std::max(s.peak_base_displacement_m, std::fabs(building_.base_disp_m()));
  s.final_participant_ratio = damper_.participant_ratio();
  return s;
}

std::vector<double> load_ground_accel(const std::filesystem::path& record, double pga_g, double step_s,
                                      double duration_s) {
  const excitation::GroundMotion raw = excitation::read_ground_motion(record);
  const excitation::GroundMotion scaled = excitation::scaled_to_pga(raw, pga_g * units::kStandardGravity_m_s2);
  return duration_s > 0.0 ? excitation::resample_linear(scaled, step_s, duration_s)
                          : excitation::resample_linear(scaled, step_s);
}

}  // namespace mrd::peers
