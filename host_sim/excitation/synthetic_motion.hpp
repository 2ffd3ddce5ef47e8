#pragma once
/// Synthetic ground motion for runs without a recorded earthquake.
///
/// Model: filtered Gaussian white noise times a deterministic envelope,
///
///   a(t) = s · e(t) · y(t),
///
/// * y(t), stationary: white noise w(t) through the Kanai–Tajimi soil filter
///   (ω_g, ζ_g), then, by default, the Clough–Penzien high-pass (ω_f, ζ_f):
///
///     ẍ_g + 2ζ_g ω_g ẋ_g + ω_g² x_g = −w,        a_KT = −(ω_g² x_g + 2ζ_g ω_g ẋ_g)
///     ẍ_f + 2ζ_f ω_f ẋ_f + ω_f² x_f = −a_KT,     y = −ẍ_f
///
///   so that the one-sided power spectrum of y is S_w · |H(ω)|² with
///
///     |H_KT(ω)|² = (ω_g⁴ + 4ζ_g²ω_g²ω²) / ((ω_g² − ω²)² + 4ζ_g²ω_g²ω²)
///     |H_CP(ω)|² = ω⁴ / ((ω_f² − ω²)² + 4ζ_f²ω_f²ω²)
///
///   Kanai–Tajimi alone has a non-zero spectrum at ω = 0, which gives the
///   ground unbounded velocity and displacement variance; the Clough–Penzien
///   stage removes that, which matters for a long-period base-isolated building.
///   Without it, y = a_KT.
/// * e(t), a Jennings-type envelope: (t/t₁)² for t < t₁, 1 up to t₂, then
///   exp(−c·(t − t₂)).
/// * s, chosen so that max |a| equals the target PGA (scaled_to_pga).
///
/// Discretization: the filters are advanced exactly over each step of dt_s
/// (matrix exponential of the 4-state system) with the noise held constant
/// during the step; the noise is a sequence of independent standard normal
/// deviates. The filter is first run from rest for a warm-up of ten of its
/// slowest time constants (capped at 200 s and 1e7 steps) so that y is stationary at t = 0.
///
/// Determinism: normal deviates come from std::mt19937_64 through a
/// Box–Muller transform implemented here (StandardNormal), not from
/// std::normal_distribution, whose output differs between standard
/// libraries. The same parameters and seed give the same record on every
/// platform with an IEEE-754 libm (up to last-bit differences in log/sin/cos).
/// A different dt_s gives a different realization.

#include <cstdint>
#include <random>
#include <string>

#include "host_sim/excitation/ground_motion.hpp"
#include "mrd/units.hpp"

namespace mrd::excitation {

/// Parameters of the synthetic motion. Defaults: firm soil and a moderate
/// 30-s event scaled to the thesis's common PGA (Table 6.3, 0.1127 g).
struct SyntheticMotionParams {
  std::uint64_t seed = 1;   ///< RNG seed; part of the record's name
  double dt_s = 0.01;       ///< sample step, s (the records' step)
  double duration_s = 30.0; ///< last sample at floor(duration/dt)·dt, s
  double target_pga_m_s2 = 0.1127 * units::kStandardGravity_m_s2;  ///< Table 6.3 scaled PGA, 1.1052 m/s²

  /// Kanai–Tajimi ω_g, rad/s, and ζ_g: the firm-soil values widely used in
  /// the structural-control literature. |H_KT|² then peaks at
  /// ω = ω_g·√((√(1 + 8ζ_g²) − 1)/(4ζ_g²)) = 0.821·ω_g = 12.8 rad/s (2.04 Hz).
  double ground_frequency_rad_s = 15.6;
  double ground_damping_ratio = 0.6;

  /// Clough–Penzien high-pass ω_f, rad/s, and ζ_f (ω_f about 0.1 ω_g).
  bool high_pass = true;
  double high_pass_frequency_rad_s = 1.5;
  double high_pass_damping_ratio = 0.6;

  /// Envelope: rise to t₁, plateau to t₂, then decay with rate c. With the
  /// defaults e(30 s) = exp(−0.3·18) = 0.0045.
  double rise_time_s = 2.0;      ///< t₁, s
  double plateau_end_s = 12.0;   ///< t₂, s
  double decay_rate_1_s = 0.3;   ///< c, 1/s
};

/// Standard normal deviates from std::mt19937_64 by the Box–Muller
/// transform: u₁ ∈ (0, 1], u₂ ∈ [0, 1) from the top 53 bits of one draw
/// each, z₁ = √(−2 ln u₁) cos 2πu₂, z₂ = √(−2 ln u₁) sin 2πu₂ (z₂ is kept
/// for the next call).
class StandardNormal {
 public:
  explicit StandardNormal(std::uint64_t seed) : engine_(seed) {}
  double next();

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

/// e(t) of the model, dimensionless, for t in s (0 for t < 0).
double jennings_envelope(double t_s, const SyntheticMotionParams& params) noexcept;

/// |H(ω)|² of the model's filter (Kanai–Tajimi, times Clough–Penzien when
/// high_pass), dimensionless; ω in rad/s. The power spectrum of y is this
/// times the white-noise level.
double filter_power_gain(double omega_rad_s, const SyntheticMotionParams& params) noexcept;

/// One realization of the model, named `synthetic-kanai-tajimi(seed=N)`,
/// with the parameters written in `source`. Throws io::UsageError for
/// non-positive or non-finite steps, durations, frequencies, damping ratios
/// or target PGA, for ω_g at or above the Nyquist frequency π/dt, for
/// t₂ < t₁, for a negative decay rate, or for fewer than 2 or more than 1e9
/// samples.
GroundMotion synthetic_motion(const SyntheticMotionParams& params);

}  // namespace mrd::excitation
