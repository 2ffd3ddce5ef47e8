#pragma once
/// The hysteretic part of the isolation bearings (building_params.hpp): the
/// Bouc–Wen variable z of each bearing group and the force Q·z (lead-rubber)
/// or μ(u̇)·W·z (friction pendulum) it gives. Their linear parts (k_p, W/R)
/// are in the building's K (building.hpp).
///
/// z is advanced in the displacement domain: over an increment Δu of the
/// isolation layer's deformation,
/// <pre>
///   dz/du = (1 − |z|ⁿ·(γ·sgn(Δu·z) + β)) / D_y
/// </pre>
/// by classical Runge–Kutta in sub-increments of at most D_y/8, so a step
/// that crosses the yield displacement several times is still resolved
/// (z's rate form ż = u̇·dz/du is the equation). The force is taken
/// with z at the start of a structural sub-step and held over it (see
/// plant.hpp for the sub-step).

#include <vector>

#include "host_sim/structure/building_params.hpp"

namespace mrd::structure {

class IsolatorBank {
 public:
  /// The building's bearings, z = 0 (the bearings centred, no history).
  void init(const BuildingParams& p);
  /// z back to 0.
  void reset() noexcept;
  bool empty() const noexcept { return groups_.empty(); }

  /// Σ over the groups of the hysteretic force at element 0, N: count·Q·z and
  /// count·μ(v)·W·z, positive resisting a positive deformation;
  /// `rate_m_s` is the isolation layer's deformation rate u̇_0.
  double hysteretic_force_n(double rate_m_s) const noexcept;

  /// The isolators' whole force (linear and hysteretic parts) at the
  /// deformation `u_m` and rate `rate_m_s`, N.
  double total_force_n(double u_m, double rate_m_s) const noexcept;

  /// Advances every z over the deformation increment `du_m`.
  void advance(double du_m) noexcept;

  /// The Bouc–Wen variable of group `g`.
  double z(std::size_t g) const noexcept { return groups_[g].z; }

  /// Smallest displacement capacity of the groups that state one, m (0: none).
  double displacement_capacity_m() const noexcept { return capacity_m_; }

  /// Largest tangent stiffness the hysteretic parts reach (at z = 0), N/m:
  /// Σ count·Q/D_y and count·μ_fast·W/D_y. Sets the structural sub-step.
  double initial_stiffness_n_m() const noexcept { return initial_stiffness_n_m_; }

  /// Smallest yield displacement of the groups, m (0 when empty).
  double smallest_yield_displacement_m() const noexcept { return smallest_dy_m_; }

 private:
  struct Group {
    bool pendulum = false;
    double count = 1.0;
    double strength_n = 0.0;       ///< Q (lead-rubber) or W (pendulum, load per bearing)
    double linear_n_m = 0.0;       ///< k_p or W/R per bearing
    double mu_slow = 0.0, mu_fast = 0.0, rate_s_per_m = 0.0;
    double dy_m = 1.0;
    double exponent = 2.0;
    double z = 0.0;
  };
  std::vector<Group> groups_;
  double capacity_m_ = 0.0;
  double initial_stiffness_n_m_ = 0.0;
  double smallest_dy_m_ = 0.0;
};

}  // namespace mrd::structure
