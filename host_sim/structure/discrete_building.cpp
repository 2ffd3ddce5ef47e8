#include "host_sim/structure/discrete_building.hpp"

#include <algorithm>
#include <array>
#include <utility>
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
  const Eigen::Index states = model.a.rows();
  const Eigen::Index inputs = model.b.cols();
  Matrix aug = Matrix::Zero(states + inputs, states + inputs);
  aug.topLeftCorner(states, states) = model.a * dt_s;
  aug.topRightCorner(states, inputs) = model.b * dt_s;
  const Matrix e = aug.exp();

  DiscreteModel d;
  d.phi = e.topLeftCorner(states, states);
  d.gamma = e.topRightCorner(states, inputs);
  return d;
}

namespace {

/// Σ row[k·stride]·q[k] over k < N, summed by halves recursively:
/// (p0 + (p1 + p2)) + (p3 + (p4 + p5)) for N = 6, the order of Eigen's
/// fixed-size dot product of a strided matrix row. Unrolled at compile time.
template <int N>
inline double dot_halving_n(const double* row, Eigen::Index stride, const double* q) noexcept {
  if constexpr (N == 1) {
    return row[0] * q[0];
  } else {
    constexpr int kHalf = N / 2;
    return dot_halving_n<kHalf>(row, stride, q) + dot_halving_n<N - kHalf>(row + kHalf * stride, stride, q + kHalf);
  }
}

using DotFn = double (*)(const double*, Eigen::Index, const double*) noexcept;

template <std::size_t... I>
constexpr std::array<DotFn, sizeof...(I)> unrolled_dots(std::index_sequence<I...>) {
  return {&dot_halving_n<static_cast<int>(I) + 1>...};
}

/// The unrolled sums for 1..32 terms (buildings of up to 16 DOFs in one call).
constexpr auto kUnrolledDots = unrolled_dots(std::make_index_sequence<32>{});

/// dot_halving_n for a run-time n: the same halving, unrolled below 33 terms.
double dot_halving(const double* row, Eigen::Index stride, const double* q, int n) noexcept {
  if (n == 12) return dot_halving_n<12>(row, stride, q);  // the thesis building, inlined
  if (n <= static_cast<int>(kUnrolledDots.size())) return kUnrolledDots[static_cast<std::size_t>(n - 1)](row, stride, q);
  const int half = n / 2;
  return dot_halving(row, stride, q, half) + dot_halving(row + half * stride, stride, q + half, n - half);
}

/// Σ row[k·stride]·q[k] over k < n, k ascending (the order of Eigen's
/// fixed-size coefficient-based matrix-vector product).
double sum_in_order(const double* row, Eigen::Index stride, const double* q, int n) noexcept {
  double acc = row[0] * q[0];
  for (int k = 1; k < n; ++k) acc = row[k * stride] * q[k] + acc;
  return acc;
}

/// The one-time design of the stepping form, in matrices of `States` rows
/// and `Inputs` columns (fixed sizes for the thesis building's 12 states and
/// 2 inputs, so that its design is the arithmetic it always was; dynamic
/// otherwise).
struct Design {
  bool modal = false;
  Matrix t, t_inv, blocks, gamma_q, accel_rows;
};

/// Real modal basis of A: for each complex pair λ = σ ± iω with eigenvector
/// a ± ib, the columns a, b. Returns false when A has a real eigenvalue.
template <class StateMatrix>
bool real_modal_basis(const Matrix& a, StateMatrix& t) {
  Eigen::EigenSolver<Matrix> es(a);
  if (es.info() != Eigen::Success) return false;
  const auto values = es.eigenvalues();
  const auto vectors = es.eigenvectors();
  const Eigen::Index states = a.rows();
  Eigen::Index col = 0;
  for (Eigen::Index k = 0; k < states; ++k) {
    if (std::fabs(values(k).imag()) <= 1e-12 * std::abs(values(k))) return false;
    if (values(k).imag() < 0.0) continue;  // take one of each conjugate pair
    if (col + 2 > states) return false;
    t.col(col) = vectors.col(k).real();
    t.col(col + 1) = vectors.col(k).imag();
    col += 2;
  }
  return col == states;
}

template <int States, int Inputs>
Design design(const ContinuousModel& cm, const DiscreteModel& d) {
  using StateMatrix = Eigen::Matrix<double, States, States>;
  using InputMatrix = Eigen::Matrix<double, States, Inputs>;
  constexpr int kDofsOrDynamic = States == Eigen::Dynamic ? Eigen::Dynamic : States / 2;
  const Eigen::Index states = cm.a.rows();
  const Eigen::Index dofs = states / 2;
  const StateMatrix a = cm.a;
  const StateMatrix phi = d.phi;
  const InputMatrix gamma = d.gamma;

  Design out;
  StateMatrix t = StateMatrix::Identity(states, states);
  StateMatrix t_inv = StateMatrix::Identity(states, states);
  StateMatrix candidate(states, states);
  if (real_modal_basis(cm.a, candidate)) {
    const StateMatrix candidate_inv = candidate.inverse();
    const StateMatrix phi_q = candidate_inv * phi * candidate;
    // Accept the modal form only when everything off the 2×2 diagonal
    // blocks is rounding noise.
    double off = 0.0;
    for (Eigen::Index r = 0; r < states; ++r) {
      for (Eigen::Index c = 0; c < states; ++c) {
        if (r / 2 != c / 2) off = std::max(off, std::fabs(phi_q(r, c)));
      }
    }
    if (off <= 1e-12 && std::isfinite(phi_q.sum())) {
      out.modal = true;
      t = candidate;
      t_inv = candidate_inv;
      out.blocks = Matrix(states, 2);
      for (Eigen::Index r = 0; r < states; ++r) {
        const Eigen::Index c0 = (r / 2) * 2;
        out.blocks(r, 0) = phi_q(r, c0);
        out.blocks(r, 1) = phi_q(r, c0 + 1);
      }
    }
  }
  const InputMatrix gamma_q = t_inv * gamma;
  const Eigen::Matrix<double, kDofsOrDynamic, States> accel_rows =
      a.template block<kDofsOrDynamic, States>(dofs, 0, dofs, states) * t;
  out.t = t;
  out.t_inv = t_inv;
  out.gamma_q = gamma_q;
  out.accel_rows = accel_rows;
  return out;
}

}  // namespace

void DiscreteBuilding::init(const BuildingParams& params, double dt_s) {
  const ContinuousModel cm = continuous_model(params);
  const DiscreteModel d = discretize_zoh(cm, dt_s);
  dofs_ = params.dofs();
  elements_ = structure::force_elements(params);
  phi_ = d.phi;
  gamma_ = d.gamma;
  inv_mass_ = Vector(dofs_);
  for (int i = 0; i < dofs_; ++i) inv_mass_(i) = 1.0 / params.mass_kg[i];
  dt_s_ = dt_s;

  const Design s = dofs_ == 6 && gamma_.cols() == 2 ? design<12, 2>(cm, d)
                                                     : design<Eigen::Dynamic, Eigen::Dynamic>(cm, d);
  modal_ = s.modal;
  t_ = s.t;
  t_inv_ = s.t_inv;
  blocks_ = modal_ ? s.blocks : Matrix::Zero(2 * dofs_, 2);
  gamma_q_ = s.gamma_q;
  accel_rows_ = s.accel_rows;
  q_ = Vector::Zero(2 * dofs_);
  next_ = Vector::Zero(2 * dofs_);
  held_.assign(elements_.size(), 0.0);
  reset();
}

void DiscreteBuilding::reset() noexcept {
  q_.setZero();
  std::fill(held_.begin(), held_.end(), 0.0);
  steps_ = 0;
}

void DiscreteBuilding::set_state(const Vector& z) noexcept {
  const int n = 2 * dofs_;
  for (int r = 0; r < n; ++r) q_(r) = sum_in_order(t_inv_.data() + r, t_inv_.outerStride(), z.data(), n);
  std::fill(held_.begin(), held_.end(), 0.0);
}

Vector DiscreteBuilding::state() const {
  const int n = 2 * dofs_;
  Vector z(n);
  for (int r = 0; r < n; ++r) z(r) = sum_in_order(t_.data() + r, t_.outerStride(), q_.data(), n);
  return z;
}

double DiscreteBuilding::disp_m(int i) const noexcept {
  return dot_halving(t_.data() + i, t_.outerStride(), q_.data(), 2 * dofs_);
}

double DiscreteBuilding::vel_m_s(int i) const noexcept {
  return dot_halving(t_.data() + dofs_ + i, t_.outerStride(), q_.data(), 2 * dofs_);
}

void DiscreteBuilding::step(double ground_accel_m_s2, const double* element_forces_n) noexcept {
  const int n = 2 * dofs_;
  if (modal_) {
    for (int j = 0; j < n; j += 2) {
      const double q0 = q_(j);
      const double q1 = q_(j + 1);
      next_(j) = blocks_(j, 0) * q0 + blocks_(j, 1) * q1;
      next_(j + 1) = blocks_(j + 1, 0) * q0 + blocks_(j + 1, 1) * q1;
    }
  } else {
    for (int r = 0; r < n; ++r) next_(r) = sum_in_order(phi_.data() + r, phi_.outerStride(), q_.data(), n);
  }
  for (int j = 0; j < n; ++j) next_(j) = next_(j) + gamma_q_(j, 0) * ground_accel_m_s2;
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const double f = element_forces_n[k];
    const Eigen::Index col = 1 + static_cast<Eigen::Index>(k);
    for (int j = 0; j < n; ++j) next_(j) = next_(j) + gamma_q_(j, col) * f;
    held_[k] = f;
  }
  q_.swap(next_);
  ++steps_;
}

double DiscreteBuilding::abs_accel_m_s2(int i) const noexcept {
  double a = dot_halving(accel_rows_.data() + i, accel_rows_.outerStride(), q_.data(), 2 * dofs_);
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const int e = elements_[k];
    if (i == e) a -= inv_mass_(e) * held_[k];
    if (i == e - 1) a += inv_mass_(i) * held_[k];
  }
  return a;
}

void DiscreteBuilding::abs_accel_m_s2(double* out) const noexcept {
  for (int i = 0; i < dofs_; ++i) {
    out[i] = sum_in_order(accel_rows_.data() + i, accel_rows_.outerStride(), q_.data(), 2 * dofs_);
  }
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const int e = elements_[k];
    out[e] -= inv_mass_(e) * held_[k];
    if (e > 0) out[e - 1] += inv_mass_(e - 1) * held_[k];
  }
}

}  // namespace mrd::structure
