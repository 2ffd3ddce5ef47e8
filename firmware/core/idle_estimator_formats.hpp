#pragma once
/// Number formats and arithmetic of the idle-time estimator, the mixing
/// scheduler and the mixing task, per numeric policy: the double reference
/// (fw::Float64Policy), single-precision float (num::Float32Policy) and
/// 32/64-bit fixed point (num::Fixed32Policy). The blocks are written once
/// against `IdleArith<Policy>`; only this file knows the representation.
///
/// In every build, time is a 64-bit count of control ticks (50 years of 1 ms
/// ticks is 1.58e12 < 2^41), the wall clock a 64-bit count of milliseconds,
/// and configured durations are converted to ticks once, at init().
///
/// Fixed point (num::Fixed32Policy). 32-bit values saturate, never wrap;
/// products and quotients form 64-bit intermediates and round once.
///
/// | role   | unit                 | format            | range              | resolution      | worst case it covers                         |
/// |--------|----------------------|-------------------|--------------------|-----------------|----------------------------------------------|
/// | Ratio  | 1 (SQ, PR, capacity) | Q1.30             | [−2, 2)            | 9.3e−10         | PR from 0.1 to 1, SQ at 0.8, capacity ≤ 1    |
/// | Coef   | 1 (c_PR, c_i, …)     | Q3.28             | [−8, 8)            | 3.7e−9          | c_initial = 7, a_rise = 5.474 (Table 5.6)    |
/// | Expo   | 1 (exp argument, ln) | Q5.26             | [−32, 32)          | 1.5e−8          | exp(−32) = 1.3e−14 < Ratio LSB: larger is 0  |
/// | Rate   | 1/m³ (c_PR/unit)     | Q13.18            | [−8192, 8192)      | 3.8e−6 /m³      | 5.474/1 L = 5474 /m³                         |
/// | Disp   | m                    | Q3.28             | [−8, 8) m          | 3.7e−9 m        | stroke ±0.292 m (as the control core)        |
/// | Area   | m²                   | Q0.31             | [−1, 1) m²         | 4.7e−10 m²      | flow area 0.01062 m²                         |
/// | Accel  | m/s²                 | Q7.24             | [−128, 128) m/s²   | 6.0e−8 m/s²     | accelerometers ±4 g; triggers 0.05 m/s²      |
/// | Volume | m³                   | int64 Q23.40      | [0, 8.4e6) m³      | 9.1e−13 m³      | see below                                    |
///
/// Volume: one 64-bit counter, no split needed. A 1 ms step at 1 µm/s moves
/// the damper 1 nm: 1e−9 m · 0.01062 m² = 1.1e−11 m³ = 12 LSB, counted
/// exactly; a decade of ambient motion (0.005 L a day: 0.018 m³) plus 50
/// years of earthquakes and mixing (< 100 m³) uses < 2^47 of 2^63. The
/// per-step increment |Δy|·A is the exact 64-bit product of the Disp and
/// Area raw values rounded once to 2^−40 m³ (≤ 4.6e−13 m³ a step, unbiased).
/// The float build keeps the same 64-bit counter (a float sum would drop
/// increments below 6e−8 of the total).
///
/// Float (num::Float32Policy): every role is `float` except Volume (the
/// 64-bit counter above) and time (ticks). exp and log are expf/logf.

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "firmware/core/idle_estimator_math.hpp"
#include "firmware/core/numeric_formats.hpp"

namespace mrd::fw {

/// Displaced volume in units of 2^−40 m³ (the Volume row above).
struct VolumeCount {
  std::int64_t raw = 0;
  static constexpr int kFracBits = 40;
  friend constexpr bool operator==(VolumeCount a, VolumeCount b) noexcept { return a.raw == b.raw; }
  friend constexpr auto operator<=>(VolumeCount a, VolumeCount b) noexcept { return a.raw <=> b.raw; }
};
inline constexpr double kVolumeCountM3 = 1.0 / 1099511627776.0;  ///< one count, m³ (2^−40)

/// The wall-clock field of an input: seconds as double in the reference
/// build, whole milliseconds in the float and fixed builds.
struct RtcSeconds {
  double rtc_s = 0.0;  ///< wall clock (e.g. Unix time), s
};
struct RtcMillis {
  std::int64_t rtc_ms = 0;  ///< wall clock (e.g. Unix time), ms
};

template <class Policy>
struct IdleArith;

/// double and float: plain arithmetic in T; Volume is double m³ in the
/// reference build and the 64-bit counter in the float build.
template <class T, class VolumeT, class RtcField>
struct FloatingIdleArith {
  using Sample = T;
  using Ratio = T;
  using Coef = T;
  using Expo = T;
  using Rate = T;
  using Disp = T;
  using Area = T;
  using Accel = T;
  using Volume = VolumeT;
  using Rtc = std::conditional_t<std::is_same_v<RtcField, RtcSeconds>, double, std::int64_t>;
  using RtcInput = RtcField;
  static constexpr bool kCountedVolume = !std::is_same_v<VolumeT, T>;

  template <class X>
  static X from(double v) noexcept {
    return static_cast<X>(v);
  }
  static constexpr T zero() noexcept { return T(0); }
  static constexpr T one() noexcept { return T(1); }
  static T exp_neg(Expo x) noexcept { return std::exp(-x); }
  /// ln(n/d), n ≥ d > 0; 0 otherwise.
  static Expo ln_quotient(Ratio n, Ratio d) noexcept { return d > T(0) && n > d ? std::log(n / d) : T(0); }
  static Ratio sq_of(std::uint64_t tau, std::uint64_t t_max) noexcept {
    return tau >= t_max ? T(1) : static_cast<T>(tau) / static_cast<T>(t_max);
  }
  static Expo times(Coef c, Ratio r) noexcept { return c * r; }
  static Ratio mul(Ratio a, Ratio b) noexcept { return a * b; }
  static Coef mul_coef(Coef a, Ratio b) noexcept { return a * b; }
  static Rate rate_of(Coef c, Rate per_unit) noexcept { return c * per_unit; }
  /// min(L/c, 1) for L ≥ 0, c > 0.
  static Ratio div_clamp01(Expo l, Coef c) noexcept {
    const T q = l / c;
    return q < T(1) ? q : T(1);
  }
  static std::uint64_t scale_ticks(Ratio q, std::uint64_t n) noexcept {
    if (!(q > T(0))) return 0;
    if (q >= T(1)) return n;
    return static_cast<std::uint64_t>(q * static_cast<T>(n) + T(0.5));
  }
  static std::int64_t to_sample_ticks(std::uint64_t n) noexcept { return static_cast<std::int64_t>(n); }
  static Sample seconds(std::uint64_t ticks, Sample period_s) noexcept { return static_cast<T>(ticks) * period_s; }
  static Sample to_sample(T v) noexcept { return v; }

  // Volume.
  static Volume vol_zero() noexcept { return Volume{}; }
  static Volume vol_add(Volume a, Volume b) noexcept {
    if constexpr (kCountedVolume) {
      return Volume{a.raw + b.raw};
    } else {
      return a + b;
    }
  }
  /// max(a − b, 0).
  static Volume vol_sub0(Volume a, Volume b) noexcept {
    if constexpr (kCountedVolume) {
      return Volume{a.raw > b.raw ? a.raw - b.raw : 0};
    } else {
      return a > b ? a - b : T(0);
    }
  }
  static bool vol_positive(Volume v) noexcept {
    if constexpr (kCountedVolume) {
      return v.raw > 0;
    } else {
      return v > T(0);
    }
  }
  static Volume vol_of_stroke(Disp dy_abs, Area area) noexcept {
    if constexpr (kCountedVolume) {
      return Volume{static_cast<std::int64_t>(dy_abs * area * T(1099511627776.0) + T(0.5))};
    } else {
      return dy_abs * area;
    }
  }
  static Volume vol_scale(Volume v, Ratio f) noexcept {
    if constexpr (kCountedVolume) {
      return Volume{static_cast<std::int64_t>(static_cast<T>(v.raw) * f)};
    } else {
      return v * f;
    }
  }
  static Volume vol_times(Volume v, std::uint32_t n) noexcept {
    if constexpr (kCountedVolume) {
      return Volume{v.raw * static_cast<std::int64_t>(n)};
    } else {
      return v * static_cast<T>(n);
    }
  }
  /// ⌈needed/per⌉ (0 for needed ≤ 0), saturated at `limit`.
  static std::uint32_t cycles_for(Volume needed, Volume per, std::uint32_t limit) noexcept {
    if constexpr (kCountedVolume) {
      if (needed.raw <= 0) return 0;
      const std::int64_t n = (needed.raw + per.raw - 1) / per.raw;
      return n > static_cast<std::int64_t>(limit) ? limit : static_cast<std::uint32_t>(n);
    } else {
      if (!(needed > T(0))) return 0;
      const T n = std::ceil(needed / per);
      return n > static_cast<T>(limit) ? limit : static_cast<std::uint32_t>(n);
    }
  }
  /// Eq. 5.9's exponent c·V/unit = rate·V.
  static Expo expo_of(Rate rate, Volume v) noexcept {
    if constexpr (kCountedVolume) {
      return rate * (static_cast<T>(v.raw) * T(9.094947017729282e-13));
    } else {
      return rate * v;
    }
  }
  /// The volume whose exponent is `l`: l/rate (rate > 0).
  static Volume vol_of_expo(Expo l, Rate rate) noexcept {
    if constexpr (kCountedVolume) {
      return Volume{static_cast<std::int64_t>(l / rate * T(1099511627776.0))};
    } else {
      return l / rate;
    }
  }
  static Sample vol_to_sample(Volume v) noexcept {
    if constexpr (kCountedVolume) {
      return static_cast<T>(v.raw) * T(9.094947017729282e-13);
    } else {
      return v;
    }
  }
  static std::int64_t vol_to_counts(Volume v) noexcept {
    if constexpr (kCountedVolume) {
      return v.raw;
    } else {
      return static_cast<std::int64_t>(std::llround(v * 1099511627776.0));
    }
  }
  static Volume vol_from_counts(std::int64_t counts) noexcept {
    if constexpr (kCountedVolume) {
      return Volume{counts};
    } else {
      return static_cast<T>(counts) * kVolumeCountM3;
    }
  }
  static double vol_to_double(Volume v) noexcept {
    if constexpr (kCountedVolume) {
      return static_cast<double>(v.raw) * kVolumeCountM3;
    } else {
      return static_cast<double>(v);
    }
  }
  static Volume vol_from_double(double m3) noexcept {
    if constexpr (kCountedVolume) {
      return Volume{m3 > 0.0 ? static_cast<std::int64_t>(m3 / kVolumeCountM3 + 0.5) : 0};
    } else {
      return static_cast<T>(m3);
    }
  }

  // Boundary values.
  static Disp disp_of(Sample x) noexcept { return x; }
  static bool sample_ok(Sample x) noexcept { return x == x && x - x == T(0); }  // finite
  static Accel accel_of(Sample a) noexcept { return a; }
  static T abs(T v) noexcept { return v < T(0) ? -v : v; }
  static double to_double(T v) noexcept { return static_cast<double>(v); }

  /// Wall-clock reading as milliseconds; false when not finite.
  static bool rtc_ms_of(const RtcField& in, std::int64_t& ms) noexcept {
    if constexpr (std::is_same_v<RtcField, RtcSeconds>) {
      if (!(std::fabs(in.rtc_s) < 9.0e15)) return false;  // not finite, or beyond int64 ms
      ms = std::llround(in.rtc_s * 1000.0);
      return true;
    } else {
      ms = in.rtc_ms;
      return true;
    }
  }
  static bool rtc_ms_of(Rtc rtc, std::int64_t& ms) noexcept {
    RtcField f;
    if constexpr (std::is_same_v<RtcField, RtcSeconds>) {
      f.rtc_s = rtc;
    } else {
      f.rtc_ms = rtc;
    }
    return rtc_ms_of(f, ms);
  }
};

template <>
struct IdleArith<Float64Policy> : FloatingIdleArith<double, double, RtcSeconds> {};
template <>
struct IdleArith<num::Float32Policy> : FloatingIdleArith<float, VolumeCount, RtcMillis> {};

/// Fixed point: the formats of the table above.
template <>
struct IdleArith<num::Fixed32Policy> {
  using Sample = float;
  using Ratio = num::Fixed<1, 30>;
  using Coef = num::Fixed<3, 28>;
  using Expo = num::Fixed<5, 26>;
  using Rate = num::Fixed<13, 18>;
  using Disp = num::Fixed<3, 28>;
  using Area = num::Fixed<0, 31>;
  using Accel = num::Fixed<7, 24>;
  using Volume = VolumeCount;
  using Rtc = std::int64_t;
  using RtcInput = RtcMillis;

  template <class X>
  static X from(double v) noexcept {
    return num::from_double<X>(v);
  }
  static constexpr Ratio zero() noexcept { return Ratio{}; }
  static constexpr Ratio one() noexcept { return Ratio::from_raw(1 << 30); }
  static Ratio exp_neg(Expo x) noexcept { return Ratio::from_raw(idle_math::exp_neg_q26(x.raw())); }
  static Expo ln_quotient(Ratio n, Ratio d) noexcept {
    return Expo::from_raw(idle_math::ln_quotient_q26(n.raw(), d.raw()));
  }
  static Ratio sq_of(std::uint64_t tau, std::uint64_t t_max) noexcept {
    return tau >= t_max ? one() : Ratio::from_raw(idle_math::ratio_q(tau, t_max, 30));
  }
  static Expo times(Coef c, Ratio r) noexcept { return num::mul<Expo>(c, r); }
  static Ratio mul(Ratio a, Ratio b) noexcept { return a * b; }
  static Coef mul_coef(Coef a, Ratio b) noexcept { return num::mul<Coef>(a, b); }
  static Rate rate_of(Coef c, Rate per_unit) noexcept { return num::mul<Rate>(c, per_unit); }
  static Ratio div_clamp01(Expo l, Coef c) noexcept {
    if (l.raw() <= 0) return zero();
    if (c.raw() <= 0) return one();
    // (l·2^−26)/(c·2^−28) in Q30: l·2^32/c.
    const std::int64_t q = (std::int64_t{l.raw()} << 32) / c.raw();
    return q >= (std::int64_t{1} << 30) ? one() : Ratio::from_raw(static_cast<std::int32_t>(q));
  }
  static std::uint64_t scale_ticks(Ratio q, std::uint64_t n) noexcept {
    if (q.raw() <= 0) return 0;
    if (q.raw() >= (1 << 30)) return n;
    return idle_math::scale_count(q.raw(), n, 30);
  }
  static Sample seconds(std::uint64_t ticks, Sample period_s) noexcept { return static_cast<float>(ticks) * period_s; }
  static Sample to_sample(Ratio v) noexcept { return num::to_float(v); }

  // Volume.
  static Volume vol_zero() noexcept { return Volume{}; }
  static Volume vol_add(Volume a, Volume b) noexcept { return Volume{a.raw + b.raw}; }
  static Volume vol_sub0(Volume a, Volume b) noexcept { return Volume{a.raw > b.raw ? a.raw - b.raw : 0}; }
  static bool vol_positive(Volume v) noexcept { return v.raw > 0; }
  /// |Δy|·A: (2^−28 m)·(2^−31 m²) = 2^−59 m³, rounded to 2^−40 m³.
  static Volume vol_of_stroke(Disp dy_abs, Area area) noexcept {
    return Volume{idle_math::shift_round(std::int64_t{dy_abs.raw()} * area.raw(), 19)};
  }
  /// v·f for 0 ≤ f < 2 (Q1.30), split so that the product cannot overflow.
  static Volume vol_scale(Volume v, Ratio f) noexcept {
    if (v.raw <= 0 || f.raw() <= 0) return Volume{};
    return Volume{static_cast<std::int64_t>(idle_math::scale_count(f.raw(), static_cast<std::uint64_t>(v.raw), 30))};
  }
  static Volume vol_times(Volume v, std::uint32_t n) noexcept { return Volume{v.raw * static_cast<std::int64_t>(n)}; }
  static std::uint32_t cycles_for(Volume needed, Volume per, std::uint32_t limit) noexcept {
    if (needed.raw <= 0) return 0;
    const std::int64_t n = (needed.raw + per.raw - 1) / per.raw;
    return n > static_cast<std::int64_t>(limit) ? limit : static_cast<std::uint32_t>(n);
  }
  /// rate·V: (2^−18 /m³)·(2^−40 m³) = 2^−58 → Q5.26 (÷2^32), saturated at 32.
  static Expo expo_of(Rate rate, Volume v) noexcept {
    if (rate.raw() <= 0 || v.raw <= 0) return Expo{};
    const auto r = static_cast<std::uint64_t>(rate.raw());
    const auto u = static_cast<std::uint64_t>(v.raw);
    const std::uint64_t hi = r * (u >> 32);  // already in 2^−26
    if (hi >= 0x7FFFFFFFu) return Expo::max();
    const std::uint64_t x = hi + ((r * (u & 0xFFFFFFFFu) + (std::uint64_t{1} << 31)) >> 32);
    return x >= 0x7FFFFFFFu ? Expo::max() : Expo::from_raw(static_cast<std::int32_t>(x));
  }
  /// l/rate in 2^−40 m³: (l·2^−26)/(rate·2^−18)·2^40 = l·2^32/rate.
  static Volume vol_of_expo(Expo l, Rate rate) noexcept {
    if (l.raw() <= 0 || rate.raw() <= 0) return Volume{};
    return Volume{(std::int64_t{l.raw()} << 32) / rate.raw()};
  }
  static Sample vol_to_sample(Volume v) noexcept { return static_cast<float>(v.raw) * 9.094947e-13f; }
  static std::int64_t vol_to_counts(Volume v) noexcept { return v.raw; }
  static Volume vol_from_counts(std::int64_t counts) noexcept { return Volume{counts}; }
  static double vol_to_double(Volume v) noexcept { return static_cast<double>(v.raw) * kVolumeCountM3; }
  static Volume vol_from_double(double m3) noexcept {
    return Volume{m3 > 0.0 ? static_cast<std::int64_t>(m3 / kVolumeCountM3 + 0.5) : 0};
  }

  // Boundary values (float samples, converted without double arithmetic).
  static Disp disp_of(Sample x) noexcept { return num::from_float<Disp>(x); }
  static bool sample_ok(Sample x) noexcept { return x == x && x - x == 0.0f; }
  static Accel accel_of(Sample a) noexcept { return num::from_float<Accel>(a); }
  template <class X>
  static X abs(X v) noexcept {
    return v < X{} ? -v : v;
  }
  template <class X>
  static double to_double(X v) noexcept {
    return v.to_double();
  }
  static bool rtc_ms_of(const RtcMillis& in, std::int64_t& ms) noexcept {
    ms = in.rtc_ms;
    return true;
  }
  static bool rtc_ms_of(Rtc rtc, std::int64_t& ms) noexcept {
    ms = rtc;
    return true;
  }
};

/// The number of ticks of `duration_s` for a `≥` comparison (ceil; a value
/// within 1e−6 tick of a whole number counts as that number).
inline std::uint64_t ticks_at_least(double duration_s, double period_s) noexcept {
  const double n = duration_s / period_s;
  if (!(n > 0.0)) return 0;
  const double r = std::round(n);
  return static_cast<std::uint64_t>(std::fabs(n - r) <= 1e-6 ? r : std::ceil(n));
}
/// The number of ticks of `duration_s` for a `>` comparison (floor, same rule).
inline std::uint64_t ticks_within(double duration_s, double period_s) noexcept {
  const double n = duration_s / period_s;
  if (!(n > 0.0)) return 0;
  const double r = std::round(n);
  return static_cast<std::uint64_t>(std::fabs(n - r) <= 1e-6 ? r : std::floor(n));
}

}  // namespace mrd::fw
