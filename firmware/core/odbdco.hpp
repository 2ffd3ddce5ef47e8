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
#include <type_traits>

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

/// One tick's command and the branch that gave it (per lane for lanes).
template <class Policy>
struct OdbdcoDecision {
  using Branch = std::conditional_t<LaneTypes<Policy>::kLanes == 1, OdbdcoBranch, typename LaneTypes<Policy>::Int>;
  typename Formats<Policy>::Current command_a{};
  Branch branch = num::splat<Branch>(OdbdcoBranch::kOff);
};

/// The law above; its state is the direction, the target, the dwell and
/// rest counters and the previous tick's forcing sign. Written with masks
/// (`m ? a : b`), so that one source steps one controller and N lanes.
template <class Policy>
class Odbdco {
 public:
  using Force = typename Formats<Policy>::Force;
  using Current = typename Formats<Policy>::Current;
  using Velocity = typename Formats<Policy>::Velocity;
  using Mask = typename LaneTypes<Policy>::Mask;
  using Count = typename LaneTypes<Policy>::Count;
  using Int = typename LaneTypes<Policy>::Int;
  using Branch = typename OdbdcoDecision<Policy>::Branch;

  /// Direction unknown, target 0 A, free to change at once (in the lanes of `m`).
  void reset(Mask m = num::all_set<Mask>()) noexcept {
    direction_ = num::select(m, Int{}, direction_);
    target_ = num::select(m, num::splat<Int>(kZero), target_);
    latched_a_ = num::select(m, Current{}, latched_a_);
    since_change_ = num::select(m, num::splat<Count>(kNever), since_change_);
    at_rest_ = num::select(m, Count{}, at_rest_);
    forcing_ = num::select(m, Int{}, forcing_);
  }

  /// One tick in the lanes of `m` (the others keep their state).
  /// `velocity_per_tick` is the velocity estimate in s_V m per tick
  /// (VelocityEstimator); `ceiling_a` is I_c.
  [[gnu::always_inline]] OdbdcoDecision<Policy> step(const OdbdcoParams<Policy>& p, Force desired_n, Force measured_n, Current coil_a,
                              Velocity velocity_per_tick, Current ceiling_a,
                              Mask m = num::all_set<Mask>()) noexcept {
    const Int zero{};
    const Int one = num::splat<Int>(1);
    // Each block of state changes runs where some lane needs it (`num::any`):
    // one controller takes the branch, lanes take it if any of them does and
    // pick per lane.
    // Direction with hysteresis.
    const Velocity v = velocity_per_tick;
    Int direction = direction_;
    const Mask up = p.velocity_on < v;
    const Mask down = !up && v < -p.velocity_on;
    if (num::any(up || down)) direction = (up ? one : (down ? -one : direction));
    const Mask stops =
        !up && !down && ((direction_ > 0 && v < p.velocity_off) || (direction_ < 0 && -p.velocity_off < v));
    if (num::any(stops)) direction = (stops ? zero : direction);

    // Wish: +1 more force, −1 less force, −2 no force at all, 0 keep.
    const Mask moving = direction != 0;
    Int wish = zero;
    Int error_sign = zero;  // sign of e = s·F_d − s·F_m
    Count at_rest = at_rest_;
    if (num::any(moving)) {
      const Mask neg = direction < 0;
      const Force achievable = signed_by(neg, desired_n);  // s·F_d
      const Mask can = moving && Force{} < achievable;
      wish = (moving ? num::splat<Int>(-2) : wish);
      if (num::any(can)) {
        const Force e = achievable - signed_by(neg, measured_n);
        error_sign = (can ? (Force{} < e ? one : (e < Force{} ? -one : zero)) : error_sign);
        wish = (can ? (p.deadband_n < e ? one : (e < -p.deadband_n ? -one : zero)) : wish);
      }
      at_rest = (moving ? Count{} : at_rest);
    }
    if (!num::all(moving)) {
      const Mask resting = !moving && at_rest_ < p.rest_ticks;
      at_rest = (resting ? at_rest_ + 1u : at_rest);
      wish = (!moving && !resting ? num::splat<Int>(-2) : wish);
    }

    // Target, with the minimum dwell between changes.
    Count since = (since_change_ != kNever ? since_change_ + 1u : since_change_);
    const Current target = target_a(ceiling_a);
    const Current latch = num::clamp(coil_a, Current{}, ceiling_a);
    Int target_state = target_;
    Current latched = latched_a_;
    // A move whose force has crossed F_d (e changed sign) ends at the present
    // current, at any time: up (target I_c) and the force is now beyond F_d,
    // or down (target 0) and the force is now short of it.
    const Mask crossed = (error_sign < 0 && target_ == kCeiling && latch < ceiling_a - p.band_a) ||
                         (error_sign > 0 && target_ == kZero && p.band_a < latch);
    if (num::any(crossed)) {
      target_state = (crossed ? num::splat<Int>(kLatched) : target_state);
      latched = (crossed ? latch : latched);
      since = (crossed ? Count{} : since);
    }
    const Mask free = !crossed && since >= p.dwell_ticks;
    if (num::any(free)) {
      const Mask outside = coil_a < target - p.band_a || target + p.band_a < coil_a;
      // KEEP while moving: stay at the present current.
      const Mask keep_latch = free && wish == 0 && moving && outside && !(latch == target);
      const Int next = (wish < 0 ? num::splat<Int>(kZero) : (wish == 1 ? num::splat<Int>(kCeiling) : (keep_latch ? num::splat<Int>(kLatched) : target_)));
      latched = (keep_latch ? latch : latched);
      const Mask restart = free && (next != target_ || (next == kLatched && !(target == latched)));
      since = (restart ? Count{} : since);
      target_state = (free ? next : target_state);
    }
    const Current target_now = target_a(ceiling_a, target_state, latched);

    // Command: force the coil towards the target, never straight from one
    // forcing direction to the other.
    const Int forcing_wanted =
        (p.band_a < target_now && coil_a < target_now - p.band_a ? one : (target_now + p.band_a < coil_a ? -one : zero));
    const Int forcing = (forcing_wanted != 0 && forcing_wanted == -forcing_ ? zero : forcing_wanted);

    OdbdcoDecision<Policy> d;
    d.command_a = (forcing > 0 ? p.overdrive_a : (forcing < 0 ? p.backdrive_a : target_now));
    d.branch = (forcing > 0 ? branch(OdbdcoBranch::kOverDrive) : (forcing < 0 ? branch(OdbdcoBranch::kBackDrive) : (Current{} < target_now ? branch(OdbdcoBranch::kTarget) : branch(OdbdcoBranch::kOff))));
    direction_ = num::select(m, direction, direction_);
    at_rest_ = num::select(m, at_rest, at_rest_);
    since_change_ = num::select(m, since, since_change_);
    target_ = num::select(m, target_state, target_);
    latched_a_ = num::select(m, latched, latched_a_);
    forcing_ = num::select(m, forcing, forcing_);
    return d;
  }

  /// −1, 0 (unknown) or +1.
  Int direction() const noexcept { return direction_; }
  /// The target I_t for the ceiling `ceiling_a`.
  Current target_a(Current ceiling_a) const noexcept { return target_a(ceiling_a, target_, latched_a_); }
  /// True when the target is the ceiling I_c.
  Mask target_on() const noexcept { return target_ == kCeiling; }
  /// True when the target is 0 A.
  Mask target_off() const noexcept { return target_ == kZero; }

 private:
  // The target's kind.
  static constexpr int kZero = 0;
  static constexpr int kCeiling = 1;
  static constexpr int kLatched = 2;
  static constexpr std::uint32_t kNever = 0xffffffffu;
  Int direction_{};
  Int target_{};
  Current latched_a_{};
  Count since_change_ = num::splat<Count>(kNever);
  Count at_rest_{};
  Int forcing_{};

  static constexpr Branch branch(OdbdcoBranch b) noexcept { return num::splat<Branch>(b); }

  static Current target_a(Current ceiling_a, Int kind, Current latched_a) noexcept {
    return kind == kCeiling ? ceiling_a : (kind == kLatched ? (latched_a < ceiling_a ? latched_a : ceiling_a) : Current{});
  }
};

}  // namespace mrd::fw
