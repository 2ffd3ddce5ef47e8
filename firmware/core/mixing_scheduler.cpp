// plan_mixing and the double (reference) build of the mixing scheduler.
#include "firmware/core/mixing_scheduler.hpp"

#include "firmware/core/mixing_scheduler_impl.hpp"

#include <cmath>

#include "mrd/units.hpp"

namespace mrd::fw {

MixingPlan plan_mixing(const MixingSchedulerConfig& c, double volume_needed_m3) noexcept {
  MixingPlan p;
  p.amplitude_m = c.max_amplitude_m;
  const double omega_limit = c.max_velocity_m_s / p.amplitude_m;  // rad/s at the velocity limit
  const double f_limit_hz = omega_limit / (2.0 * units::kPi);
  p.frequency_hz = c.preferred_frequency_hz < f_limit_hz ? c.preferred_frequency_hz : f_limit_hz;
  const double per_cycle_m3 = 4.0 * p.amplitude_m * c.flow_area_m2;  // ∫|ẋ|dt over one period is 4A
  double n = volume_needed_m3 > 0.0 ? std::ceil(volume_needed_m3 / per_cycle_m3) : 0.0;
  if (n < static_cast<double>(c.min_cycles)) n = static_cast<double>(c.min_cycles);
  if (n > static_cast<double>(c.max_cycles)) n = static_cast<double>(c.max_cycles);
  p.cycles = static_cast<std::uint32_t>(n);
  p.volume_m3 = static_cast<double>(p.cycles) * per_cycle_m3;
  p.duration_s = static_cast<double>(p.cycles) / p.frequency_hz;
  p.duration_ticks = c.period_s > 0.0 ? static_cast<std::uint64_t>(std::llround(p.duration_s / c.period_s)) : 0;
  const double omega = 2.0 * units::kPi * p.frequency_hz;
  p.peak_velocity_m_s = omega * p.amplitude_m;
  p.peak_accel_m_s2 = omega * omega * p.amplitude_m;
  return p;
}

template class BasicMixingScheduler<Float64Policy>;

}  // namespace mrd::fw
