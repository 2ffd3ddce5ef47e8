#pragma once
/// The 200 kN MR damper of the thesis written from its equations alone, for
/// the independent record generator: Bingham plastic force with exponential
/// current laws (Eq. 4.1–4.4, Table 4.1), the participant ratio of chapter 5
/// (Eq. 5.6–5.12, Table 5.6) and the coil dynamics of Eq. 4.5 as a
/// continuous-time system. Standard library only.

namespace indep {

/// Table 4.1, converted to SI (kN → N, kN·s/mm → N·s/m).
inline constexpr double kFcA_n = 4.1e3;          ///< f_c,a: yield force at 0 A
inline constexpr double kFcB_n = 170.0e3;        ///< f_c,b: yield force at 2.5 A
inline constexpr double kFcC_per_a = 0.7;        ///< f_c,c
inline constexpr double kC0A_n_s_m = 0.0825e6;   ///< c_0,a: 0.0825 kN·s/mm
inline constexpr double kC0B_n_s_m = 0.365e6;    ///< c_0,b: 0.365 kN·s/mm
inline constexpr double kC0C_per_a = 1.15;       ///< c_0,c
/// Eq. 4.4: the transition velocity, 10 mm/s.
inline constexpr double kTransitionVelocity_m_s = 0.010;

/// Eq. 4.5 with unity DC gain: two first-order lags weighted ½ and ½.
inline constexpr double kCoilTauSlow_s = 0.7;
inline constexpr double kCoilTauFast_s = 0.03;
inline constexpr double kCoilWeightSlow = 0.5;
inline constexpr double kCoilWeightFast = 0.5;
/// Eq. 4.5's mean delay (the first moment of its impulse response), s: ½·0.7 + ½·0.03.
inline constexpr double kCoilMeanTau_s = kCoilWeightSlow * kCoilTauSlow_s + kCoilWeightFast * kCoilTauFast_s;

/// Effective flow area that turns |v| into the flow rate Q of Eq. 5.9, m²;
/// ∫Q dt is counted in litres.
inline constexpr double kFlowArea_m2 = 0.01062;

/// Table 3.1: the damper's largest velocity, m/s.
inline constexpr double kMaxVelocity_m_s = 0.2491;

/// Eq. 5.6–5.8 with Table 5.6: the participant-ratio law for a settling quotient.
struct PrLaw {
  double a_pr;       ///< PR before any mixing (Eq. 5.6)
  double b_pr;       ///< PR after long mixing (Eq. 5.7)
  double c_pr_per_l; ///< rate per litre of displaced volume (Eq. 5.8)
};

/// PR law for settling quotient `sq` (a fraction, 0 = fully mixed).
[[nodiscard]] PrLaw pr_law(double sq);

/// Eq. 5.9: PR after `volume_l` litres of displaced fluid.
[[nodiscard]] double participant_ratio(const PrLaw& law, double volume_l);

/// Eq. 5.10: yield force at coil current `current_a` and participant ratio `pr`, N.
[[nodiscard]] double yield_force_n(double current_a, double pr);
/// Eq. 5.11: viscous coefficient, N·s/m.
[[nodiscard]] double viscous_coeff_n_s_m(double current_a, double pr);

/// Eq. 4.4: the transition function.
[[nodiscard]] double transition_factor(double vel_m_s);

}  // namespace indep
