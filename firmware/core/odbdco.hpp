#pragma once
/// ODBDCO: over-driven, back-driven clipped-optimal current logic (thesis
/// §6.3, after Phillips & Spencer 2012). It turns the desired force F_d of
/// the RILD filter into a current command for the PWM drive, using the
/// measured force F_m, the measured coil current i_m and the sign of the
/// damper velocity v (estimated from the measured stroke).
///
/// An MR damper is semi-active: its force always has the sign of its
/// velocity, F·v ≥ 0, and the current only sets how large it is. So:
/// <pre>
///   s = +1 if v > v_db,  −1 if v < −v_db,  0 otherwise          direction of motion
///
///   s = 0                      → HOLD                           direction unknown
///   s·F_d ≤ 0                  → RELEASE                        F_d opposes what the damper can give
///   e = s·F_d − s·F_m
///     e >  F_db                → OVER-DRIVE                     force must grow
///     e < −F_db                → RELEASE                        force must shrink
///     |e| ≤ F_db               → HOLD
///
///   OVER-DRIVE: u = I_od        while i_m < I_ceil, else u = I_ceil
///   RELEASE:    u = I_bd (< 0)  while i_m > I_rel   (back-drive: pull the coil current down fast)
///               u = 0           once  i_m ≤ I_rel   (no current)
///   HOLD:       u = clamp(i_m, 0, I_ceil)           (keep the present current)
/// </pre>
/// Default parameters (ControllerConfig): I_od = 10 A, the drive's command
/// limit (±10 V at 1 V/A, §3.2), 4× the nominal 2.5 A, well inside the drive's
/// 15 A continuous rating; I_ceil = 10 A; I_bd = −10 A; I_rel = 0.05 A;
/// F_db = 2 kN; v_db = 1 mm/s. Back-drive stops as soon as the coil current
/// has fallen, because a negative coil current magnetizes the fluid like a
/// positive one (the Bingham laws depend on |i|).
///
/// Fixed point: forces Q19.12 N, currents Q7.24 A, velocity Q3.28 m/tick.
/// s·F_d − s·F_m saturates at ±524 kN; only its sign against F_db matters,
/// and saturation keeps the sign. The command is one of the constants I_od,
/// I_ceil, I_bd, 0 or i_m clamped to [0, I_ceil], so it can never leave
/// [I_bd, I_od].

#include <cstdint>

#include "firmware/core/numeric_formats.hpp"

namespace mrd::fw {

enum class OdbdcoBranch : std::uint8_t {
  kOverDrive = 0,  ///< I_od (or I_ceil once the coil has reached it)
  kBackDrive = 1,  ///< I_bd: release with the coil current still above I_rel
  kOff = 2,        ///< 0 A: release with the coil current already down
  kHold = 3,       ///< the measured coil current, clamped to [0, I_ceil]
};
inline constexpr int kOdbdcoBranches = 4;

template <class Policy>
struct OdbdcoParams {
  using Force = typename Formats<Policy>::Force;
  using Current = typename Formats<Policy>::Current;
  using Disp = typename Formats<Policy>::Disp;
  Current overdrive_a{};       ///< I_od
  Current ceiling_a{};         ///< I_ceil
  Current backdrive_a{};       ///< I_bd (negative)
  Current release_a{};         ///< I_rel
  Force deadband_n{};          ///< F_db
  Disp velocity_deadband_m{};  ///< v_db · T, m per tick
};

template <class Policy>
struct OdbdcoDecision {
  typename Formats<Policy>::Current command_a{};
  OdbdcoBranch branch = OdbdcoBranch::kOff;
};

/// The law above. `velocity_per_tick_m` is the velocity estimate in m per
/// tick (VelocityEstimator).
template <class Policy>
constexpr OdbdcoDecision<Policy> odbdco(const OdbdcoParams<Policy>& p, typename Formats<Policy>::Force desired_n,
                                        typename Formats<Policy>::Force measured_n,
                                        typename Formats<Policy>::Current coil_a,
                                        typename Formats<Policy>::Disp velocity_per_tick_m) noexcept {
  using Force = typename Formats<Policy>::Force;
  using Current = typename Formats<Policy>::Current;
  OdbdcoDecision<Policy> d;

  const bool moving_up = p.velocity_deadband_m < velocity_per_tick_m;
  const bool moving_down = velocity_per_tick_m < -p.velocity_deadband_m;
  enum class Want : std::uint8_t { kMore, kLess, kSame } want = Want::kSame;
  if (moving_up || moving_down) {
    const bool neg = moving_down;
    const Force achievable = signed_by(neg, desired_n);  // s·F_d
    if (!(Force{} < achievable)) {
      want = Want::kLess;  // F_d opposes the damper's force: no current
    } else {
      const Force e = achievable - signed_by(neg, measured_n);
      if (p.deadband_n < e) {
        want = Want::kMore;
      } else if (e < -p.deadband_n) {
        want = Want::kLess;
      }
    }
  }

  switch (want) {
    case Want::kMore:
      d.branch = OdbdcoBranch::kOverDrive;
      d.command_a = coil_a < p.ceiling_a ? p.overdrive_a : p.ceiling_a;
      break;
    case Want::kLess:
      if (p.release_a < coil_a) {
        d.branch = OdbdcoBranch::kBackDrive;
        d.command_a = p.backdrive_a;
      } else {
        d.branch = OdbdcoBranch::kOff;
        d.command_a = Current{};
      }
      break;
    case Want::kSame:
      d.branch = OdbdcoBranch::kHold;
      d.command_a = num::clamp(coil_a, Current{}, p.ceiling_a);
      break;
  }
  return d;
}

}  // namespace mrd::fw
