#include "mrd/physics/settling.hpp"

#include <algorithm>
#include <cmath>

#include "mrd/units.hpp"

namespace mrd::physics {

double stokes_velocity_m_s(const SettlingParams& p) noexcept {
  // Eq. 5.1: V_t = g_c d_p² (ρ_s − ρ_l) / (18 η)
  const double d = p.particle_diameter_m;
  return p.gravity_m_s2 * d * d * (p.solid_density_kg_m3 - p.liquid_density_kg_m3) /
         (18.0 * p.viscosity_pa_s);
}

double hindered_velocity_m_s(const SettlingParams& p) noexcept {
  // Eq. 5.2: V_ts = V_t (1 − χ)^n
  return stokes_velocity_m_s(p) * std::pow(1.0 - p.solid_fraction, p.hindered_exponent);
}

double circular_segment_area_m2(double radius_m, double height_m) noexcept {
  // Bracket of Eq. 5.3: R² acos((R−h)/R) − (R−h) √(2Rh − h²)
  const double r = radius_m;
  if (height_m <= 0.0) return 0.0;
  if (height_m >= 2.0 * r) return units::kPi * r * r;
  const double d = r - height_m;
  return r * r * std::acos(d / r) - d * std::sqrt(2.0 * r * height_m - height_m * height_m);
}

double settled_volume_m3(const SettlingParams& p, double height_m) noexcept {
  // Eq. 5.3 with the shaft removed (Table 5.5): the shaft is coaxial, so its
  // bottom sits at R − r_s above the cylinder's bottom ("height to bottom of
  // shaft", 0.0616 m); the part of it below h is a segment of its own circle.
  const double r = 0.5 * p.inner_diameter_m;
  const double shaft_bottom_m = r - p.shaft_radius_m;
  const double area = circular_segment_area_m2(r, height_m) -
                      circular_segment_area_m2(p.shaft_radius_m, height_m - shaft_bottom_m);
  return p.fluid_length_m * area;
}

double settled_layer_height_m(const SettlingParams& p) noexcept {
  // Volume of particles: χ · V_fluid (Table 5.4 (a): 0.00665 m³). The settled
  // volume grows monotonically with h, so bisection on [0, ID] converges.
  const double target_m3 = p.solid_fraction * p.fluid_volume_m3;
  double lo = 0.0;
  double hi = p.inner_diameter_m;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (settled_volume_m3(p, mid) < target_m3) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

double max_settling_time_s(const SettlingParams& p) noexcept {
  if (p.measured_max_settling_time_s > 0.0) return p.measured_max_settling_time_s;
  // Eq. 5.4: the top particle falls from the inner diameter down to the top
  // of the fully settled layer at the hindered velocity.
  return (p.inner_diameter_m - settled_layer_height_m(p)) / hindered_velocity_m_s(p);
}

double settling_quotient(double idle_time_s, double max_settling_time_s) noexcept {
  // Eq. 5.5 as a fraction rather than a percentage, saturating at 1.
  if (!(idle_time_s > 0.0)) return 0.0;
  return std::min(idle_time_s / max_settling_time_s, 1.0);
}

double settling_quotient_after_idle(double idle_time_s, const SettlingParams& p) noexcept {
  return settling_quotient(idle_time_s, max_settling_time_s(p));  // Eq. 5.4, 5.5
}

}  // namespace mrd::physics
