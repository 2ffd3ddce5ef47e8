#include "host_sim/structure/building.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mrd/units.hpp"

namespace mrd::structure {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("building: " + what);
}

std::string at(const char* field, std::size_t i) { return std::string(field) + "[" + std::to_string(i) + "]"; }

bool finite_positive(double v) { return std::isfinite(v) && v > 0.0; }

/// Shear-chain assembly of element values e[0..N−1]: e[0] ties DOF 0 to the
/// ground, e[i] ties DOF i to DOF i−1 (Fig. 6.2).
Matrix assemble_chain(const std::vector<double>& e) {
  const int n = static_cast<int>(e.size());
  Matrix out = Matrix::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    out(i, i) += e[i];
    if (i > 0) {
      out(i - 1, i - 1) += e[i];
      out(i - 1, i) -= e[i];
      out(i, i - 1) -= e[i];
    }
  }
  return out;
}

/// The linear stiffness an isolator adds to element 0, N/m.
double isolator_linear_stiffness(const BuildingParams& p, const Isolator& iso) {
  if (const auto* lr = std::get_if<LeadRubberBearing>(&iso)) return lr->count * lr->post_yield_stiffness_n_m;
  const auto& fp = std::get<FrictionPendulumBearing>(iso);
  return fp.count * bearing_weight_n(p, fp) / fp.radius_m;
}

void validate_isolator(const Isolator& iso, std::size_t i) {
  const std::string name = at("isolator", i);
  auto common = [&](unsigned count, double dy, double n, double capacity) {
    require(count >= 1, name + ".count must be at least 1");
    require(finite_positive(dy), name + ".yield_displacement_m must be finite and > 0");
    require(std::isfinite(n) && n >= 1.0 && n <= 10.0, name + ".exponent must be in [1, 10]");
    require(std::isfinite(capacity) && capacity >= 0.0, name + ".displacement_capacity_m must be finite and >= 0");
  };
  if (const auto* lr = std::get_if<LeadRubberBearing>(&iso)) {
    common(lr->count, lr->yield_displacement_m, lr->exponent, lr->displacement_capacity_m);
    require(finite_positive(lr->characteristic_strength_n), name + ".characteristic_strength_n must be finite and > 0");
    require(std::isfinite(lr->post_yield_stiffness_n_m) && lr->post_yield_stiffness_n_m >= 0.0,
            name + ".post_yield_stiffness_n_m must be finite and >= 0");
    return;
  }
  const auto& fp = std::get<FrictionPendulumBearing>(iso);
  common(fp.count, fp.yield_displacement_m, fp.exponent, fp.displacement_capacity_m);
  require(finite_positive(fp.radius_m), name + ".radius_m must be finite and > 0");
  require(std::isfinite(fp.friction_slow) && fp.friction_slow >= 0.0 && fp.friction_slow < 1.0,
          name + ".friction_slow must be in [0, 1)");
  require(std::isfinite(fp.friction_fast) && fp.friction_fast >= fp.friction_slow && fp.friction_fast < 1.0,
          name + ".friction_fast must be in [friction_slow, 1)");
  require(std::isfinite(fp.rate_s_per_m) && fp.rate_s_per_m >= 0.0, name + ".rate_s_per_m must be finite and >= 0");
  require(std::isfinite(fp.weight_n) && fp.weight_n >= 0.0, name + ".weight_n must be finite and >= 0");
}

/// A full N×N matrix given by the user: N² finite entries, symmetric within
/// 1e-9 of its largest entry, and positive definite (`definite`) or
/// semi-definite within 1e-9 of its largest eigenvalue.
void validate_full(const std::vector<double>& v, std::size_t n, const std::string& name, bool definite) {
  require(v.size() == n * n, name + " must have N*N = " + std::to_string(n * n) + " entries");
  double largest = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    require(std::isfinite(v[i]), name + " entry " + std::to_string(i) + " must be finite");
    largest = std::max(largest, std::fabs(v[i]));
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      require(std::fabs(v[i * n + j] - v[j * n + i]) <= 1e-9 * largest,
              name + " must be symmetric: [" + std::to_string(i) + "][" + std::to_string(j) + "] differs from [" +
                  std::to_string(j) + "][" + std::to_string(i) + "]");
  const Eigen::Map<const Matrix> m(v.data(), static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  Eigen::SelfAdjointEigenSolver<Matrix> es(m, Eigen::EigenvaluesOnly);
  const double lo = es.eigenvalues().minCoeff();
  const double hi = std::max(es.eigenvalues().maxCoeff(), 0.0);
  if (definite)
    require(lo > 1e-12 * hi && hi > 0.0, name + " must be positive definite (its smallest eigenvalue is " +
                                            std::to_string(lo) + ")");
  else
    require(lo >= -1e-9 * hi, name + " must be positive semi-definite (its smallest eigenvalue is " +
                                  std::to_string(lo) + ")");
}

}  // namespace

void validate(const BuildingParams& p) {
  const std::size_t n = p.mass_kg.size();
  require(n >= 1 && n <= static_cast<std::size_t>(kMaxDofs),
          "mass_kg must have 1 to " + std::to_string(kMaxDofs) + " entries");
  require(p.story_stiffness_n_m.size() == n, "stiffness_n_m must have as many entries as mass_kg");
  require(p.rayleigh || p.story_damping_n_s_m.size() == n, "damping_n_s_m must have as many entries as mass_kg");
  for (std::size_t i = 0; i < n; ++i) {
    require(finite_positive(p.mass_kg[i]), at("mass_kg", i) + " must be finite and > 0");
    const double k = p.story_stiffness_n_m[i];
    if (p.stiffness_matrix_n_m.empty())
      require(std::isfinite(k) && (k > 0.0 || (i == 0 && k == 0.0)), at("stiffness_n_m", i) + " must be finite and > 0");
    if (!p.rayleigh && p.damping_matrix_n_s_m.empty()) {
      const double c = p.story_damping_n_s_m[i];
      require(std::isfinite(c) && c >= 0.0, at("damping_n_s_m", i) + " must be finite and >= 0");
    }
  }
  if (!p.stiffness_matrix_n_m.empty()) {
    validate_full(p.stiffness_matrix_n_m, n, "stiffness_matrix_n_m", true);
    require(p.isolators.empty(), "a building with a full stiffness matrix has no isolators");
  }
  if (!p.damping_matrix_n_s_m.empty()) {
    require(!p.rayleigh, "damping_matrix_n_s_m and rayleigh exclude each other");
    validate_full(p.damping_matrix_n_s_m, n, "damping_matrix_n_s_m", false);
  }
  if (p.rayleigh) {
    const RayleighDamping& r = *p.rayleigh;
    require(std::isfinite(r.ratio) && r.ratio > 0.0 && r.ratio < 1.0, "rayleigh.ratio must be in (0, 1)");
    require(r.mode_a >= 1 && r.mode_b >= 1 && r.mode_a <= static_cast<int>(n) && r.mode_b <= static_cast<int>(n) &&
                r.mode_a != r.mode_b,
            "rayleigh.modes must be two different modes in 1.." + std::to_string(n));
  }
  require(p.isolators.empty() || p.base == BaseKind::kIsolated, "a fixed-base building has no isolators");
  for (std::size_t i = 0; i < p.isolators.size(); ++i) validate_isolator(p.isolators[i], i);
  bool restoring =
      !p.stiffness_matrix_n_m.empty() || p.story_stiffness_n_m.empty() || p.story_stiffness_n_m[0] > 0.0;
  for (const Isolator& iso : p.isolators) restoring = restoring || isolator_linear_stiffness(p, iso) > 0.0;
  require(restoring, "no restoring force at element 0: stiffness_n_m[0] is 0 and no isolator restores");
  for (std::size_t i = 0; i < p.dampers.size(); ++i) {
    require(p.dampers[i].element < n, at("damper", i) + ".element must be in 0.." + std::to_string(n - 1));
    require(p.dampers[i].count >= 1, at("damper", i) + ".count must be at least 1");
  }
}

Matrix mass_matrix(const BuildingParams& p) {
  const int n = p.dofs();
  Matrix m = Matrix::Zero(n, n);
  for (int i = 0; i < n; ++i) m(i, i) = p.mass_kg[i];
  return m;
}

Matrix stiffness_matrix(const BuildingParams& p) {
  if (!p.stiffness_matrix_n_m.empty())
    return Eigen::Map<const Matrix>(p.stiffness_matrix_n_m.data(), p.dofs(), p.dofs()).transpose();
  Matrix k = assemble_chain(p.story_stiffness_n_m);
  for (const Isolator& iso : p.isolators) k(kBaseDof, kBaseDof) += isolator_linear_stiffness(p, iso);
  return k;
}

Matrix damping_matrix(const BuildingParams& p) {
  if (!p.damping_matrix_n_s_m.empty())
    return Eigen::Map<const Matrix>(p.damping_matrix_n_s_m.data(), p.dofs(), p.dofs()).transpose();
  if (!p.rayleigh) return assemble_chain(p.story_damping_n_s_m);
  const Matrix m = mass_matrix(p);
  const Matrix k = stiffness_matrix(p);
  Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> gs(k, m, Eigen::EigenvaluesOnly);
  if (gs.info() != Eigen::Success) throw std::invalid_argument("building: K φ = ω² M φ did not converge");
  const double wa = std::sqrt(gs.eigenvalues()(p.rayleigh->mode_a - 1));
  const double wb = std::sqrt(gs.eigenvalues()(p.rayleigh->mode_b - 1));
  const double zeta = p.rayleigh->ratio;
  const double a0 = 2.0 * zeta * wa * wb / (wa + wb);
  const double a1 = 2.0 * zeta / (wa + wb);
  return a0 * m + a1 * k;
}

double total_mass_kg(const BuildingParams& p) {
  double sum = 0.0;
  for (double m : p.mass_kg) sum += m;
  return sum;
}

double bearing_weight_n(const BuildingParams& p, const FrictionPendulumBearing& b) {
  if (b.weight_n > 0.0) return b.weight_n;
  return units::kStandardGravity_m_s2 * total_mass_kg(p) / static_cast<double>(b.count);
}

std::vector<int> force_elements(const BuildingParams& p) {
  std::vector<int> e;
  if (!p.isolators.empty()) e.push_back(kBaseDof);
  for (const DamperPlacement& d : p.dampers) e.push_back(static_cast<int>(d.element));
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  return e;
}

ContinuousModel continuous_model(const BuildingParams& p) {
  validate(p);
  const int n = p.dofs();
  Vector inv_mass(n);
  for (int i = 0; i < n; ++i) inv_mass(i) = 1.0 / p.mass_kg[i];
  const Matrix k = stiffness_matrix(p);
  const Matrix c = damping_matrix(p);

  ContinuousModel cm;
  cm.a = Matrix::Zero(2 * n, 2 * n);
  cm.a.topRightCorner(n, n).setIdentity();
  cm.a.bottomLeftCorner(n, n) = -(inv_mass.asDiagonal() * k);
  cm.a.bottomRightCorner(n, n) = -(inv_mass.asDiagonal() * c);

  const std::vector<int> elements = force_elements(p);
  cm.b = Matrix::Zero(2 * n, 1 + static_cast<int>(elements.size()));
  cm.b.bottomRows(n).col(0).setConstant(-1.0);
  for (std::size_t k_col = 0; k_col < elements.size(); ++k_col) {
    const int e = elements[k_col];
    const int col = 1 + static_cast<int>(k_col);
    cm.b(n + e, col) = -inv_mass(e);
    if (e > 0) cm.b(n + e - 1, col) = inv_mass(e - 1);
  }
  return cm;
}

}  // namespace mrd::structure
