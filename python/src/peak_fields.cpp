#include "python/src/peak_fields.hpp"

namespace mrd::python {

const std::vector<std::string>& peak_names() {
  static const std::vector<std::string> names{
      "peak_base_displacement_m",    "peak_damper_force_n",        "peak_base_velocity_m_s",
      "peak_superstructure_accel_m_s2", "peak_base_accel_m_s2",    "peak_current_a",
      "peak_isolator_force_n",       "peak_story_drift_m",         "peak_damper_stroke_m",
      "final_participant_ratio",     "sq",                         "duration_s",
      "ticks",                       "peak_coil_current_a",        "rms_coil_current_a",
      "time_above_rated_s",          "command_changes_per_s",      "peak_coil_temperature_rise_k",
  };
  return names;
}

std::vector<double> peak_values(const plant::PlantSummary& s) {
  return {s.peak_base_displacement_m,
          s.peak_damper_force_n,
          s.peak_base_velocity_m_s,
          s.peak_superstructure_accel_m_s2,
          s.peak_base_accel_m_s2,
          s.peak_current_a,
          s.peak_isolator_force_n,
          s.peak_story_drift_m,
          s.peak_damper_stroke_m,
          s.final_participant_ratio,
          s.sq,
          s.duration_s,
          static_cast<double>(s.ticks),
          s.coil.peak_coil_current_a,
          s.coil.rms_coil_current_a,
          s.coil.time_above_rated_s,
          s.coil.command_changes_per_s,
          s.coil.peak_coil_temperature_rise_k};
}

}  // namespace mrd::python
