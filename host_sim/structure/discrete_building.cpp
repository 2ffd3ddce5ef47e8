#include "structure/discrete_building.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>

namespace mrd::structure {

DiscreteModel discretize_zoh(const ContinuousModel& model, double dt_s) {
  if (!std::isfinite(dt_s) || dt_s <= 0.0) {
    throw std::invalid_argument("discretization step must be finite and > 0 s, got " + std::to_string(dt_s));
  }
  constexpr int kAug = kStates + kInputs;
  using Augmented = Eigen::Matrix<double, kAug, kAug>;
  Augmented aug = Augmented::Zero();
  aug.topLeftCorner<kStates, kStates>() = model.a * dt_s;
  aug.topRightCorner<kStates, kInputs>() = model.b * dt_s;
  const Augmented e = aug.exp();

  DiscreteModel d;
  d.phi = e.topLeftCorner<kStates, kStates>();
  d.gamma = e.topRightCorner<kStates, kInputs>();
  return d;
}

DiscreteBuilding::DiscreteBuilding() noexcept
    : phi_(StateMatrix::Identity()),
      gamma_(InputMatrix::Zero()),
      accel_rows_(Eigen::Matrix<double, kDofs, kStates>::Zero()),
      z_(State::Zero()) {}

void DiscreteBuilding::init(const BuildingParams& params, double dt_s) {
  const ContinuousModel cm = continuous_model(params);
  const DiscreteModel d = discretize_zoh(cm, dt_s);
  phi_ = d.phi;
  gamma_ = d.gamma;
  accel_rows_ = cm.a.bottomRows<kDofs>();
  inv_base_mass_per_kg_ = 1.0 / params.mass_kg[kBaseDof];
  dt_s_ = dt_s;
  reset();
}

void DiscreteBuilding::reset() noexcept {
  z_.setZero();
  held_force_n_ = 0.0;
  steps_ = 0;
}

void DiscreteBuilding::set_state(const State& z) noexcept {
  z_ = z;
  held_force_n_ = 0.0;
}

void DiscreteBuilding::step(double ground_accel_m_s2, double damper_force_n) noexcept {
  State next;
  next.noalias() = phi_.lazyProduct(z_);  // coefficient-wise: unrolled for fixed sizes, no GEMV kernel
  next.noalias() += gamma_.col(0) * ground_accel_m_s2;
  next.noalias() += gamma_.col(1) * damper_force_n;
  z_ = next;
  held_force_n_ = damper_force_n;
  ++steps_;
}

double DiscreteBuilding::abs_accel_m_s2(int i) const noexcept {
  double a = accel_rows_.row(i).dot(z_);
  if (i == kBaseDof) a -= inv_base_mass_per_kg_ * held_force_n_;
  return a;
}

Vector6 DiscreteBuilding::abs_accel_m_s2() const noexcept {
  Vector6 a;
  a.noalias() = accel_rows_.lazyProduct(z_);
  a(kBaseDof) -= inv_base_mass_per_kg_ * held_force_n_;
  return a;
}

}  // namespace mrd::structure
