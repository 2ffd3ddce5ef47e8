#include "signals.hpp"

#include <cmath>
#include <numbers>

namespace indep {

double Rng::uniform() {
  // The top 53 bits as a fraction.
  return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

double Rng::log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }

double Rng::normal() {
  double u1 = uniform();
  while (u1 <= 0.0) u1 = uniform();
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

double Motion::displacement_m(double t_s) const {
  double x = offset_m + ramp_m_s * t_s;
  for (const auto& s : sines) x += s.amplitude_m * std::sin(2.0 * std::numbers::pi * s.frequency_hz * t_s + s.phase_rad);
  return x;
}

double Motion::velocity_m_s(double t_s) const {
  double v = ramp_m_s;
  for (const auto& s : sines) {
    const double w = 2.0 * std::numbers::pi * s.frequency_hz;
    v += s.amplitude_m * w * std::cos(w * t_s + s.phase_rad);
  }
  return v;
}

double CurrentProgram::at(double t_s) const {
  double level = levels_a.empty() ? 0.0 : levels_a.front();
  for (std::size_t j = 1; j < start_s.size() && j < levels_a.size(); ++j) {
    if (t_s >= start_s[j]) level = levels_a[j];
  }
  return level;
}

}  // namespace indep
