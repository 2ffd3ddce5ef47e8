#pragma once
/// ODBDCO: over-driven, back-driven clipped-optimal current logic (thesis
/// §6.3, after Phillips & Spencer 2012), held to the coil's rating. It turns
/// the desired force F_d of the RILD filter into a current command for the
/// PWM drive, using the measured force F_m, the measured coil current i_m
/// and the damper velocity v (estimated from the measured stroke).
///
/// An MR damper is semi-active: its force always has the sign of its
/// velocity, F·v ≥ 0, and the current only sets how large it is. The law
/// chooses a target current in [0, I_c] and then drives the coil to it:
/// <pre>
///   direction s, with hysteresis (v_on > v_off ≥ 0):
///     s ← +1 if v > v_on,  −1 if v < −v_on
///     s ← 0  if s = +1 and v < v_off,  or s = −1 and v > −v_off
///
///   wish:
///     s = 0                         → KEEP, and after `rest_ticks` ticks with s = 0 → NONE
///     s·F_d ≤ 0                     → NONE   F_d opposes what the damper can give
///     e = s·F_d − s·F_m
///       e >  F_db                   → MORE   force must grow
///       e < −F_db                   → LESS   force must shrink
///       |e| ≤ F_db                  → KEEP
///
///   target I_t:
///     a move whose force has crossed F_d (I_t = I_c and e < 0, or I_t = 0 and e > 0)
///          → latched at clamp(i_m, 0, I_c) at once: the move ends at the present current
///     otherwise, only when `dwell_ticks` have passed since the last change:
///     MORE → I_c;  LESS, NONE → 0
///     KEEP with s ≠ 0 and |i_m − I_t| > I_band → latched at clamp(i_m, 0, I_c)  (the force is
///          where it should be: stay at the present current, read once)
///     KEEP otherwise, or s = 0 → unchanged
///   I_c = the coil I²t ceiling ≤ I_r (coil_i2t.hpp); a latched target is min(latched, I_c)
///
///   command:
///     I_t > I_band and i_m < I_t − I_band     → OVER-DRIVE  u = I_od   voltage forcing up
///     i_m > I_t + I_band                      → BACK-DRIVE  u = I_bd   voltage forcing down
///     otherwise                               → u = I_t     (OFF branch at 0 A, TARGET branch above)
///     a forcing branch of the opposite sign to the previous tick's is replaced by u = target for one tick
/// </pre>
/// Default parameters (ControllerConfig), and why:
/// - I_r = 2.5 A, the damper's rated current (Table 4.1's laws are fitted on
///   0–2.5 A): the only current the coil is held at;
/// - I_od = 10 A, I_bd = −10 A, the drive's command limit (±10 V at 1 V/A,
///   §3.2): only while the measured current is short of (above) the target,
///   so the coil's L·di/dt gets the drive's full voltage and the current
///   itself never settles beyond I_r;
/// - I_band = 0.1 A: 20× the current sensor's 5 mA noise and 5× a ±20 mA
///   bias, so neither noise nor bias starts forcing; the drive (slew
///   15–24 A/s, 15–24 mA per tick) crosses the band in 4–7 ticks;
/// - v_on = 6 mm/s, v_off = 3 mm/s: the LVDT (±0.2921 m, 16 bit → 8.9 µm,
///   2 µm noise) gives σ_x = √(2² + 8.9²/12) = 3.3 µm per sample; the
///   velocity estimator's noise gain is √(Σh²) = β√(2/(2−β)) = 0.180 at
///   β = 0.172 (30 Hz, 1 kHz), so σ_v = 0.18·3.3 µm/1 ms = 0.59 mm/s, and one
///   LVDT step moves the estimate by β·8.9 µm/1 ms = 1.5 mm/s. v_on is 10 σ_v
///   and 4 steps; v_off ends a direction once the motion has clearly
///   stopped. At 0.25 Hz and 75 mm/s velocity amplitude the velocity is
///   below 6 mm/s for 5 % of a cycle;
/// - F_db = 2 kN;
/// - dwell 30 ms: the drive needs 0.10–0.17 s to take the coil from 0 to
///   2.5 A (15–24 A/s), and the damper's field lags the current by ~0.7 s,
///   so a target held for less than ~30 ms changes nothing but heat and
///   wear; 30 ms bounds the target to 2 changes (a move and its end at the
///   crossing) per 30 ms, ≤ 67 changes/s (2.5–20 measured on the hardware
///   plant), while costing ≤ 30 ms of a 4 s structural period (2.7°);
/// - rest 1 s: a direction that stays unknown for 1 s means the building is
///   at rest; the target goes to 0 A. Before that the last target is kept
///   (a velocity reversal passes through the deadband in tens of ms).
/// Back-drive stops as soon as the coil current is within the band of the
/// target, because a negative coil current magnetizes the fluid like a
/// positive one (the Bingham laws depend on |i|). The measured current is
/// never fed back as a command tick by tick: it is read once when a target
/// is latched, and latched again only when the coil is more than I_band
/// away from the target, so a current-sensor bias below I_band cannot walk
/// the current; at rest (s = 0) nothing is latched at all.
///
/// Units: velocities in the controller's s_V m per tick, forces in its s_F N,
/// currents in its s_I A (numeric_formats.hpp; 1 in the float build, and
/// s_F = s_I = 1 for the thesis's damper in fixed point), so every level
/// above is the configured one divided by its scale.
///
/// Fixed point: forces Q19.12 s_F N, currents Q7.24 s_I A, velocity Q3.28
/// s_V m/tick. s·F_d − s·F_m saturates at ±524 288 s_F N; only its sign against
/// F_db matters, and saturation keeps the sign. The command is I_od, I_bd,
/// 0 or the target I_t ∈ [0, I_c] ⊂ [0, I_r], so it can never leave
/// [I_bd, I_od], whose ends fit Current by validate_config.

#include <cstdint>

#include "firmware/core/numeric_formats.hpp"

namespace mrd::fw {

enum class OdbdcoBranch : std::uint8_t {
  kOverDrive = 0,  ///< I_od: the measured current is short of the target
  kBackDrive = 1,  ///< I_bd: the measured current is above the target
  kOff = 2,        ///< 0 A: target 0 reached
  kTarget = 3,     ///< the target I_t > 0 (the ceiling I_c or a latched current)
};
inline constexpr int kOdbdcoBranches = 4;

template <class Policy>
struct OdbdcoParams {
  using Force = typename Formats<Policy>::Force;
  using Current = typename Formats<Policy>::Current;
  using Velocity = typename Formats<Policy>::Velocity;
  Current overdrive_a{};         ///< I_od
  Current backdrive_a{};         ///< I_bd (negative)
  Current band_a{};              ///< I_band
  Force deadband_n{};            ///< F_db
  Velocity velocity_on{};        ///< v_on · T, s_V m per tick
  Velocity velocity_off{};       ///< v_off · T, s_V m per tick
  std::uint32_t dwell_ticks = 0; ///< minimum ticks between target changes
  std::uint32_t rest_ticks = 0;  ///< ticks of unknown direction before the target goes to 0
};

template <class Policy>
struct OdbdcoDecision {
  typename Formats<Policy>::Current command_a{};
  OdbdcoBranch branch = OdbdcoBranch::kOff;
};

/// The law above; its state is the direction, the target, the dwell and
/// rest counters and the previous tick's forcing sign.
template <class Policy>
class Odbdco {
 public:
  using Force = typename Formats<Policy>::Force;
  using Current = typename Formats<Policy>::Current;
  using Velocity = typename Formats<Policy>::Velocity;

  /// Direction unknown, target 0 A, free to change at once.
  void reset() noexcept {
    direction_ = 0;
    target_ = Target::kZero;
    latched_a_ = Current{};
    since_change_ = 0xffffffffu;
    at_rest_ = 0;
    forcing_ = 0;
  }

  /// One tick. `velocity_per_tick` is the velocity estimate in s_V m per
  /// tick (VelocityEstimator); `ceiling_a` is I_c.
  OdbdcoDecision<Policy> step(const OdbdcoParams<Policy>& p, Force desired_n, Force measured_n, Current coil_a,
                              Velocity velocity_per_tick, Current ceiling_a) noexcept {
    // Direction with hysteresis.
    const Velocity v = velocity_per_tick;
    if (p.velocity_on < v) {
      direction_ = 1;
    } else if (v < -p.velocity_on) {
      direction_ = -1;
    } else if ((direction_ > 0 && v < p.velocity_off) || (direction_ < 0 && -p.velocity_off < v)) {
      direction_ = 0;
    }

    // Wish: +1 more force, −1 less force, −2 no force at all, 0 keep.
    int wish = 0;
    int error_sign = 0;  // sign of e = s·F_d − s·F_m
    if (direction_ != 0) {
      at_rest_ = 0;
      const bool neg = direction_ < 0;
      const Force achievable = signed_by(neg, desired_n);  // s·F_d
      if (!(Force{} < achievable)) {
        wish = -2;
      } else {
        const Force e = achievable - signed_by(neg, measured_n);
        error_sign = Force{} < e ? 1 : (e < Force{} ? -1 : 0);
        if (p.deadband_n < e) {
          wish = 1;
        } else if (e < -p.deadband_n) {
          wish = -1;
        }
      }
    } else if (at_rest_ < p.rest_ticks) {
      ++at_rest_;
    } else {
      wish = -2;
    }

    // Target, with the minimum dwell between changes.
    if (since_change_ != 0xffffffffu) ++since_change_;
    Current target = target_a(ceiling_a);
    const Current latch = num::clamp(coil_a, Current{}, ceiling_a);
    // A move whose force has crossed F_d (e changed sign) ends at the present
    // current, at any time: up (target I_c) and the force is now beyond F_d,
    // or down (target 0) and the force is now short of it.
    const bool crossed = (error_sign < 0 && target_ == Target::kCeiling && latch < ceiling_a - p.band_a) ||
                         (error_sign > 0 && target_ == Target::kZero && p.band_a < latch);
    if (crossed) {
      target_ = Target::kLatched;
      latched_a_ = latch;
      since_change_ = 0;
    } else if (since_change_ >= p.dwell_ticks) {
      const bool outside = coil_a < target - p.band_a || target + p.band_a < coil_a;
      Target next = target_;
      if (wish == -2 || wish == -1) {
        next = Target::kZero;
      } else if (wish == 1) {
        next = Target::kCeiling;
      } else if (direction_ != 0 && outside && !(latch == target)) {
        next = Target::kLatched;  // KEEP while moving: stay at the present current
        latched_a_ = latch;
      }
      if (next != target_ || next == Target::kLatched) {
        if (next != target_ || !(target == latched_a_)) since_change_ = 0;
        target_ = next;
      }
    }
    target = target_a(ceiling_a);

    // Command: force the coil towards the target, never straight from one
    // forcing direction to the other.
    OdbdcoDecision<Policy> d;
    int forcing = 0;
    if (p.band_a < target && coil_a < target - p.band_a) {
      forcing = 1;
    } else if (target + p.band_a < coil_a) {
      forcing = -1;
    }
    if (forcing != 0 && forcing == -forcing_) forcing = 0;
    forcing_ = forcing;
    if (forcing > 0) {
      d.branch = OdbdcoBranch::kOverDrive;
      d.command_a = p.overdrive_a;
    } else if (forcing < 0) {
      d.branch = OdbdcoBranch::kBackDrive;
      d.command_a = p.backdrive_a;
    } else {
      d.branch = Current{} < target ? OdbdcoBranch::kTarget : OdbdcoBranch::kOff;
      d.command_a = target;
    }
    return d;
  }

  /// −1, 0 (unknown) or +1.
  int direction() const noexcept { return direction_; }
  /// The target I_t for the ceiling `ceiling_a`.
  Current target_a(Current ceiling_a) const noexcept {
    switch (target_) {
      case Target::kCeiling: return ceiling_a;
      case Target::kLatched: return latched_a_ < ceiling_a ? latched_a_ : ceiling_a;
      case Target::kZero: break;
    }
    return Current{};
  }
  /// True when the target is the ceiling I_c.
  bool target_on() const noexcept { return target_ == Target::kCeiling; }
  /// True when the target is 0 A.
  bool target_off() const noexcept { return target_ == Target::kZero; }

 private:
  enum class Target : std::uint8_t { kZero, kCeiling, kLatched };
  int direction_ = 0;
  Target target_ = Target::kZero;
  Current latched_a_{};
  std::uint32_t since_change_ = 0xffffffffu;
  std::uint32_t at_rest_ = 0;
  int forcing_ = 0;
};

}  // namespace mrd::fw
