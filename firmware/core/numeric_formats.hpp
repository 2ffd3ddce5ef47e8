#pragma once
/// The number formats of the control core, per numeric policy, and the
/// scales of its units.
///
/// Every block of the core is a template on a policy of `mrd/num/policy.hpp`
/// and names its numbers by physical role through `Formats<Policy>`. Sensor
/// values arrive in SI (m, N, A) in both builds; the controller
/// (damper_controller.hpp) multiplies strokes by 1/s_D, forces by 1/s_F and
/// currents by 1/s_I at its input and its command by s_I at its output, so
/// that inside the core a stroke is counted in units of s_D metres, a force
/// in units of s_F newtons and a current in units of s_I amperes
/// (`CoreScales`, chosen at init from the configuration, below). The float
/// build keeps s_D = s_F = s_I = 1.
///
/// Fixed point (`num::Fixed32Policy`), all 32-bit, saturating, never wrapping:
///
/// | role    | unit (scaled)  | format | range (units)       | resolution (units) | holds                                 |
/// |---------|----------------|--------|---------------------|--------------------|---------------------------------------|
/// | Disp    | s_D m          | Q3.28  | [−8, 8)             | 3.7e−9             | stroke limit ≤ 0.42; RILD ≤ 4× it     |
/// | Velocity| s_V m per tick | Q3.28  | [−8, 8)             | 3.7e−9             | 8 s_D m/s ≤ 4 units; v_on, v_off      |
/// | Force   | s_F N          | Q19.12 | [−524 288, 524 288) | 2.4e−4             | F_d, load-cell and F_db limits        |
/// | Current | s_I A          | Q7.24  | [−128, 128)         | 6.0e−8             | drive peak and sensor limit           |
/// | Coef    | 1              | Q2.29  | [−4, 4)             | 1.9e−9             | filter poles and gains in (−1, 1)     |
/// | Gain    | s_F/s_D N/m    | Q23.8  | [−8.39e6, 8.39e6)   | 3.9e−3             | kη (Eq. 6.1)                          |
/// | Square  | s_I² A²        | Q9.22  | [−512, 512)         | 2.4e−7             | I_r² and I_cmd² (I_cmd ≤ 22.6 units)  |
///
/// A value in units is the SI value divided by its scale: at s_F = 2^−7 the
/// Force format spans ±4096 N at 1.9e−6 N.
///
/// At s_D = s_F = s_I = 1 (the thesis's 200 kN damper, its ±0.2921 m stroke
/// and 2.5 A coil) the table reads in m, N and A: Disp ±8 m for the 0.30 m
/// stroke limit, Force ±524 kN for its 400 kN desired-force limit and
/// 500 kN load cell, Gain ±8.39e6 N/m for kη = 2.63e6 N/m, Current ±128 A
/// for ±10 A commands and a 30 A drive peak, Square 512 A² for the ±10 A
/// command limit's 100 A².
///
/// Products (`num::mul<Out>`) form the exact 64-bit product of the two raw
/// values, round once to the output's resolution and saturate to its range.
/// Sums saturate. Sensor floats convert with `num::from_float` (round,
/// saturate, NaN → 0; the input guard rejects NaN before that). `init()`
/// checks that every configured constant is representable
/// (validate_config, controller_config.hpp, names what does not fit).
///
/// Choosing the scales (`select_core_scales`, fixed point only; each a power
/// of two in 2^−24 … 2^24):
/// - s_D is the power of two nearest to d_lim / 0.30 m in the log (d_lim the
///   input guard's stroke limit), the one that puts d_lim in (0.21, 0.42]
///   units, around the thesis's 0.30 m for which Disp was sized: the RILD
///   state (< 4 d_lim ≤ 1.7 units) always fits, and strokes and the RILD
///   filter's rounding keep the thesis's resolution relative to the stroke. Thesis 0.30 m → s_D = 1; a lab
///   damper's 30 mm → 1/8 (0.24 units); a 2 m stroke → 8.
/// - s_F is the smallest power of two for which the largest configured
///   force (desired-force limit, load-cell limit, deadband) fits Force and
///   kη fits Gain: max(F)/s_F ≤ 524 288 and kη s_D/s_F ≤ 8.39e6. The force
///   format then always holds the limits the input guard and the clamp of
///   F_d enforce, and when the forces set s_F its resolution is the finest
///   that does: the largest force spans more than 2^30 counts (1e−9 of it).
///   Thesis: 500 kN, kη = 2.63e6 N/m → s_F = 1. A 1 kN damper (limits 2 and
///   2.5 kN) → s_F = 2^−7 (2.5 kN is 320 000 units); a 2 MN damper (limits
///   4 and 5 MN) → s_F = 16. A stiff isolation layer raises s_F until kη
///   fits: the 1 kN damper with kη = 2e6 N/m at s_D = 1 → s_F = 1/4.
/// - s_I is the power of two nearest to I_r / 2.5 A in the log, i.e. the
///   one that puts the rated current I_r in (1.77, 3.54] units, around the
///   thesis's 2.5 A for which the current formats were sized: 0.5 A →
///   s_I = 1/4 (2 units), 1 A → 1/2, 2.5 A → 1, 5 A → 2, 10 A → 4
///   (2.5 units). The current formats' range and resolution follow the
///   coil's rating: I²t's m settles within 0.5 LSB/α ≈ 9e−3 s_I² A² of the
///   exact value (τ = 20 min, T = 1 ms), 0.14 % of the thesis's I_r² and at
///   most 0.3 % of any I_r² (a Q9.22 in A² would leave 3.6 % of a 0.5 A
///   coil's 0.25 A²), and the command limit of a 10 A coil's drive (4 I_r
///   as the thesis's, 40 A) keeps its square inside Square.
/// - Powers of two make the scaling exact: a float sensor value times 2^−k
///   is the same value with another exponent, and in fixed point a scaled
///   quantity is the unscaled one with its binary point moved. Scale 1 is
///   the identity, so the thesis's outputs are the unscaled ones bit for
///   bit. The scale is not a compile-time format choice: one binary holds
///   dampers from 1 kN to 2 MN and coils from 0.5 to 10 A.
/// - s_V, the velocity's unit (m per control tick), is the smallest power of
///   two that puts 8 s_D m/s (for the thesis 8 m/s, 32 times the damper's
///   0.25 m/s rating; for any damper 19 times its stroke limit per second)
///   within 4 units at the control period T: 8 s_D T ≤ 4 s_V, half the
///   format, so that the estimator's v − d never saturates below it. Thesis,
///   T = 1 ms: s_V = 2^−8 m per tick, a count of 1.5e−11 m per tick
///   (1.5e−8 m/s), 1/256 of a Disp count: the direction thresholds (6 and
///   3 mm/s) resolve to 7e−9 m/s and the estimate settles within 4e−8 m/s
///   of the exact filter of the same samples (velocity_estimator.hpp), so
///   the fixed build decides a velocity reversal on the same tick as the
///   float build unless the velocity passes the threshold within about
///   1e−7 m/s of it. A velocity above 31 m/s saturates, keeping its sign.
/// What no scale can hold is refused by validate_config with
/// ConfigError::kFixedPointRange, and `fixed_point_misfit()` names the
/// constant and its format's limit (a velocity threshold below one count
/// per tick, drive currents beyond 128 s_I, a stiffness so far above the
/// forces that F_d loses its resolution, …).

#include <cstdint>
#include <type_traits>

#include "mrd/num/policy.hpp"

namespace mrd::fw {

template <class Policy>
struct Formats;

template <>
struct Formats<num::Float32Policy> {
  using Disp = float;      ///< m
  using Velocity = float;  ///< m per tick
  using Force = float;    ///< N
  using Current = float;  ///< A
  using Coef = float;     ///< dimensionless filter coefficient
  using Gain = float;     ///< N/m
  using Square = float;   ///< A², mean-square coil current
};

template <>
struct Formats<num::Fixed32Policy> {
  using Disp = num::Fixed<3, 28>;
  using Velocity = num::Fixed<3, 28>;
  using Force = num::Fixed<19, 12>;
  using Current = num::Fixed<7, 24>;
  using Coef = num::Fixed<2, 29>;
  using Gain = num::Fixed<23, 8>;
  using Square = num::Fixed<9, 22>;
};

/// The float build in N lanes: N independent controllers (one per run of a
/// batch, host side) stepped together, each lane's numbers and decisions
/// those of the float build bit for bit. Every role is N floats (GCC vector
/// extension); the core's branches on data are masks (`LaneTypes`).
/// `Tag` tells apart builds of the same width compiled for different
/// instruction sets (a type of an unnamed namespace keeps each build's
/// functions to its own file).
template <int N, class Tag = void>
struct LanePolicy {
  static constexpr const char* kName = "float32-lanes";
  static constexpr int kLanes = N;
};

template <int N, class Tag>
struct Formats<LanePolicy<N, Tag>> {
  using Disp = num::LaneFloat<N>;
  using Velocity = num::LaneFloat<N>;
  using Force = num::LaneFloat<N>;
  using Current = num::LaneFloat<N>;
  using Coef = num::LaneFloat<N>;
  using Gain = num::LaneFloat<N>;
  using Square = num::LaneFloat<N>;
};

/// The one-controller build whose numbers each lane of `Policy` carries: the
/// policy itself, and the float build for LanePolicy<N> (its configuration
/// is checked and scaled as the float build's).
template <class Policy>
struct LaneScalar {
  using type = Policy;
};
template <int N, class Tag>
struct LaneScalar<LanePolicy<N, Tag>> {
  using type = num::Float32Policy;
};
template <class Policy>
using LaneScalarPolicy = typename LaneScalar<Policy>::type;

/// The types of a build's decisions and counts, by lane count: for one
/// controller (N = 1) a bool mask, 32-bit counts, an int, a 64-bit tick and
/// float samples; for N lanes each of them N wide (a tick counts 32 bits per
/// lane there: 49 days at 1 kHz, far beyond any run a batch steps).
template <int N, class Tag = void>
struct LaneSet {
  using Self = LaneSet;
  static constexpr int kLanes = N;
  using Mask = num::LaneMask<N>;
  using Count = num::LaneCount<N>;
  using Int = num::LaneMask<N>;
  using Tick = num::LaneCount<N>;
  using Sample = num::LaneFloat<N>;
  using Bits = num::LaneCount<N>;
};

template <>
struct LaneSet<1> {
  using Self = LaneSet;
  static constexpr int kLanes = 1;
  using Mask = bool;
  using Count = std::uint32_t;
  using Int = int;
  using Tick = std::uint64_t;
  using Sample = float;
  using Bits = std::uint32_t;
};

/// A build's lane set: one lane for the float, fixed and double builds.
template <class Policy>
struct LaneTypes : LaneSet<1> {};

template <int N, class Tag>
struct LaneTypes<LanePolicy<N, Tag>> : LaneSet<N, Tag> {};

/// The double-precision reference build of the idle-time estimator, the
/// mixing scheduler and the mixing task (host side; their float and fixed
/// builds use num::Float32Policy and num::Fixed32Policy, with the formats of
/// firmware/core/idle_estimator_formats.hpp).
struct Float64Policy {
  static constexpr const char* kName = "double";
};

/// The control core's double-precision build: the host's reference, with the
/// rounding of neither the float nor the fixed-point build, against which both
/// are measured (`mrd sim --numeric double`; never on a board). It takes the
/// same float inputs and gives the same float outputs as they do.
template <>
struct Formats<Float64Policy> {
  using Disp = double;
  using Velocity = double;
  using Force = double;
  using Current = double;
  using Coef = double;
  using Gain = double;
  using Square = double;
};

/// 2^e, exactly (|e| ≤ 1000), in constant expressions too.
constexpr double pow2(int e) noexcept {
  double v = 1.0;
  for (; e > 0; --e) v *= 2.0;
  for (; e < 0; ++e) v *= 0.5;
  return v;
}

/// Exponents of the core's unit scales: strokes in s_D = 2^disp_exp m,
/// forces in s_F = 2^force_exp N (gains in s_F/s_D N/m), currents in
/// s_I = 2^current_exp A (mean squares in s_I² A²), velocities in
/// s_V = 2^velocity_exp m per control tick.
struct CoreScales {
  int disp_exp = 0;
  int force_exp = 0;
  int current_exp = 0;
  int velocity_exp = 0;
  constexpr double disp_m() const noexcept { return pow2(disp_exp); }
  constexpr double velocity_m() const noexcept { return pow2(velocity_exp); }
  constexpr double force_n() const noexcept { return pow2(force_exp); }
  constexpr double current_a() const noexcept { return pow2(current_exp); }
};

/// Bounds of the scale exponents: s_D, s_F, s_I ∈ [2^−24, 2^24].
inline constexpr int kMaxScaleExp = 24;
/// The stroke limit and the rated current the formats were sized for (the
/// thesis's damper and coil).
inline constexpr double kScaleReferenceStroke_m = 0.30;
inline constexpr double kScaleReferenceCurrent_a = 2.5;
/// The velocity format holds 8 s_D m/s within half its range.
inline constexpr double kVelocityRangeStrokesPerS = 8.0;

/// The smallest e in [−kMaxScaleExp, kMaxScaleExp] with v ≤ top·2^e.
constexpr int smallest_exp_within(double v, double top) noexcept {
  int e = -kMaxScaleExp;
  while (e < kMaxScaleExp && !(v <= top * pow2(e))) ++e;
  return e;
}

/// The scales for a configuration whose input guard's stroke limit is
/// `disp_limit_m`, whose largest force is `force_bound_n`, whose RILD gain is
/// `gain_n_m` (kη), whose coil is rated `rated_current_a` and whose control
/// period is `period_s` (rules above). Float: s_D = s_F = s_I = s_V = 1.
template <class Policy>
constexpr CoreScales select_core_scales(double disp_limit_m, double force_bound_n, double gain_n_m,
                                        double rated_current_a, double period_s) noexcept {
  using F = Formats<Policy>;
  constexpr double kSqrt2 = 1.4142135623730951;
  CoreScales s;
  if constexpr (std::is_floating_point_v<typename F::Force>) {
    return s;
  } else {
    // d_lim / s_D ≤ 0.30 m · √2: the smallest such exponent puts it in (0.21, 0.42].
    s.disp_exp = smallest_exp_within(disp_limit_m, kScaleReferenceStroke_m * kSqrt2);
    // max(F)/s_F ≤ Force's end and kη s_D/s_F ≤ Gain's end: the larger exponent.
    const int by_force = smallest_exp_within(force_bound_n, F::Force::max_value());
    const int by_gain = smallest_exp_within(gain_n_m * s.disp_m(), F::Gain::max_value());
    s.force_exp = by_force > by_gain ? by_force : by_gain;
    // I_r / s_I ≤ 2.5 A · √2: the smallest such exponent puts I_r / s_I in (1.77, 3.54].
    s.current_exp = smallest_exp_within(rated_current_a, kScaleReferenceCurrent_a * kSqrt2);
    // 8 s_D m/s × T ≤ 4 s_V.
    s.velocity_exp = smallest_exp_within(kVelocityRangeStrokesPerS * s.disp_m() * period_s, 4.0);
    return s;
  }
}

/// True when `v` lies in the range of T (float: finite and within ±FLT_MAX).
template <class T>
constexpr bool representable(double v) noexcept {
  if constexpr (std::is_floating_point_v<T>) {
    return v == v && v <= 3.4028234e38 && v >= -3.4028234e38;
  } else {
    return v >= T::lowest_value() && v <= T::max_value();
  }
}

/// s·v for s = −1 (`negative`) or +1, without a multiply (per lane for a mask).
template <class M, class T>
[[gnu::always_inline]] constexpr T signed_by(M negative, T v) noexcept {
  return negative ? -v : v;
}

}  // namespace mrd::fw
