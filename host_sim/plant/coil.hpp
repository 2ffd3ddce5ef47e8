#pragma once
/// The damper's coil as a resistance in series with a current-dependent
/// inductance (§3.2, Table 3.1: 4.8 Ω; 5.0 H at 1 A, 3.0 H at 2 A):
///
/// <pre>
///   v = R i + L(i) di/dt,   L(i) = dλ/di = max(L_0 exp(−|i| / I_s), L_min)
/// </pre>
///
/// L(i) is the differential inductance (the one the drive's voltage works
/// against), read through the two thesis points: L_0 = 5.0 H · (5/3) =
/// 8.33 H and I_s = 1 A / ln(5/3) = 1.958 A. It stays positive at any current
/// and falls as the steel saturates: 8.33 H at 0 A, 2.32 H at 2.5 A. The
/// flux linkage is λ(i) = L_0 I_s (1 − exp(−|i|/I_s)) sgn i below the floor.
/// The thesis says nothing of the saturated coil: L_min = 0.5 H (an
/// assumption) holds the inductance from 5.5 A up, so that the exponential
/// does not fall to nothing at the drive's 10–30 A (it would give 0.05 H at
/// 10 A) and the drive's fixed-gain loop stays well damped.
///
/// step() integrates the ODE over one interval with the voltage held, by the
/// midpoint rule (second order; at the drive's 0.1 ms substep the error is
/// far below a microampere, since L/R ≥ 0.1 s).

#include <algorithm>
#include <cmath>

#include "mrd/physics/coil_heat.hpp"

namespace mrd::plant {

struct CoilParams {
  double resistance_ohm = 4.8;         ///< Table 3.1
  double inductance_1a_h = 5.0;        ///< L at 1 A, H (Table 3.1)
  double inductance_2a_h = 3.0;        ///< L at 2 A, H (Table 3.1)
  double min_inductance_h = 0.5;       ///< saturated coil, H (assumption)
};

/// The circuit of a coil of `resistance_ohm` with inductance `l` (the
/// damper's: physics::MrDamperParams::coil_heat and ::coil_inductance).
inline CoilParams coil_params(double resistance_ohm, const physics::CoilInductance& l) noexcept {
  return {resistance_ohm, l.inductance_1a_h, l.inductance_2a_h, l.min_inductance_h};
}

class Coil {
 public:
  Coil() = default;
  explicit Coil(const CoilParams& p) noexcept { init(p); }

  void init(const CoilParams& p) noexcept {
    p_ = p;
    saturation_a_ = 1.0 / std::log(p.inductance_1a_h / p.inductance_2a_h);
    l0_h_ = p.inductance_1a_h * std::exp(1.0 / saturation_a_);
    current_a_ = 0.0;
  }

  /// Differential inductance dλ/di at `current_a`, H.
  double inductance_h(double current_a) const noexcept {
    return std::max(l0_h_ * std::exp(-std::fabs(current_a) / saturation_a_), p_.min_inductance_h);
  }

  /// Advances the current over `dt_s` with `voltage_v` across the coil.
  void step(double voltage_v, double dt_s) noexcept {
    const double i_mid = current_a_ + 0.5 * dt_s * slope(voltage_v, current_a_);
    current_a_ += dt_s * slope(voltage_v, i_mid);
  }

  void set_current_a(double current_a) noexcept { current_a_ = current_a; }
  double current_a() const noexcept { return current_a_; }
  double l0_h() const noexcept { return l0_h_; }
  double saturation_a() const noexcept { return saturation_a_; }
  const CoilParams& params() const noexcept { return p_; }

 private:
  CoilParams p_{};
  double l0_h_ = 0.0;
  double saturation_a_ = 1.0;
  double current_a_ = 0.0;

  double slope(double voltage_v, double current_a) const noexcept {
    return (voltage_v - p_.resistance_ohm * current_a) / inductance_h(current_a);
  }
};

}  // namespace mrd::plant
