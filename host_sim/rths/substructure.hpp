#pragma once
/// The numerical substructure of an RTHS: the building with the physical
/// specimen's mass, damping and stiffness removed at one DOF, integrated in
/// real time by the explicit Chen–Ricles (CR) algorithm (Chen, Ricles, Marullo
/// and Mercan 2009), the measured force as the input:
///
/// <pre>
///   M_n ẍ + C_n ẋ + K_n x = −M·1·a_g − e_d·f_m
///   α = (M_n + Δt/2·C_n + Δt²/4·K_n)⁻¹·M_n          (α1 = α2)
///   ẋ[k+1] = ẋ[k] + Δt·α·ẍ[k]
///   x[k+1] = x[k] + Δt·ẋ[k] + Δt²·α·ẍ[k]
///   ẍ[k]   = M_n⁻¹·(−M·1·a_g[k] − e_d·f_m[k] − C_n ẋ[k] − K_n x[k])
/// </pre>
///
/// M, C, K are the whole building's (the all-numerical reference); M_n, C_n,
/// K_n have m_e, c_e, k_e taken off at DOF d. The ground term keeps the whole
/// mass (the specimen's share of −m·a_g is not in the measured force, which
/// the laboratory's fixed floor produces from relative motion only). The
/// displacement x[k+1] is explicit in step k's state, so it is the target
/// that the actuator must reach one step later. CR is unconditionally stable
/// for a linear building and, for a linear specimen, second-order accurate
/// with the period error of the constant-average-acceleration rule.

#include "host_sim/rths/lab_plant.hpp"
#include "host_sim/rths/state_space.hpp"

namespace mrd::rths {

struct StructureMatrices {
  Matrix m, c, k;
};

/// The building without the specimen at DOF `dof`.
StructureMatrices without_specimen(const StructureMatrices& whole, const Specimen& s, int dof);

class ChenRiclesIntegrator {
 public:
  /// `whole` supplies the ground term's mass; `numerical` is integrated.
  ChenRiclesIntegrator(const StructureMatrices& whole, const StructureMatrices& numerical, int specimen_dof,
                       double dt_s);

  /// Step k: with the ground acceleration a_g[k] and the force measured at
  /// DOF d (N, the specimen resisting a positive displacement), forms ẍ[k]
  /// and advances to x[k+1], ẋ[k+1]. Returns x[k+1] at the specimen's DOF.
  double step(double ground_accel_m_s2, double measured_force_n);

  const Vector& displacement_m() const noexcept { return x_; }
  const Vector& velocity_m_s() const noexcept { return v_; }

 private:
  int dof_;
  double dt_s_;
  Matrix k_, c_, m_inv_, alpha_;
  Vector ground_;  ///< −M·1
  Vector x_, v_;
  Vector p_, a_, alpha_a_;  ///< work vectors (no allocation per step)
};

}  // namespace mrd::rths
