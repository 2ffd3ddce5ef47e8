#pragma once
/// The damper coil's heating constants: its resistance and a first-order
/// thermal model against its surroundings (host_sim/plant/coil_thermal.hpp
/// steps it; the firmware's I²t derating, firmware/core/coil_i2t.hpp, uses
/// the same time constant):
///
/// <pre>
///   C dΔT/dt = i² R − ΔT / R_th,   τ = R_th C,   steady rise i² R R_th
/// </pre>
///
/// The thesis gives the coil's resistance (4.8 Ω, §3.2, Table 3.1) but no
/// thermal data. Its R_th and τ are assumptions: R_th is sized so that the
/// rated current held continuously settles kRatedCoilRise_k above ambient
/// (2.5 A · 2.5 A · 4.8 Ω = 30 W → 60 K: 2 K/W), and τ = 20 min is the order
/// of a coil of a few kilograms of copper inside the damper's steel housing.
/// A user's coil without thermal data takes the same assumption at its own
/// rating (rated_rise_thermal_resistance_k_w): its rise is then 60 K·(i/I_r)²
/// in the steady state whatever its resistance. The resistance is constant
/// (no copper temperature coefficient).

namespace mrd::physics {

/// Steady rise above ambient of a coil carrying its rated current
/// continuously, where no thermal data say otherwise, K (the assumption the
/// thesis coil's R_th stands for).
inline constexpr double kRatedCoilRise_k = 60.0;

struct CoilHeatParams {
  double resistance_ohm = 4.8;          ///< R: the coil's resistance, Ω (Table 3.1)
  double thermal_resistance_k_w = 2.0;  ///< R_th: coil to ambient, K/W (assumption: 2.5 A → 60 K)
  double time_constant_s = 1200.0;      ///< τ = R_th C, s (assumption: 20 min)

  friend bool operator==(const CoilHeatParams&, const CoilHeatParams&) = default;
};

/// The coil's differential inductance L(i) through two points, as the
/// hardware plant's R–L(i) coil reads it (host_sim/plant/coil.hpp: L_0
/// exp(−|i|/I_s) through L(1 A) and L(2 A), held at a saturated floor):
/// Table 3.1's 5.0 H at 1 A and 3.0 H at 2 A for the thesis coil. The floor
/// is an assumption (the thesis says nothing of the saturated coil): 0.5 H,
/// or the coil's own L(2 A) where that is lower (coil_inductance()).
struct CoilInductance {
  double inductance_1a_h = 5.0;   ///< L at 1 A, H (Table 3.1)
  double inductance_2a_h = 3.0;   ///< L at 2 A, H (Table 3.1)
  double min_inductance_h = 0.5;  ///< saturated coil, H (assumption)

  friend bool operator==(const CoilInductance&, const CoilInductance&) = default;
};

/// The saturated floor of a coil whose own L(2 A) is not known to be above it, H.
inline constexpr double kSaturatedCoilInductance_h = 0.5;

/// A coil of L(1 A) = `inductance_1a_h` and L(2 A) = `inductance_2a_h` (at
/// most L(1 A): the iron saturates), its floor the smaller of 0.5 H and its
/// own L(2 A).
[[nodiscard]] constexpr CoilInductance coil_inductance(double inductance_1a_h, double inductance_2a_h) noexcept {
  return {inductance_1a_h, inductance_2a_h,
          inductance_2a_h < kSaturatedCoilInductance_h ? inductance_2a_h : kSaturatedCoilInductance_h};
}

/// R_th that makes `rated_current_a` held continuously in a coil of
/// `resistance_ohm` settle kRatedCoilRise_k above ambient:
/// 60 K / (I_r² R), K/W. The thesis coil: 60 / (2.5² · 4.8) = 2 K/W
/// (6.25 · 4.8 rounds to 30 exactly in binary64, so the quotient is 2.0).
[[nodiscard]] constexpr double rated_rise_thermal_resistance_k_w(double rated_current_a,
                                                                 double resistance_ohm) noexcept {
  return kRatedCoilRise_k / (rated_current_a * rated_current_a * resistance_ohm);
}

}  // namespace mrd::physics
