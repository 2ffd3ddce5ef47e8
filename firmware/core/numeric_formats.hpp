#pragma once
/// The number formats of the control core, per numeric policy.
///
/// Every block of the core is a template on a policy of `mrd/num/policy.hpp`
/// and names its numbers by physical role through `Formats<Policy>`. Units are
/// SI in both builds (m, N, A), so the same source converts sensor values the
/// same way; only the representation differs.
///
/// Fixed point (`num::Fixed32Policy`), all 32-bit, saturating, never wrapping:
///
/// | role    | unit           | format | range               | resolution  | why this range                         |
/// |---------|----------------|--------|---------------------|-------------|----------------------------------------|
/// | Disp    | m (and m/tick) | Q3.28  | [−8, 8) m           | 3.7e−9 m    | stroke ±0.292 m; RILD state ≤ 3× input |
/// | Force   | N              | Q19.12 | [−524 288, 524 288) | 2.4e−4 N    | damper ≤ 200 kN; load cell ≤ 500 kN    |
/// | Current | A              | Q7.24  | [−128, 128) A       | 6.0e−8 A    | command ±10 A, drive peak 30 A         |
/// | Coef    | 1              | Q2.29  | [−4, 4)             | 1.9e−9      | filter poles and gains in (−1, 1)      |
/// | Gain    | N/m            | Q23.8  | [−8.39e6, 8.39e6)   | 3.9e−3 N/m  | kη = 2.63e6 N/m (Eq. 6.1)              |
/// | Square  | A²             | Q9.22  | [−512, 512) A²      | 2.4e−7 A²   | i² ≤ 225 A² at the sensor's 15 A       |
///
/// Products (`num::mul<Out>`) form the exact 64-bit product of the two raw
/// values, round once to the output's resolution and saturate to its range.
/// Sums saturate. Sensor floats convert with `num::from_float` (round,
/// saturate, NaN → 0; the input guard rejects NaN before that). `init()`
/// checks that every configured constant is representable.

#include <cstdint>
#include <type_traits>

#include "mrd/num/policy.hpp"

namespace mrd::fw {

template <class Policy>
struct Formats;

template <>
struct Formats<num::Float32Policy> {
  using Disp = float;     ///< m, or m per tick for velocities
  using Force = float;    ///< N
  using Current = float;  ///< A
  using Coef = float;     ///< dimensionless filter coefficient
  using Gain = float;     ///< N/m
  using Square = float;   ///< A², mean-square coil current
};

template <>
struct Formats<num::Fixed32Policy> {
  using Disp = num::Fixed<3, 28>;
  using Force = num::Fixed<19, 12>;
  using Current = num::Fixed<7, 24>;
  using Coef = num::Fixed<2, 29>;
  using Gain = num::Fixed<23, 8>;
  using Square = num::Fixed<9, 22>;
};

/// The double-precision reference build of the idle-time estimator, the
/// mixing scheduler and the mixing task (host side; their float and fixed
/// builds use num::Float32Policy and num::Fixed32Policy, with the formats of
/// firmware/core/idle_estimator_formats.hpp).
struct Float64Policy {
  static constexpr const char* kName = "double";
};

/// True when `v` lies in the range of T (float: finite and within ±FLT_MAX).
template <class T>
constexpr bool representable(double v) noexcept {
  if constexpr (std::is_floating_point_v<T>) {
    return v == v && v <= 3.4028234e38 && v >= -3.4028234e38;
  } else {
    return v >= T::lowest_value() && v <= T::max_value();
  }
}

/// s·v for s = −1 (`negative`) or +1, without a multiply.
template <class T>
constexpr T signed_by(bool negative, T v) noexcept {
  return negative ? -v : v;
}

}  // namespace mrd::fw
