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
/// The thesis gives the coil resistance (4.8 Ω, §3.2, Table 3.1) but no
/// thermal data. R_th and τ are assumptions: R_th is sized so that the rated
/// current of 2.5 A held continuously (30 W) settles 60 K above ambient, and
/// τ = 20 min is the order of a coil of a few kilograms of copper inside the
/// damper's steel housing. The resistance is taken as constant (no copper
/// temperature coefficient).

#include <cmath>

namespace mrd::plant {

struct CoilThermalParams {
  double resistance_ohm = 4.8;           ///< coil resistance, Ω (Table 3.1)
  double thermal_resistance_k_w = 2.0;   ///< coil to ambient, K/W (assumption: 2.5 A → 60 K)
  double time_constant_s = 1200.0;       ///< R_th C, s (assumption)
};

class CoilThermal {
 public:
  CoilThermal() = default;
  CoilThermal(const CoilThermalParams& p, double step_s) noexcept { init(p, step_s); }

  void init(const CoilThermalParams& p, double step_s) noexcept {
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
  const CoilThermalParams& params() const noexcept { return p_; }

 private:
  CoilThermalParams p_{};
  double a_ = 1.0;
  double rise_k_ = 0.0;
};

}  // namespace mrd::plant
