#include "nonlinear_building.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "constant_current_damper.hpp"

namespace ibuild {

double bouc_wen_rate_per_s(double z, double velocity_m_s, double yield_displacement_m, double exponent) {
  const double vz = velocity_m_s * z;
  const double sgn = vz > 0.0 ? 1.0 : (vz < 0.0 ? -1.0 : 0.0);
  return velocity_m_s / yield_displacement_m *
         (1.0 - std::pow(std::fabs(z), exponent) * (kBoucWenGamma * sgn + kBoucWenBeta));
}

double pendulum_friction(const IsolatorGroup& g, double velocity_m_s) {
  return g.friction_fast - (g.friction_fast - g.friction_slow) * std::exp(-g.rate_s_per_m * std::fabs(velocity_m_s));
}

BuildingEquations::BuildingEquations(Building b) : b_(std::move(b)), n_(b_.dofs()) {
  const auto bad = [&](const std::string& what) { throw std::invalid_argument("building '" + b_.name + "': " + what); };
  if (n_ < 1) bad("no degree of freedom");
  if (b_.stiffness_n_m.size() != b_.mass_kg.size()) bad("stiffness and mass lengths differ");
  if (b_.rayleigh) {
    if (!b_.damping_n_s_m.empty()) bad("both element dashpots and Rayleigh damping");
    rayleigh_ = rayleigh_coefficients(b_, *b_.rayleigh);
  } else if (b_.damping_n_s_m.size() != b_.mass_kg.size()) {
    bad("damping and mass lengths differ");
  }
  for (double m : b_.mass_kg) {
    if (!(m > 0.0)) bad("a mass is not positive");
  }
  for (const DamperGroup& d : b_.dampers) {
    if (d.element < 0 || d.element >= n_) bad("a damper's element is out of range");
  }
  for (const IsolatorGroup& g : b_.isolators) {
    if (!(g.yield_displacement_m > 0.0) || g.count == 0) bad("a bearing group needs a yield displacement and a count");
    double w = g.weight_n;
    if (g.kind == IsolatorKind::kFrictionPendulum && !(w > 0.0)) w = total_weight_n(b_) / g.count;
    bearing_weight_n_.push_back(w);
  }
  restoring_n_.assign(static_cast<std::size_t>(n_), 0.0);
}

double BuildingEquations::isolator_group_force_n(std::size_t group, const std::vector<double>& y) const {
  const IsolatorGroup& g = b_.isolators[group];
  const double u = y[0];
  const double z = y[static_cast<std::size_t>(2 * n_) + group];
  if (g.kind == IsolatorKind::kLeadRubber) {
    return g.count * (g.post_yield_stiffness_n_m * u + g.characteristic_strength_n * z);
  }
  const double w = bearing_weight_n_[group];
  const double v = y[static_cast<std::size_t>(n_)];
  return g.count * (w / g.radius_m * u + pendulum_friction(g, v) * w * z);
}

double BuildingEquations::restoring_forces(double current_a, const std::vector<double>& y,
                                           std::vector<double>* damper_n) const {
  const auto n = static_cast<std::size_t>(n_);
  const double* x = y.data();
  const double* v = y.data() + n;
  std::vector<double>& r = restoring_n_;
  std::fill(r.begin(), r.end(), 0.0);
  // Elements: spring (and dashpot) force f_i = k_i u_i + c_i u̇_i, +f_i on DOF i, −f_i on DOF i−1.
  for (std::size_t i = 0; i < n; ++i) {
    const double u = x[i] - (i > 0 ? x[i - 1] : 0.0);
    const double du = v[i] - (i > 0 ? v[i - 1] : 0.0);
    const double c = b_.rayleigh ? rayleigh_.a1_s * b_.stiffness_n_m[i] : b_.damping_n_s_m[i];
    const double f = b_.stiffness_n_m[i] * u + c * du;
    r[i] += f;
    if (i > 0) r[i - 1] -= f;
  }
  if (b_.rayleigh) {
    for (std::size_t i = 0; i < n; ++i) r[i] += rayleigh_.a0_per_s * b_.mass_kg[i] * v[i];
  }
  double isolators = 0.0;
  for (std::size_t g = 0; g < b_.isolators.size(); ++g) isolators += isolator_group_force_n(g, y);
  r[0] += isolators;
  if (damper_n) damper_n->assign(b_.dampers.size(), 0.0);
  for (std::size_t d = 0; d < b_.dampers.size(); ++d) {
    const auto e = static_cast<std::size_t>(b_.dampers[d].element);
    const double du = v[e] - (e > 0 ? v[e - 1] : 0.0);
    const double f = damper_force_n(du, current_a);
    if (damper_n) (*damper_n)[d] = f;
    r[e] += b_.dampers[d].count * f;
    if (e > 0) r[e - 1] -= b_.dampers[d].count * f;
  }
  return isolators;
}

void BuildingEquations::derivative(double ground_accel_m_s2, double current_a, const std::vector<double>& y,
                                   std::vector<double>& dydt) const {
  const auto n = static_cast<std::size_t>(n_);
  restoring_forces(current_a, y, nullptr);
  for (std::size_t i = 0; i < n; ++i) {
    dydt[i] = y[n + i];
    dydt[n + i] = -ground_accel_m_s2 - restoring_n_[i] / b_.mass_kg[i];
  }
  for (std::size_t g = 0; g < b_.isolators.size(); ++g) {
    const IsolatorGroup& iso = b_.isolators[g];
    dydt[2 * n + g] = bouc_wen_rate_per_s(y[2 * n + g], y[n], iso.yield_displacement_m, iso.exponent);
  }
}

void BuildingEquations::forces(double current_a, const std::vector<double>& y, Forces& out) const {
  out.isolator_force_n = restoring_forces(current_a, y, &out.damper_force_n);
  out.abs_accel_m_s2.resize(static_cast<std::size_t>(n_));
  for (std::size_t i = 0; i < out.abs_accel_m_s2.size(); ++i) out.abs_accel_m_s2[i] = -restoring_n_[i] / b_.mass_kg[i];
}

Dp45Options default_options(const Building& b) {
  Dp45Options o;
  o.h_max_s = 0.5e-3;
  constexpr double kFastestBearing_m_s = 1.0;
  for (const IsolatorGroup& g : b.isolators) o.h_max_s = std::min(o.h_max_s, g.yield_displacement_m / kFastestBearing_m_s / 5.0);
  return o;
}

Peaks simulate_earthquake(const Building& b, const GroundRecord& record, const RunSpec& spec, Dp45Stats* stats) {
  const BuildingEquations eq(b);
  const auto n = static_cast<std::size_t>(eq.dofs());
  const bool fixed = b.base == Base::kFixed;
  const std::size_t first_story = fixed ? 0 : 1;
  std::vector<double> y(eq.state_size(), 0.0);
  auto rhs = [&](double t, const std::vector<double>& s, std::vector<double>& dydt) {
    eq.derivative(record.at(t), coil_current_a(spec.command_a, t), s, dydt);
  };
  Peaks p;
  Forces f;
  auto observe = [&](double t, const std::vector<double>& s) {
    eq.forces(coil_current_a(spec.command_a, t), s, f);
    p.base_displacement_m = std::max(p.base_displacement_m, std::fabs(s[0]));
    p.base_velocity_m_s = std::max(p.base_velocity_m_s, std::fabs(s[n]));
    p.isolator_force_n = std::max(p.isolator_force_n, std::fabs(f.isolator_force_n));
    for (double fd : f.damper_force_n) p.damper_force_n = std::max(p.damper_force_n, std::fabs(fd));
    for (std::size_t i = first_story; i < n; ++i) {
      p.superstructure_accel_m_s2 = std::max(p.superstructure_accel_m_s2, std::fabs(f.abs_accel_m_s2[i]));
      p.story_drift_m = std::max(p.story_drift_m, std::fabs(s[i] - (i > 0 ? s[i - 1] : 0.0)));
    }
  };
  Dp45Stats local;
  Dp45Stats& st = stats ? *stats : local;
  double h = spec.options.h_first_s;
  // Record sample by sample: a_g is linear within each interval.
  double t = 0.0;
  for (std::size_t k = 1; t < spec.duration_s; ++k) {
    const double t_next = std::min(spec.duration_s, record.step_s * static_cast<double>(k));
    if (t_next > t) integrate_dp45(rhs, t, t_next, y, h, spec.options, st, observe);
    t = t_next;
  }
  return p;
}

}  // namespace ibuild
