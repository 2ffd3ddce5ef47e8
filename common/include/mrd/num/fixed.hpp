#pragma once
/// Signed fixed-point Q numbers in 32 bits with saturating arithmetic.
///
/// `Fixed<I, F>` stores a value v as the int32 raw = round(v · 2^F), with
/// I integer bits, F fractional bits and one sign bit (I + F = 31), i.e. the
/// classic Q(I).(F) format: Q0.31 (CMSIS q31) is `Fixed<0, 31>`, Q15.16 is
/// `Fixed<15, 16>`. Range [−2^I, 2^I − 2^−F], resolution 2^−F.
///
/// Scaling and overflow behaviour (the same for every operation):
/// - conversions from double/float round to nearest and saturate to the
///   range; NaN converts to 0 (callers that must treat NaN as a fault check
///   for it before converting);
/// - +, −, negation, ×, ÷ saturate the exact result to the range (× and ÷
///   in a 64-bit accumulator; + and − from the overflow flag); they never
///   wrap;
/// - × and `mul<Out>` round the 64-bit product to nearest (ties towards +∞)
///   when dropping fractional bits;
/// - ÷ by zero saturates to the range end with the sign of the dividend
///   (0/0 gives 0).
/// Nothing here allocates, throws or touches I/O; it builds freestanding.

#include <cmath>
#include <cstdint>
#include <limits>

namespace mrd::num {

namespace detail {
/// v saturated to int32. The common case (v fits) is one sign-extension and
/// one compare; the range end is picked only when v does not fit.
constexpr std::int32_t saturate_i32(std::int64_t v) noexcept {
  const auto low = static_cast<std::int32_t>(v);  // modular (C++20)
  if (low == v) [[likely]]
    return low;
  return v > 0 ? std::numeric_limits<std::int32_t>::max() : std::numeric_limits<std::int32_t>::min();
}

/// a + b and a − b saturated to int32, from the processor's overflow flag:
/// the exact sum leaves the range only when a and b (a and −b) have the same
/// sign, and then on the side of a's sign.
constexpr std::int32_t add_saturate_i32(std::int32_t a, std::int32_t b) noexcept {
  std::int32_t r = 0;
  if (__builtin_add_overflow(a, b, &r)) [[unlikely]]
    return a < 0 ? std::numeric_limits<std::int32_t>::min() : std::numeric_limits<std::int32_t>::max();
  return r;
}
constexpr std::int32_t sub_saturate_i32(std::int32_t a, std::int32_t b) noexcept {
  std::int32_t r = 0;
  if (__builtin_sub_overflow(a, b, &r)) [[unlikely]]
    return a < 0 ? std::numeric_limits<std::int32_t>::min() : std::numeric_limits<std::int32_t>::max();
  return r;
}

/// Shifts a 64-bit value right by `shift` bits with rounding to nearest
/// (ties towards +∞), or left by −shift bits with saturation, then saturates
/// to int32. |v| ≤ 2^62 (a product of two int32, or an int32).
constexpr std::int32_t shift_round_saturate(std::int64_t v, int shift) noexcept {
  if (shift > 0) {
    if (shift >= 63) return 0;
    const std::int64_t half = std::int64_t{1} << (shift - 1);
    // v + half cannot overflow: every caller passes a product of two int32
    // or an int32 (|v| ≤ 2^62), and half ≤ 2^61.
    return saturate_i32((v + half) >> shift);
  }
  if (shift < 0) {
    const int left = -shift;
    if (left >= 32) return v == 0 ? 0 : saturate_i32(v > 0 ? std::numeric_limits<std::int64_t>::max()
                                                            : std::numeric_limits<std::int64_t>::min());
    const std::int64_t lim = std::int64_t{std::numeric_limits<std::int32_t>::max()} >> left;
    if (v > lim) return std::numeric_limits<std::int32_t>::max();
    if (v < -lim - 1) return std::numeric_limits<std::int32_t>::min();
    return static_cast<std::int32_t>(v * (std::int64_t{1} << left));
  }
  return saturate_i32(v);
}
}  // namespace detail

template <int IntBits, int FracBits>
class Fixed {
  static_assert(IntBits >= 0 && FracBits >= 0 && IntBits + FracBits == 31,
                "Fixed<I, F> needs I + F == 31 (one sign bit in 32)");

 public:
  using raw_type = std::int32_t;
  static constexpr int kIntBits = IntBits;
  static constexpr int kFracBits = FracBits;
  /// 2^F as a double: one unit of the value in raw counts.
  static constexpr double kScale = static_cast<double>(std::int64_t{1} << FracBits);

  constexpr Fixed() noexcept = default;

  static constexpr Fixed from_raw(raw_type raw) noexcept {
    Fixed f;
    f.raw_ = raw;
    return f;
  }

  /// Rounds to nearest, saturates to the range; NaN gives 0.
  static constexpr Fixed from_double(double v) noexcept {
    if (v != v) return Fixed{};
    const double scaled = v * kScale;
    if (scaled >= 2147483647.0) return max();
    if (scaled <= -2147483648.0) return lowest();
    // Nearest, ties away from zero, from the exact fraction (scaled + 0.5
    // would round twice: 0.49999999999999994 to 1).
    const auto whole = static_cast<std::int64_t>(scaled);
    const double frac = scaled - static_cast<double>(whole);
    const std::int64_t r = whole + (frac >= 0.5 ? 1 : 0) - (frac <= -0.5 ? 1 : 0);
    return from_raw(static_cast<raw_type>(r));  // |scaled| < 2^31 above: r fits
  }
  static constexpr Fixed from_float(float v) noexcept { return from_double(static_cast<double>(v)); }

  constexpr double to_double() const noexcept { return static_cast<double>(raw_) / kScale; }
  constexpr float to_float() const noexcept { return static_cast<float>(to_double()); }
  constexpr raw_type raw() const noexcept { return raw_; }

  static constexpr Fixed max() noexcept { return from_raw(std::numeric_limits<raw_type>::max()); }
  static constexpr Fixed lowest() noexcept { return from_raw(std::numeric_limits<raw_type>::min()); }
  /// Smallest positive step, 2^−F.
  static constexpr Fixed epsilon() noexcept { return from_raw(1); }
  static constexpr double max_value() noexcept { return max().to_double(); }
  static constexpr double lowest_value() noexcept { return lowest().to_double(); }

  constexpr bool is_saturated() const noexcept {
    return raw_ == std::numeric_limits<raw_type>::max() || raw_ == std::numeric_limits<raw_type>::min();
  }

  friend constexpr Fixed operator+(Fixed a, Fixed b) noexcept { return from_raw(detail::add_saturate_i32(a.raw_, b.raw_)); }
  friend constexpr Fixed operator-(Fixed a, Fixed b) noexcept { return from_raw(detail::sub_saturate_i32(a.raw_, b.raw_)); }
  friend constexpr Fixed operator-(Fixed a) noexcept { return from_raw(detail::sub_saturate_i32(0, a.raw_)); }
  friend constexpr Fixed operator*(Fixed a, Fixed b) noexcept {
    return from_raw(detail::shift_round_saturate(std::int64_t{a.raw_} * b.raw_, FracBits));
  }
  friend constexpr Fixed operator/(Fixed a, Fixed b) noexcept {
    if (b.raw_ == 0) {
      if (a.raw_ == 0) return Fixed{};
      return a.raw_ > 0 ? max() : lowest();
    }
    const std::int64_t num = std::int64_t{a.raw_} * (std::int64_t{1} << FracBits);
    return from_raw(detail::saturate_i32(num / b.raw_));
  }
  constexpr Fixed& operator+=(Fixed b) noexcept { return *this = *this + b; }
  constexpr Fixed& operator-=(Fixed b) noexcept { return *this = *this - b; }
  constexpr Fixed& operator*=(Fixed b) noexcept { return *this = *this * b; }

  friend constexpr bool operator==(Fixed a, Fixed b) noexcept { return a.raw_ == b.raw_; }
  friend constexpr auto operator<=>(Fixed a, Fixed b) noexcept { return a.raw_ <=> b.raw_; }

 private:
  raw_type raw_ = 0;
};

/// Multiplies two Q numbers of any formats into a third, with one rounding
/// and saturation: raw_out = round(raw_a·raw_b / 2^(Fa+Fb−Fout)).
template <class Out, int Ia, int Fa, int Ib, int Fb>
constexpr Out mul(Fixed<Ia, Fa> a, Fixed<Ib, Fb> b) noexcept {
  return Out::from_raw(
      detail::shift_round_saturate(std::int64_t{a.raw()} * b.raw(), Fa + Fb - Out::kFracBits));
}

/// Converts between Q formats: rounds when dropping bits, saturates.
template <class Out, int I, int F>
constexpr Out q_cast(Fixed<I, F> v) noexcept {
  return Out::from_raw(detail::shift_round_saturate(std::int64_t{v.raw()}, F - Out::kFracBits));
}

/// Common formats.
using Q31 = Fixed<0, 31>;     ///< [−1, 1), CMSIS q31
using Q15_16 = Fixed<15, 16>; ///< [−32768, 32768), 1.5e−5 resolution
using Q7_24 = Fixed<7, 24>;   ///< [−128, 128), 6e−8 resolution

}  // namespace mrd::num
