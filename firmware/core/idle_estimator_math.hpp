#pragma once
/// Integer arithmetic of the idle-time estimator's fixed-point build: exp(−x),
/// ln(n/d), ratios of 64-bit tick counts, and the displaced-volume counter.
/// Integer operations only (64-bit multiply, shift, divide); no float, no
/// double, no heap. Builds freestanding.
///
/// exp(−x), x ≥ 0 given in Q5.26 (x < 32), result in Q1.30:
/// <pre>
///   x = k·ln2 + j·ln2/16 + r,  k ≥ 0, 0 ≤ j < 16, 0 ≤ r < ln2/16 = 0.0433     (in Q56: exact to 2^−56)
///   exp(−x) = 2^−k · 2^(−j/16) · exp(−r)
///   2^(−j/16): a table of 16 entries in Q1.30 (rounded to nearest);
///   exp(−r) = 1 − r(1 − r/2(1 − r/3(1 − r/4(1 − r/5))))  (Taylor, Horner, in Q1.30 with int64)
/// </pre>
/// Truncation r⁶/720 < 1e−11; table entry, five Horner products and the two
/// final products each round by ≤ ½ LSB: |error| ≤ 4·2^−30 = 3.8e−9 over
/// the whole range (tested against std::exp on [0, 32) in
/// tests/unit/idle_estimator_math_test.cpp). x ≥ 32 gives 0 (exp(−32) =
/// 1.3e−14 is below the LSB 9.3e−10).
///
/// ln(n/d), n ≥ d > 0 given as Q1.30 raw values, result in Q5.26:
/// <pre>
///   q = n/d in Q32 (64-bit quotient);  q = m·2^e, m ∈ [1, 2)
///   m = (1 + j/16)·m',  j = the top four fraction bits of m, m' ∈ [1, 1 + 1/16]
///   ln(m') = 2·atanh(s) = 2(s + s³/3 + s⁵/5),  s = (m' − 1)/(m' + 1) < 0.031
///   ln(n/d) = e·ln2 + ln(1 + j/16) + ln(m')     (ln2 and the table in Q1.30)
/// </pre>
/// Truncation 2s⁷/7 < 6e−12; the quotient, the reciprocal table, s and the
/// series round by a few 2^−31; the result rounds to Q5.26 (½ LSB =
/// 7.5e−9): |error| ≤ 1.2e−8 for n/d in [1, 2^31) (tested against std::log).
/// Results above 32 saturate to 32 − 2^−26.

#include <array>
#include <cstdint>

namespace mrd::fw::idle_math {

inline constexpr int kQ30 = 30;
inline constexpr std::int64_t kOneQ30 = std::int64_t{1} << kQ30;
inline constexpr int kQ26 = 26;
/// Largest Q5.26 raw value (32 − 2^−26).
inline constexpr std::int32_t kMaxExpoRaw = 0x7FFFFFFF;

/// ln 2 in Q56 (round(ln2·2^56)) and in Q1.30.
inline constexpr std::int64_t kLn2Q56 = 49946518145322874LL;
inline constexpr std::int64_t kLn2Q30 = 744261118LL;
/// ln2/16 in Q56.
inline constexpr std::int64_t kLn2Over16Q56 = 3121657384082680LL;

/// 2^(−j/16) in Q1.30, j = 0..15.
inline constexpr std::array<std::int32_t, 16> kExp2NegSixteenths = {
    1073741824, 1028218693, 984625594, 942880699, 902905651, 864625413, 827968132, 792865000,
    759250125, 727060411, 696235434, 666717336, 638450708, 611382493, 585461881, 560640218};
/// ln(1 + j/16) in Q1.30, j = 0..15.
inline constexpr std::array<std::int32_t, 16> kLnOnePlusSixteenths = {
    0, 65095192, 126468572, 184522808, 239598564, 291986604, 341937090, 389666807,
    435364845, 479197128, 521310048, 561833416, 600882877, 638561895, 674963409, 710171213};
/// 1/(1 + j/16) in Q1.30, j = 0..15.
inline constexpr std::array<std::int32_t, 16> kInvOnePlusSixteenths = {
    1073741824, 1010580540, 954437177, 904203641, 858993459, 818089009, 780903145, 746950834,
    715827883,  687194767,  660764199, 636291451, 613566757, 592409282, 572662306, 554189329};

/// a·b/2^30 rounded to nearest (ties towards +∞); |a·b| must fit int64.
constexpr std::int64_t mul_q30(std::int64_t a, std::int64_t b) noexcept {
  return (a * b + (std::int64_t{1} << (kQ30 - 1))) >> kQ30;
}

/// Right shift with rounding to nearest (ties towards +∞), shift ≥ 1.
constexpr std::int64_t shift_round(std::int64_t v, int shift) noexcept {
  return shift >= 63 ? 0 : (v + (std::int64_t{1} << (shift - 1))) >> shift;
}

/// exp(−x) for x ≥ 0 in Q5.26 (negative x counts as 0), result in Q1.30 raw.
constexpr std::int32_t exp_neg_q26(std::int32_t x_raw) noexcept {
  if (x_raw <= 0) return static_cast<std::int32_t>(kOneQ30);
  // Range reduction in Q56: x < 32 → x·2^30 < 2^61.
  const std::int64_t x56 = std::int64_t{x_raw} << 30;
  const std::int64_t k = x56 / kLn2Q56;
  std::int64_t r56 = x56 - k * kLn2Q56;
  const std::int64_t j = r56 / kLn2Over16Q56;
  r56 -= j * kLn2Over16Q56;
  if (k >= 32) return 0;
  const std::int64_t r = shift_round(r56, 26);  // r in Q1.30, < 0.0434
  // exp(−r) by Horner: p = 1 − r/5, 1 − r/4·p, 1 − r/3·p, 1 − r/2·p, 1 − r·p.
  std::int64_t p = kOneQ30 - (r + 2) / 5;
  p = kOneQ30 - (mul_q30(r, p) + 2) / 4;
  p = kOneQ30 - (mul_q30(r, p) + 1) / 3;
  p = kOneQ30 - (mul_q30(r, p) + 1) / 2;
  p = kOneQ30 - mul_q30(r, p);
  const std::int64_t v = mul_q30(kExp2NegSixteenths[static_cast<std::size_t>(j)], p);
  return static_cast<std::int32_t>(k == 0 ? v : shift_round(v, static_cast<int>(k)));
}

/// Index of the highest set bit of v > 0.
constexpr int top_bit(std::uint64_t v) noexcept {
  int b = 0;
  while (v >>= 1) ++b;
  return b;
}

/// ln(n/d) for n ≥ d > 0 (raw values of the same Q format), result in Q5.26
/// raw, saturated to [0, 32 − 2^−26]; 0 when n ≤ d or d ≤ 0.
constexpr std::int32_t ln_quotient_q26(std::int32_t n_raw, std::int32_t d_raw) noexcept {
  if (d_raw <= 0 || n_raw <= d_raw) return 0;
  // q = n/d in Q32 (n < 2^31, so n·2^32 < 2^63).
  const auto q = static_cast<std::uint64_t>((std::int64_t{n_raw} << 32) / d_raw);
  const int e = top_bit(q) - 32;  // q ≥ 2^32: e ≥ 0
  int ex = e;
  std::int64_t m = static_cast<std::int64_t>((q + (std::uint64_t{1} << (e + 1))) >> (e + 2));  // m ∈ [1, 2] in Q1.30
  if (m >= 2 * kOneQ30) {  // rounded up to 2
    m >>= 1;
    ++ex;
  }
  const auto jj = static_cast<std::size_t>((m >> 26) & 15);
  const std::int64_t mp = mul_q30(m, kInvOnePlusSixteenths[jj]);  // m' ∈ [1, 1 + 1/16]
  const std::int64_t s = ((mp - kOneQ30) << kQ30) / (mp + kOneQ30);
  const std::int64_t s2 = mul_q30(s, s);
  // 2(s + s³/3 + s⁵/5) = 2s(1 + s²(1/3 + s²/5)).
  const std::int64_t inner = kOneQ30 / 3 + mul_q30(s2, kOneQ30 / 5);
  const std::int64_t series = 2 * mul_q30(s, kOneQ30 + mul_q30(s2, inner));
  const std::int64_t ln_q30 = ex * kLn2Q30 + kLnOnePlusSixteenths[jj] + series;
  const std::int64_t out = shift_round(ln_q30, kQ30 - kQ26);
  return out >= kMaxExpoRaw ? kMaxExpoRaw : static_cast<std::int32_t>(out < 0 ? 0 : out);
}

/// round(a·2^frac/b) for 0 ≤ a, 0 < b (64-bit), saturated to int32: the
/// ratio of two tick counts in Q(31 − frac).frac. Both are shifted right
/// together until b < 2^32 (the shift drops at most b·2^−32 relative).
constexpr std::int32_t ratio_q(std::uint64_t a, std::uint64_t b, int frac) noexcept {
  if (b == 0) return a == 0 ? 0 : 0x7FFFFFFF;
  while (b >= (std::uint64_t{1} << 32)) {
    a >>= 1;
    b >>= 1;
  }
  const std::uint64_t whole = a / b;
  if (whole >= (std::uint64_t{1} << (31 - frac))) return 0x7FFFFFFF;
  const std::uint64_t rest = a - whole * b;  // < b < 2^32, so rest·2^frac < 2^62
  const std::uint64_t v = (whole << frac) + ((rest << frac) + b / 2) / b;
  return v >= 0x7FFFFFFFu ? 0x7FFFFFFF : static_cast<std::int32_t>(v);
}

/// round(q·n/2^frac) for a non-negative Q(31 − frac).frac q and a 64-bit
/// count n < 2^62: a fraction of a tick count, without overflow.
constexpr std::uint64_t scale_count(std::int32_t q_raw, std::uint64_t n, int frac) noexcept {
  if (q_raw <= 0) return 0;
  const auto q = static_cast<std::uint64_t>(q_raw);
  const std::uint64_t hi = (n >> 32) * q;  // < 2^30·2^31
  const std::uint64_t lo = (n & 0xFFFFFFFFu) * q;
  return (hi << (32 - frac)) + ((lo + (std::uint64_t{1} << (frac - 1))) >> frac);
}

}  // namespace mrd::fw::idle_math
