#include "host_sim/plant/hardware_sensors.hpp"

#include <algorithm>
#include <cmath>

namespace mrd::plant {

double SensorChannel::step() const noexcept { return 2.0 * range / std::ldexp(1.0, bits); }

double SensorChannel::convert(double value) const noexcept {
  const double q = step();
  return std::clamp(q * std::round(value / q), -range, range);
}

void HardwareSensors::init(const HardwareSensorSpec& s) {
  lvdt_ = {s.lvdt_range_m, s.lvdt_bits, s.lvdt_noise_rms_m, s.lvdt_offset_m};
  load_cell_ = {s.load_cell_range_n, s.load_cell_bits, s.load_cell_noise_rms_n, s.load_cell_offset_n};
  current_ = {s.current_range_a, s.current_bits, s.current_noise_rms_a, s.current_offset_a};
  rng_.seed(s.seed);
  unit_.reset();
}

double HardwareSensors::read(const SensorChannel& c, double value) {
  return c.convert(value + c.offset + c.noise_rms * unit_(rng_));
}

PlantSensors HardwareSensors::measure(const PlantState& s, double stroke_offset_m) {
  PlantSensors out;
  out.damper_disp_m = static_cast<float>(read(lvdt_, s.base_disp_m + stroke_offset_m));
  out.damper_force_n = static_cast<float>(read(load_cell_, s.damper_force_n));
  out.ground_accel_m_s2 = static_cast<float>(s.ground_accel_m_s2);
  out.base_accel_m_s2 = static_cast<float>(s.base_accel_m_s2);
  out.coil_current_a = static_cast<float>(read(current_, s.coil_current_a));
  return out;
}

}  // namespace mrd::plant
