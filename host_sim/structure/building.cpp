#include "host_sim/structure/building.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mrd::structure {
namespace {

void require(bool ok, const char* what, int i) {
  if (!ok) throw std::invalid_argument(std::string("building parameters: ") + what + " [" + std::to_string(i) + "]");
}

/// Shear-building assembly for story elements e[0..5]: e[0] ties DOF 0 to the
/// ground, e[i] ties DOF i to DOF i−1 (Fig. 6.2).
Matrix6 assemble_tridiagonal(const std::array<double, kDofs>& e) {
  Matrix6 out = Matrix6::Zero();
  for (int i = 0; i < kDofs; ++i) {
    out(i, i) += e[i];
    if (i > 0) {
      out(i - 1, i - 1) += e[i];
      out(i - 1, i) -= e[i];
      out(i, i - 1) -= e[i];
    }
  }
  return out;
}

}  // namespace

void validate(const BuildingParams& p) {
  for (int i = 0; i < kDofs; ++i) {
    require(std::isfinite(p.mass_kg[i]) && p.mass_kg[i] > 0.0, "mass_kg must be finite and > 0", i);
    require(std::isfinite(p.story_stiffness_n_m[i]) && p.story_stiffness_n_m[i] > 0.0,
            "story_stiffness_n_m must be finite and > 0", i);
    require(std::isfinite(p.story_damping_n_s_m[i]) && p.story_damping_n_s_m[i] >= 0.0,
            "story_damping_n_s_m must be finite and >= 0", i);
  }
}

Matrix6 mass_matrix(const BuildingParams& p) {
  Matrix6 m = Matrix6::Zero();
  for (int i = 0; i < kDofs; ++i) m(i, i) = p.mass_kg[i];
  return m;
}

Matrix6 damping_matrix(const BuildingParams& p) { return assemble_tridiagonal(p.story_damping_n_s_m); }

Matrix6 stiffness_matrix(const BuildingParams& p) { return assemble_tridiagonal(p.story_stiffness_n_m); }

double total_mass_kg(const BuildingParams& p) {
  double sum = 0.0;
  for (double m : p.mass_kg) sum += m;
  return sum;
}

ContinuousModel continuous_model(const BuildingParams& p) {
  validate(p);
  Vector6 inv_mass;
  for (int i = 0; i < kDofs; ++i) inv_mass(i) = 1.0 / p.mass_kg[i];
  const Matrix6 k = stiffness_matrix(p);
  const Matrix6 c = damping_matrix(p);

  ContinuousModel cm;
  cm.a.setZero();
  cm.a.topRightCorner<kDofs, kDofs>().setIdentity();
  cm.a.bottomLeftCorner<kDofs, kDofs>() = -(inv_mass.asDiagonal() * k);
  cm.a.bottomRightCorner<kDofs, kDofs>() = -(inv_mass.asDiagonal() * c);

  cm.b.setZero();
  cm.b.bottomRows<kDofs>().col(0).setConstant(-1.0);
  cm.b(kDofs + kBaseDof, 1) = -inv_mass(kBaseDof);
  return cm;
}

}  // namespace mrd::structure
