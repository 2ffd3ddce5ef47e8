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

#include <bit>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "mrd/num/fixed.hpp"

namespace mrd::num {

/// Lanes: N values of one role side by side, one per independent run, as a
/// GCC vector (`LaneFloat<N>`); comparisons give masks (`LaneMask<N>`, 0 or
/// −1 per lane) and `m ? a : b` picks per lane. A block written with masks
/// and ternaries instead of data-dependent branches builds for one value
/// (a `bool` mask, a plain ternary) and for lanes from the same source.
/// (Member typedefs: GCC keeps a dependent vector_size there, not on an
/// alias template.)
template <int N>
struct LaneVectors {
  typedef float Float __attribute__((vector_size(4 * N)));
  typedef std::int32_t Mask __attribute__((vector_size(4 * N)));
  typedef std::uint32_t Count __attribute__((vector_size(4 * N)));
};
template <int N>
using LaneFloat = typename LaneVectors<N>::Float;
template <int N>
using LaneMask = typename LaneVectors<N>::Mask;
template <int N>
using LaneCount = typename LaneVectors<N>::Count;

/// A GCC vector type (not a class, not a pointer, subscriptable).
template <class T>
concept LaneVector = !std::is_class_v<T> && !std::is_pointer_v<T> && !std::is_arithmetic_v<T> &&
                     !std::is_enum_v<T> && requires(T v) { v[0]; };

/// The element type of a lane vector.
template <LaneVector V>
using LaneElement = std::remove_cvref_t<decltype(V{}[0])>;

/// `m ? a : b`, per lane for a mask of lanes.
template <class M, class T>
[[gnu::always_inline]] constexpr T select(M m, T a, T b) noexcept {
  return m ? a : b;
}

/// Some lane's / every lane's mask is set (a bool is its own).
constexpr bool any(bool m) noexcept { return m; }
constexpr bool all(bool m) noexcept { return m; }
/// (Lanes: one vector test where the instruction set has it, AVX's vptest
/// on 32 bytes, SSE2's byte masks on 16; else the mask's bytes as 64-bit
/// words, OR-ed. No lane by lane extraction.)
template <LaneVector M>
[[gnu::always_inline]] inline bool any(M m) noexcept {
  static_assert(sizeof(M) % 8 == 0, "masks of an even number of 32-bit lanes");
#if defined(__AVX__)
  if constexpr (sizeof(M) == 32) {
    typedef long long Words __attribute__((vector_size(32)));
    Words w;
    __builtin_memcpy(&w, &m, sizeof m);
    return __builtin_ia32_ptestz256(w, w) == 0;
  }
#endif
#if defined(__SSE2__)
  if constexpr (sizeof(M) % 16 == 0) {
    typedef char Bytes __attribute__((vector_size(16)));
    int bits = 0;
    for (std::size_t k = 0; k < sizeof(M) / 16; ++k) {
      Bytes b;
      __builtin_memcpy(&b, reinterpret_cast<const char*>(&m) + 16 * k, 16);
      bits |= __builtin_ia32_pmovmskb128(b);
    }
    return bits != 0;
  }
#endif
  std::uint64_t w[sizeof(M) / 8];
  __builtin_memcpy(w, &m, sizeof m);
  std::uint64_t r = 0;
  for (std::uint64_t x : w) r |= x;
  return r != 0;
}
template <LaneVector M>
[[gnu::always_inline]] inline bool all(M m) noexcept {
  return !any(~m);  // a mask lane is 0 or −1: every lane set is no lane of ~m set
}

/// `v` in every lane (T a lane vector) or `v` itself.
template <class T, class S>
[[gnu::always_inline]] constexpr T splat(S v) noexcept {
  if constexpr (LaneVector<T>) {
    T r{};
    for (std::size_t i = 0; i < sizeof(T) / sizeof(r[0]); ++i) r[i] = static_cast<LaneElement<T>>(v);
    return r;
  } else {
    return static_cast<T>(v);
  }
}

/// A true mask of type M (every lane set).
template <class M>
[[gnu::always_inline]] constexpr M all_set() noexcept {
  if constexpr (LaneVector<M>) {
    return M{} == M{};
  } else {
    return true;
  }
}

/// Counts one more (saturating at 2^32 − 1) where `m` is set.
constexpr void bump_where(std::uint32_t& c, bool m) noexcept {
  if (m && c != 0xffffffffu) ++c;
}
template <LaneVector C, LaneVector M>
[[gnu::always_inline]] constexpr void bump_where(C& c, M m) noexcept {
#if defined(__SSE4_1__) || defined(__ARM_NEON)
  // A mask lane is 0 or −1, so c − m counts one more where m is set; the one
  // count that wraps (2^32 − 1 to 0) falls below c, and the larger of the two
  // keeps 2^32 − 1 there: an unsigned max, one instruction (pmaxud, umax).
  const C more = c - (C)m;
  c = more < c ? c : more;
#else
  // SSE2 has no unsigned compare: the count's top is tested with pcmpeqd.
  c -= (C)(m & (M)(c != 0xffffffffu));  // a mask lane is 0 or −1, so & is &&
#endif
}

/// A lane value of a scalar role: `v` in lane `l` (1 lane: `v` itself).
template <class T>
constexpr auto lane_of(const T& v, int l) noexcept {
  if constexpr (LaneVector<T>) {
    return v[l];
  } else {
    (void)l;
    return v;
  }
}

template <class T>
constexpr T from_double(double v) noexcept {
  if constexpr (requires { T::from_double(v); }) {
    return T::from_double(v);
  } else if constexpr (LaneVector<T>) {
    return splat<T>(static_cast<LaneElement<T>>(v));
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

/// Lanes of floats: the float product per lane.
template <class Out, LaneVector V>
[[gnu::always_inline]] constexpr Out mul(V a, V b) noexcept {
  static_assert(std::is_same_v<Out, V>, "lane products stay in their lanes");
  return a * b;
}

template <class T>
[[gnu::always_inline]] constexpr T clamp(T v, T lo, T hi) noexcept {
  return v < lo ? lo : (hi < v ? hi : v);
}

/// Run-time conversion of a float sample (a sensor value crossing the
/// control core's boundary) without double arithmetic, for targets whose FPU
/// is single precision. Fixed point: v·2^F in float (exact, a power of two),
/// rounded to nearest (ties away from zero; from 2^23 counts on, where float
/// has no fraction left, the float value itself), saturated; NaN gives 0.
/// The float just below ½ (nextafterf(0.5f, 0)).
inline constexpr float kJustBelowHalf = 0.49999997f;

template <class T>
constexpr T from_float(float v) noexcept {
  if constexpr (requires { T::kFracBits; }) {
    const float scaled = v * static_cast<float>(std::int64_t{1} << T::kFracBits);
    if (!(__builtin_fabsf(scaled) < 2147483648.0f)) [[unlikely]] {
      if (v != v) return T{};
      return scaled > 0.0f ? T::max() : T::lowest();
    }
    // Nearest, ties away from zero: scaled ± the float just below ½, then
    // toward zero. ± ½ itself would round twice (0.49999997 + 0.5 is 1 in
    // float; an odd count in [2^23, 2^24), where float steps by 1, plus 0.5
    // ties to the even count above); with 0.49999997 the sum rounds to the
    // right side of every integer, for every float below 2^31 (checked on
    // all of them; fixed_point_test.cpp checks whole binades).
    const float r = scaled + __builtin_copysignf(kJustBelowHalf, scaled);
    return T::from_raw(static_cast<typename T::raw_type>(r));
  } else {
    return static_cast<T>(v);
  }
}

/// Lanes of float samples into lanes of floats: themselves.
template <class T, LaneVector V>
[[gnu::always_inline]] constexpr T from_float(V v) noexcept {
  static_assert(std::is_same_v<T, V>, "lanes of floats only");
  return v;
}

/// Run-time conversion back to float (raw·2^−F, rounded to float's 24 bits).
constexpr float to_float(float v) noexcept { return v; }
constexpr float to_float(double v) noexcept { return static_cast<float>(v); }
template <LaneVector V>
[[gnu::always_inline]] constexpr V to_float(V v) noexcept {
  return v;
}
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
