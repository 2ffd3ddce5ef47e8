#include "host_sim/structure/isolators.hpp"

#include <algorithm>
#include <cmath>

#include "host_sim/structure/building.hpp"

namespace mrd::structure {
namespace {

/// |z|ⁿ: one product for the usual n = 2 (exact to the last bit, where pow()
/// is within 0.52 ulp), z itself for n = 1, pow() otherwise.
double abs_power(double a, double n) noexcept {
  if (n == 2.0) return a * a;
  if (n == 1.0) return a;
  return std::pow(a, n);
}

/// dz/du of the Bouc–Wen variable for a deformation moving in direction `s` (±1).
double slope(double z, double s, double dy, double n) noexcept {
  const double sgn = (s * z) > 0.0 ? 1.0 : ((s * z) < 0.0 ? -1.0 : 0.0);
  return (1.0 - abs_power(std::fabs(z), n) * (kBoucWenGamma * sgn + kBoucWenBeta)) / dy;
}

/// Friction coefficient μ(v) = μ_fast − (μ_fast − μ_slow)·exp(−a·|v|).
double friction(double mu_slow, double mu_fast, double a, double v) noexcept {
  return mu_fast - (mu_fast - mu_slow) * std::exp(-a * std::fabs(v));
}

}  // namespace

void IsolatorBank::init(const BuildingParams& p) {
  groups_.clear();
  capacity_m_ = 0.0;
  initial_stiffness_n_m_ = 0.0;
  smallest_dy_m_ = 0.0;
  for (const Isolator& iso : p.isolators) {
    Group g;
    double capacity = 0.0;
    if (const auto* lr = std::get_if<LeadRubberBearing>(&iso)) {
      g.count = lr->count;
      g.strength_n = lr->characteristic_strength_n;
      g.linear_n_m = lr->post_yield_stiffness_n_m;
      g.dy_m = lr->yield_displacement_m;
      g.exponent = lr->exponent;
      capacity = lr->displacement_capacity_m;
      initial_stiffness_n_m_ += g.count * g.strength_n / g.dy_m;
    } else {
      const auto& fp = std::get<FrictionPendulumBearing>(iso);
      g.pendulum = true;
      g.count = fp.count;
      g.strength_n = bearing_weight_n(p, fp);
      g.linear_n_m = g.strength_n / fp.radius_m;
      g.mu_slow = fp.friction_slow;
      g.mu_fast = fp.friction_fast;
      g.rate_s_per_m = fp.rate_s_per_m;
      g.dy_m = fp.yield_displacement_m;
      g.exponent = fp.exponent;
      capacity = fp.displacement_capacity_m;
      initial_stiffness_n_m_ += g.count * g.mu_fast * g.strength_n / g.dy_m;
    }
    if (capacity > 0.0) capacity_m_ = capacity_m_ > 0.0 ? std::min(capacity_m_, capacity) : capacity;
    smallest_dy_m_ = smallest_dy_m_ > 0.0 ? std::min(smallest_dy_m_, g.dy_m) : g.dy_m;
    groups_.push_back(g);
  }
}

void IsolatorBank::reset() noexcept {
  for (Group& g : groups_) g.z = 0.0;
}

double IsolatorBank::hysteretic_force_n(double rate_m_s) const noexcept {
  double f = 0.0;
  for (const Group& g : groups_) {
    const double per_bearing = g.pendulum
                                   ? friction(g.mu_slow, g.mu_fast, g.rate_s_per_m, rate_m_s) * g.strength_n * g.z
                                   : g.strength_n * g.z;
    f += g.count * per_bearing;
  }
  return f;
}

double IsolatorBank::total_force_n(double u_m, double rate_m_s) const noexcept {
  double linear = 0.0;
  for (const Group& g : groups_) linear += g.count * g.linear_n_m * u_m;
  return linear + hysteretic_force_n(rate_m_s);
}

void IsolatorBank::advance(double du_m) noexcept {
  if (du_m == 0.0 || !std::isfinite(du_m)) return;
  const double s = du_m > 0.0 ? 1.0 : -1.0;
  for (Group& g : groups_) {
    const int pieces = std::max(1, static_cast<int>(std::ceil(std::fabs(du_m) / (g.dy_m / 8.0))));
    const double h = du_m / pieces;
    double z = g.z;
    for (int k = 0; k < pieces; ++k) {
      const double k1 = slope(z, s, g.dy_m, g.exponent);
      const double k2 = slope(z + 0.5 * h * k1, s, g.dy_m, g.exponent);
      const double k3 = slope(z + 0.5 * h * k2, s, g.dy_m, g.exponent);
      const double k4 = slope(z + h * k3, s, g.dy_m, g.exponent);
      z += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    // |z| ≤ 1 bounds the Bouc–Wen variable with β = γ (the envelope z = ±1 is a fixed point).
    g.z = std::clamp(z, -1.0, 1.0);
  }
}

}  // namespace mrd::structure
