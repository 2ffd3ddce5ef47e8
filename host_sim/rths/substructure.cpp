#include "host_sim/rths/substructure.hpp"

#include <Eigen/LU>
#include <stdexcept>

namespace mrd::rths {

StructureMatrices without_specimen(const StructureMatrices& whole, const Specimen& s, int dof) {
  if (dof < 0 || dof >= whole.m.rows()) throw std::invalid_argument("without_specimen: DOF out of range");
  StructureMatrices n = whole;
  n.m(dof, dof) -= s.mass_kg;
  n.c(dof, dof) -= s.damping_n_s_m();
  n.k(dof, dof) -= s.stiffness_n_m;
  if (!(n.m(dof, dof) > 0.0))
    throw std::invalid_argument("without_specimen: the specimen's mass is not less than its DOF's mass");
  return n;
}

ChenRiclesIntegrator::ChenRiclesIntegrator(const StructureMatrices& whole, const StructureMatrices& numerical,
                                           int specimen_dof, double dt_s)
    : dof_(specimen_dof), dt_s_(dt_s), k_(numerical.k), c_(numerical.c) {
  const Eigen::Index n = numerical.m.rows();
  m_inv_ = numerical.m.inverse();
  alpha_ = (numerical.m + 0.5 * dt_s * numerical.c + 0.25 * dt_s * dt_s * numerical.k).partialPivLu().solve(numerical.m);
  ground_ = -(whole.m * Vector::Ones(n));
  x_ = Vector::Zero(n);
  v_ = Vector::Zero(n);
  p_ = Vector::Zero(n);
  a_ = Vector::Zero(n);
  alpha_a_ = Vector::Zero(n);
}

double ChenRiclesIntegrator::step(double ground_accel_m_s2, double measured_force_n) {
  p_ = ground_ * ground_accel_m_s2;
  p_.noalias() -= c_ * v_;
  p_.noalias() -= k_ * x_;
  p_(dof_) -= measured_force_n;
  a_.noalias() = m_inv_ * p_;
  alpha_a_.noalias() = alpha_ * a_;
  x_ += dt_s_ * v_ + dt_s_ * dt_s_ * alpha_a_;
  v_ += dt_s_ * alpha_a_;
  return x_(dof_);
}

}  // namespace mrd::rths
