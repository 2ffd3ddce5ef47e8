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

double Chirp::phase_rad(double t_s) const {
  return 2.0 * std::numbers::pi * (start_hz * t_s + 0.5 * rate_hz_per_s * t_s * t_s);
}

double Motion::displacement_m(double t_s) const {
  double x = offset_m + ramp_m_s * t_s;
  for (const auto& s : sines) x += s.amplitude_m * std::sin(2.0 * std::numbers::pi * s.frequency_hz * t_s + s.phase_rad);
  if (chirp.amplitude_m != 0.0) x += chirp.amplitude_m * std::sin(chirp.phase_rad(t_s));
  return x;
}

double Motion::velocity_m_s(double t_s) const {
  double v = ramp_m_s;
  for (const auto& s : sines) {
    const double w = 2.0 * std::numbers::pi * s.frequency_hz;
    v += s.amplitude_m * w * std::cos(w * t_s + s.phase_rad);
  }
  // d/dt sin φ(t) = φ'(t) cos φ, φ' = 2π f(t).
  if (chirp.amplitude_m != 0.0) {
    v += chirp.amplitude_m * 2.0 * std::numbers::pi * chirp.frequency_hz(t_s) * std::cos(chirp.phase_rad(t_s));
  }
  return v;
}

double Motion::acceleration_m_s2(double t_s) const {
  double a = 0.0;
  for (const auto& s : sines) {
    const double w = 2.0 * std::numbers::pi * s.frequency_hz;
    a -= s.amplitude_m * w * w * std::sin(w * t_s + s.phase_rad);
  }
  // d²/dt² sin φ = φ'' cos φ − φ'² sin φ, φ'' = 2π r.
  if (chirp.amplitude_m != 0.0) {
    const double w = 2.0 * std::numbers::pi * chirp.frequency_hz(t_s);
    const double phi = chirp.phase_rad(t_s);
    a += chirp.amplitude_m * (2.0 * std::numbers::pi * chirp.rate_hz_per_s * std::cos(phi) - w * w * std::sin(phi));
  }
  return a;
}

double CurrentProgram::at(double t_s) const {
  double level = levels_a.empty() ? 0.0 : levels_a.front();
  for (std::size_t j = 1; j < start_s.size() && j < levels_a.size(); ++j) {
    if (t_s >= start_s[j]) level = levels_a[j];
  }
  return level;
}

}  // namespace indep
