#pragma once
/// Coil heating: the Joule power i²R into a first-order thermal model of the
/// coil against its surroundings,
///
/// <pre>
///   C dΔT/dt = P − ΔT / R_th,   τ = R_th C,   P = i² R
/// </pre>
///
/// discretized exactly for P held over each step: ΔT[n+1] = a ΔT[n] + (1 − a) R_th P[n],
/// a = exp(−T/τ). The steady rise for a constant power is P·R_th.
///
/// The constants are the damper's (physics::MrDamperParams::coil_heat,
/// mrd/physics/coil_heat.hpp): the thesis coil's 4.8 Ω with its assumed
/// 2 K/W and 20 min, or a damper file's coil.

#include <cmath>

#include "mrd/physics/coil_heat.hpp"

namespace mrd::plant {

class CoilThermal {
 public:
  CoilThermal() = default;
  CoilThermal(const physics::CoilHeatParams& p, double step_s) noexcept { init(p, step_s); }

  void init(const physics::CoilHeatParams& p, double step_s) noexcept {
    p_ = p;
    a_ = std::exp(-step_s / p.time_constant_s);
    rise_k_ = 0.0;
  }

  /// Advances one step with the mean of i² over the step, A².
  void step(double mean_current_sq_a2) noexcept {
    const double power_w = mean_current_sq_a2 * p_.resistance_ohm;
    rise_k_ = a_ * rise_k_ + (1.0 - a_) * p_.thermal_resistance_k_w * power_w;
  }

  /// Coil temperature above ambient, K.
  double rise_k() const noexcept { return rise_k_; }
  const physics::CoilHeatParams& params() const noexcept { return p_; }

 private:
  physics::CoilHeatParams p_{};
  double a_ = 1.0;
  double rise_k_ = 0.0;
};

}  // namespace mrd::plant
