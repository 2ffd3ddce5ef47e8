#pragma once
/// Numeric policies: the one place where a control block learns whether it
/// computes in float or in fixed point.
///
/// A block is written once as a template on a policy `N`, takes its number
/// types per physical role from a formats table keyed on `N` (for the control
/// core, `fw::Formats<N>`), and touches numbers only through those types and
/// the free functions below, which are overloaded for `float` and for every
/// `Fixed<I, F>`:
///
///   - `num::from_double<T>(x)`  design-time conversion (coefficients, limits)
///   - `num::to_double(x)`       for tests, logs and the host side
///   - `num::mul<Out>(a, b)`     product into the wanted type (fixed point:
///                               one rounding, saturated)
///   - `num::clamp(x, lo, hi)`   saturating clamp
///
/// Coefficients are designed in double once, at `init()`, then quantized.

#include <cstdint>

#include "mrd/num/fixed.hpp"

namespace mrd::num {

template <class T>
constexpr T from_double(double v) noexcept {
  if constexpr (requires { T::from_double(v); }) {
    return T::from_double(v);
  } else {
    return static_cast<T>(v);
  }
}

constexpr double to_double(float v) noexcept { return static_cast<double>(v); }
constexpr double to_double(double v) noexcept { return v; }
template <int I, int F>
constexpr double to_double(Fixed<I, F> v) noexcept { return v.to_double(); }

/// float × float → float (Out must be float).
template <class Out>
constexpr Out mul(float a, float b) noexcept {
  static_assert(sizeof(Out) == sizeof(float), "float products stay float");
  return a * b;
}

/// double × double → double (Out must be double): the host's reference build.
template <class Out>
constexpr Out mul(double a, double b) noexcept {
  static_assert(sizeof(Out) == sizeof(double), "double products stay double");
  return a * b;
}

template <class T>
constexpr T clamp(T v, T lo, T hi) noexcept {
  return v < lo ? lo : (hi < v ? hi : v);
}

/// Run-time conversion of a float sample (a sensor value crossing the
/// control core's boundary) without double arithmetic, for targets whose FPU
/// is single precision. Fixed point: v·2^F in float (exact, a power of two),
/// rounded to nearest (ties away from zero; above 2^23 counts, where float
/// has no fraction left, the float value itself), saturated; NaN gives 0.
template <class T>
constexpr T from_float(float v) noexcept {
  if constexpr (requires { T::kFracBits; }) {
    if (v != v) return T{};
    const float scaled = v * static_cast<float>(std::int64_t{1} << T::kFracBits);
    if (scaled >= 2147483648.0f) return T::max();
    if (scaled <= -2147483648.0f) return T::lowest();
    const float r = scaled >= 0.0f ? scaled + 0.5f : scaled - 0.5f;
    return T::from_raw(static_cast<typename T::raw_type>(r));
  } else {
    return static_cast<T>(v);
  }
}

/// Run-time conversion back to float (raw·2^−F, rounded to float's 24 bits).
constexpr float to_float(float v) noexcept { return v; }
constexpr float to_float(double v) noexcept { return static_cast<float>(v); }
template <int I, int F>
constexpr float to_float(Fixed<I, F> v) noexcept {
  return static_cast<float>(v.raw()) * (1.0f / static_cast<float>(std::int64_t{1} << F));
}

/// The single-precision float build. A policy only names a build: each block
/// maps it to the number types of its physical roles (for the control core,
/// `fw::Formats<Policy>` in firmware/core/numeric_formats.hpp).
struct Float32Policy {
  static constexpr const char* kName = "float32";
};

/// The 32-bit fixed-point build (formats per role in the block that uses them,
/// each documented with its range, resolution and overflow behaviour).
struct Fixed32Policy {
  static constexpr const char* kName = "fixed32";
};

}  // namespace mrd::num
