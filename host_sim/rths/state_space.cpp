#include "host_sim/rths/state_space.hpp"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <unsupported/Eigen/MatrixFunctions>

namespace mrd::rths {

DiscreteSystem zero_order_hold(const ContinuousSystem& sys, double dt_s) {
  if (!(std::isfinite(dt_s) && dt_s > 0.0)) throw std::invalid_argument("zero_order_hold: step must be > 0");
  const Eigen::Index n = sys.a.rows();
  const Eigen::Index m = sys.b.cols();
  if (sys.a.cols() != n || sys.b.rows() != n || sys.c.cols() != n || sys.d.rows() != sys.c.rows() ||
      sys.d.cols() != m)
    throw std::invalid_argument("zero_order_hold: inconsistent A, B, C, D sizes");
  Matrix aug = Matrix::Zero(n + m, n + m);
  aug.topLeftCorner(n, n) = sys.a * dt_s;
  aug.topRightCorner(n, m) = sys.b * dt_s;
  const Matrix e = aug.exp();
  DiscreteSystem out;
  out.phi = e.topLeftCorner(n, n);
  out.gamma = e.topRightCorner(n, m);
  out.c = sys.c;
  out.d = sys.d;
  out.dt_s = dt_s;
  return out;
}

Matrix dc_gain(const ContinuousSystem& sys) { return sys.c * (-sys.a).partialPivLu().solve(sys.b) + sys.d; }

std::complex<double> frequency_response(const ContinuousSystem& sys, double omega_rad_s, int out, int in) {
  using C = Eigen::MatrixXcd;
  const Eigen::Index n = sys.a.rows();
  C jw = C::Identity(n, n) * std::complex<double>(0.0, omega_rad_s) - sys.a.cast<std::complex<double>>();
  const C x = jw.partialPivLu().solve(sys.b.cast<std::complex<double>>());
  const C y = sys.c.cast<std::complex<double>>() * x + sys.d.cast<std::complex<double>>();
  return y(out, in);
}

DiscreteBlock::DiscreteBlock(DiscreteSystem sys) : sys_(std::move(sys)), x_(Vector::Zero(sys_.phi.rows())) {}

Vector DiscreteBlock::step(const Vector& u) {
  const Vector y = sys_.c * x_ + sys_.d * u;
  x_ = sys_.phi * x_ + sys_.gamma * u;
  return y;
}

double DiscreteBlock::step(double u) {
  const double y = sys_.c.row(0).dot(x_) + sys_.d(0, 0) * u;
  x_ = sys_.phi * x_ + sys_.gamma.col(0) * u;
  return y;
}

}  // namespace mrd::rths
