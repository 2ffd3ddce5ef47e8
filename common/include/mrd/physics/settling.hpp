#pragma once
/// Particle settling during idle time (thesis §5.1.1 and §5.3):
/// Stokes velocity (Eq. 5.1), hindered velocity (Eq. 5.2), settled-layer
/// height from the cylindrical-segment volume (Eq. 5.3, Tables 5.4–5.5),
/// maximum settling time (Eq. 5.4) and settling quotient SQ (Eq. 5.5).
/// Idle times are in seconds.

namespace mrd::physics {

/// Table 5.3 (MR fluid, MRX-140ND-like) and Table 3.1 / 5.4 (damper geometry).
struct SettlingParams {
  double gravity_m_s2 = 9.81;            ///< g_c in Eq. 5.1 (the thesis's value)
  double particle_diameter_m = 5.0e-6;   ///< d_p, Table 5.3: 5 µm
  double solid_density_kg_m3 = 7870.0;   ///< ρ_s, Table 5.3
  double liquid_density_kg_m3 = 820.0;   ///< ρ_l, Table 5.3
  double viscosity_pa_s = 2.0;           ///< η, Table 5.3 (apparent plastic viscosity)
  double solid_fraction = 0.40;          ///< χ, Table 5.3: 40 %
  double hindered_exponent = 4.65;       ///< n in Eq. 5.2 for Re_p < 0.3
  double inner_diameter_m = 0.2032;      ///< Table 3.1
  double shaft_radius_m = 0.04;          ///< Table 3.1
  /// Length of the settling cylinder in Eq. 5.3. Table 5.5 is reproduced with
  /// the 0.5842 m total stroke (Table 3.1); see docs in settling.cpp.
  double fluid_length_m = 0.5842;
  double fluid_volume_m3 = 0.01660;      ///< Table 5.4 (a), method 1, rounded
  /// A measured maximum settling time, s, that replaces Eq. 5.4 when > 0
  /// (a fluid file's max_settling_time_s); 0: Eq. 5.4 from the values above.
  double measured_max_settling_time_s = 0.0;
};

/// Stokes settling velocity, Eq. 5.1, m/s.
double stokes_velocity_m_s(const SettlingParams& p) noexcept;

/// Hindered settling velocity V_ts = V_t (1 − χ)^n, Eq. 5.2, m/s.
double hindered_velocity_m_s(const SettlingParams& p) noexcept;

/// Cross-section area of a horizontal cylinder of radius r filled to height h
/// from its bottom: the bracket of Eq. 5.3, m². Clamped to [0, π r²].
double circular_segment_area_m2(double radius_m, double height_m) noexcept;

/// Volume of solids below height h with the shaft (coaxial, radius r_s)
/// removed: L·[A_seg(R, h) − A_seg(r_s, h − (R − r_s))], m³ (Eq. 5.3).
double settled_volume_m3(const SettlingParams& p, double height_m) noexcept;

/// Height of the fully settled particle layer: solves settled_volume_m3(h) =
/// χ·V_fluid by bisection (Table 5.5: 0.0831 m). m.
double settled_layer_height_m(const SettlingParams& p) noexcept;

/// Maximum settling time, Eq. 5.4: (ID − h_max)/V_ts, s.
/// (or the measured one when the parameters hold one).
double max_settling_time_s(const SettlingParams& p) noexcept;

/// Settling quotient SQ as a fraction, Eq. 5.5, saturating at 1 (a fluid
/// cannot be more than fully settled). Negative idle time is treated as 0.
double settling_quotient(double idle_time_s, double max_settling_time_s) noexcept;

/// Settling quotient after `idle_time_s` seconds idle: Eq. 5.5 with the
/// maximum settling time of Eq. 5.4 for `p`. 0 for no idle time, 0.5 at half
/// the maximum settling time, 1 at and past it.
double settling_quotient_after_idle(double idle_time_s, const SettlingParams& p) noexcept;

}  // namespace mrd::physics
