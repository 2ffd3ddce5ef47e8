#include "host_sim/structure/discrete_building.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>

namespace mrd::structure {

DiscreteModel discretize_zoh(const ContinuousModel& model, double dt_s) {
  if (!std::isfinite(dt_s) || dt_s <= 0.0) {
    throw std::invalid_argument("discretization step must be finite and > 0 s, got " + std::to_string(dt_s));
  }
  // Dynamic-size matrices for the one-time setup (the exponential and the
  // eigen-decomposition below): they run once, and the fixed 14×14 and
  // 12×12 forms unroll into more code to compile.
  constexpr int kAug = kStates + kInputs;
  Eigen::MatrixXd aug = Eigen::MatrixXd::Zero(kAug, kAug);
  aug.topLeftCorner<kStates, kStates>() = model.a * dt_s;
  aug.topRightCorner<kStates, kInputs>() = model.b * dt_s;
  const Eigen::MatrixXd e = aug.exp();

  DiscreteModel d;
  d.phi = e.topLeftCorner<kStates, kStates>();
  d.gamma = e.topRightCorner<kStates, kInputs>();
  return d;
}

DiscreteBuilding::DiscreteBuilding() noexcept
    : phi_(StateMatrix::Identity()),
      gamma_(InputMatrix::Zero()),
      accel_rows_(Eigen::Matrix<double, kDofs, kStates>::Zero()),
      t_(StateMatrix::Identity()),
      t_inv_(StateMatrix::Identity()),
      blocks_(Eigen::Matrix<double, kStates, 2>::Zero()),
      gamma_q_(InputMatrix::Zero()),
      q_(State::Zero()) {}

namespace {

/// Real modal basis of A: for each complex pair λ = σ ± iω with eigenvector
/// a ± ib, the columns a, b. Returns false when A has a real eigenvalue.
bool real_modal_basis(const StateMatrix& a, StateMatrix& t) {
  const Eigen::MatrixXd a_dyn = a;
  Eigen::EigenSolver<Eigen::MatrixXd> es(a_dyn);
  if (es.info() != Eigen::Success) return false;
  const auto values = es.eigenvalues();
  const auto vectors = es.eigenvectors();
  int col = 0;
  for (int k = 0; k < kStates; ++k) {
    if (std::fabs(values(k).imag()) <= 1e-12 * std::abs(values(k))) return false;
    if (values(k).imag() < 0.0) continue;  // take one of each conjugate pair
    if (col + 2 > kStates) return false;
    t.col(col) = vectors.col(k).real();
    t.col(col + 1) = vectors.col(k).imag();
    col += 2;
  }
  return col == kStates;
}

}  // namespace

void DiscreteBuilding::init(const BuildingParams& params, double dt_s) {
  const ContinuousModel cm = continuous_model(params);
  const DiscreteModel d = discretize_zoh(cm, dt_s);
  phi_ = d.phi;
  gamma_ = d.gamma;
  inv_base_mass_per_kg_ = 1.0 / params.mass_kg[kBaseDof];
  dt_s_ = dt_s;

  modal_ = false;
  t_.setIdentity();
  StateMatrix t;
  if (real_modal_basis(cm.a, t)) {
    const StateMatrix t_inv = t.inverse();
    const StateMatrix phi_q = t_inv * phi_ * t;
    // Accept the modal form only when everything off the 2×2 diagonal
    // blocks is rounding noise.
    double off = 0.0;
    for (int r = 0; r < kStates; ++r) {
      for (int c = 0; c < kStates; ++c) {
        if (r / 2 != c / 2) off = std::max(off, std::fabs(phi_q(r, c)));
      }
    }
    if (off <= 1e-12 && std::isfinite(phi_q.sum())) {
      modal_ = true;
      t_ = t;
      t_inv_ = t_inv;
      for (int r = 0; r < kStates; ++r) {
        const int c0 = (r / 2) * 2;
        blocks_(r, 0) = phi_q(r, c0);
        blocks_(r, 1) = phi_q(r, c0 + 1);
      }
    }
  }
  if (!modal_) t_inv_.setIdentity();
  gamma_q_ = t_inv_ * gamma_;
  accel_rows_ = cm.a.bottomRows<kDofs>() * t_;
  reset();
}

void DiscreteBuilding::reset() noexcept {
  q_.setZero();
  held_force_n_ = 0.0;
  steps_ = 0;
}

void DiscreteBuilding::set_state(const State& z) noexcept {
  q_.noalias() = t_inv_ * z;
  held_force_n_ = 0.0;
}

void DiscreteBuilding::step(double ground_accel_m_s2, double damper_force_n) noexcept {
  State next;
  if (modal_) {
    for (int j = 0; j < kStates; j += 2) {
      const double q0 = q_(j);
      const double q1 = q_(j + 1);
      next(j) = blocks_(j, 0) * q0 + blocks_(j, 1) * q1;
      next(j + 1) = blocks_(j + 1, 0) * q0 + blocks_(j + 1, 1) * q1;
    }
  } else {
    next.noalias() = phi_.lazyProduct(q_);  // coefficient-wise: unrolled for fixed sizes
  }
  next.noalias() += gamma_q_.col(0) * ground_accel_m_s2;
  next.noalias() += gamma_q_.col(1) * damper_force_n;
  q_ = next;
  held_force_n_ = damper_force_n;
  ++steps_;
}

double DiscreteBuilding::abs_accel_m_s2(int i) const noexcept {
  double a = accel_rows_.row(i).dot(q_);
  if (i == kBaseDof) a -= inv_base_mass_per_kg_ * held_force_n_;
  return a;
}

Vector6 DiscreteBuilding::abs_accel_m_s2() const noexcept {
  Vector6 a;
  a.noalias() = accel_rows_.lazyProduct(q_);
  a(kBaseDof) -= inv_base_mass_per_kg_ * held_force_n_;
  return a;
}

}  // namespace mrd::structure
