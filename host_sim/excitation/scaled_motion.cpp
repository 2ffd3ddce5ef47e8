#include "host_sim/excitation/scaled_motion.hpp"

#include "host_sim/excitation/ground_motion.hpp"
#include "mrd/units.hpp"

namespace mrd::excitation {

ScaledMotion load_scaled_motion(const std::filesystem::path& path, double pga_g, double step_s, double duration_s) {
  const GroundMotion raw = read_ground_motion(path);
  const double target_m_s2 = pga_g * units::kStandardGravity_m_s2;
  ScaledMotion m;
  m.name = raw.name;
  m.source = raw.source;
  m.scale_factor = scale_factor_for_pga(raw, target_m_s2);
  const GroundMotion scaled = scaled_to_pga(raw, target_m_s2);
  m.pga_m_s2 = scaled.pga_m_s2();
  m.accel_m_s2 = duration_s > 0.0 ? resample_linear(scaled, step_s, duration_s) : resample_linear(scaled, step_s);
  return m;
}

}  // namespace mrd::excitation
