#pragma once
/// Checks every tick's sensor values before any of them reaches a filter:
/// the same checks in the float and the fixed-point build, on the float
/// values of `control::ControllerInput`.
///
/// Per signal, the first of these that applies is the signal's fault:
///   1. flagged:      the sender marked it invalid (`InputFlags`);
///   2. NaN;
///   3. infinite;
///   4. out of range: |value| above the signal's physical limit;
///   5. stuck:        (stroke and force only) bit-identical for `stuck_ticks`
///                    consecutive ticks although the ground-acceleration
///                    sensor saw shaking (|a_g| ≥ threshold) during that run.
///                    A moving base always changes the float value of its
///                    stroke and of the damper force; at rest the values may
///                    repeat without a fault.
/// Pure, no heap, no exceptions; NaN and infinity are found from the bit
/// pattern, so `-ffast-math` cannot remove the checks.

#include <array>
#include <bit>
#include <cstdint>

#include "mrd/control/io.hpp"

namespace mrd::fw {

enum class InputSignal : std::uint8_t {
  kDisp = 0,          ///< damper stroke
  kForce = 1,         ///< load-cell force
  kGroundAccel = 2,   ///< ground acceleration
  kBaseAccel = 3,     ///< absolute base acceleration
  kCoilCurrent = 4,   ///< coil current measured by the drive
};
inline constexpr int kInputSignals = 5;

enum class InputFault : std::uint8_t {
  kNone = 0,
  kFlagged = 1,
  kNotANumber = 2,
  kInfinite = 3,
  kOutOfRange = 4,
  kStuck = 5,
};
inline constexpr int kInputFaultKinds = 6;  ///< including kNone

constexpr const char* input_fault_name(InputFault f) noexcept {
  switch (f) {
    case InputFault::kNone: return "none";
    case InputFault::kFlagged: return "flagged";
    case InputFault::kNotANumber: return "nan";
    case InputFault::kInfinite: return "infinite";
    case InputFault::kOutOfRange: return "out-of-range";
    case InputFault::kStuck: return "stuck";
  }
  return "unknown";
}

/// Classifies a float from its bits: kNone, kNotANumber or kInfinite.
constexpr InputFault classify_float(float v) noexcept {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
  if ((bits & 0x7f800000u) != 0x7f800000u) return InputFault::kNone;
  return (bits & 0x007fffffu) != 0u ? InputFault::kNotANumber : InputFault::kInfinite;
}

struct InputGuardLimits {
  float disp_limit_m = 0.30f;           ///< stroke ±292.1 mm (§3.1) plus margin
  float force_limit_n = 500.0e3f;       ///< 2.5× the damper's 200 kN
  float accel_limit_m_s2 = 50.0f;       ///< ≈ 5 g
  float coil_current_limit_a = 30.0f;   ///< the drive's peak current
  std::uint32_t stuck_ticks = 500;      ///< 0.5 s at 1 kHz
  float shaking_threshold_m_s2 = 0.1f;  ///< ≈ 0.01 g
};

class InputGuard {
 public:
  using Faults = std::array<InputFault, kInputSignals>;

  void init(const InputGuardLimits& limits) noexcept {
    limits_ = limits;
    reset();
  }

  void reset() noexcept {
    last_bits_ = {};
    same_run_ = {};
    have_last_ = {};
    ticks_since_shaking_ = kNever;
  }

  /// Checks one tick's input and returns each signal's fault.
  Faults check(const control::ControllerInput& in) noexcept {
    Faults f{};
    f[idx(InputSignal::kDisp)] = basic(in.damper_disp_m, in.flags.disp_valid, limits_.disp_limit_m);
    f[idx(InputSignal::kForce)] = basic(in.damper_force_n, in.flags.force_valid, limits_.force_limit_n);
    f[idx(InputSignal::kGroundAccel)] =
        basic(in.ground_accel_m_s2, in.flags.ground_accel_valid, limits_.accel_limit_m_s2);
    f[idx(InputSignal::kBaseAccel)] = basic(in.base_accel_m_s2, in.flags.base_accel_valid, limits_.accel_limit_m_s2);
    f[idx(InputSignal::kCoilCurrent)] = basic(in.coil_current_a, true, limits_.coil_current_limit_a);

    // Shaking seen by a valid ground-acceleration sensor.
    if (ticks_since_shaking_ < kNever) ++ticks_since_shaking_;
    if (f[idx(InputSignal::kGroundAccel)] == InputFault::kNone &&
        !(in.ground_accel_m_s2 < limits_.shaking_threshold_m_s2 &&
          -limits_.shaking_threshold_m_s2 < in.ground_accel_m_s2)) {
      ticks_since_shaking_ = 0;
    }
    stuck(InputSignal::kDisp, in.damper_disp_m, f);
    stuck(InputSignal::kForce, in.damper_force_n, f);
    return f;
  }

  static constexpr int idx(InputSignal s) noexcept { return static_cast<int>(s); }

 private:
  static constexpr std::uint32_t kNever = 0xffffffffu;
  InputGuardLimits limits_{};
  std::array<std::uint32_t, 2> last_bits_{};
  std::array<std::uint32_t, 2> same_run_{};
  std::array<bool, 2> have_last_{};
  std::uint32_t ticks_since_shaking_ = kNever;

  static constexpr InputFault basic(float v, bool flagged_valid, float limit) noexcept {
    if (!flagged_valid) return InputFault::kFlagged;
    const InputFault c = classify_float(v);
    if (c != InputFault::kNone) return c;
    if (!(v <= limit && -limit <= v)) return InputFault::kOutOfRange;
    return InputFault::kNone;
  }

  /// Stuck test for stroke (slot 0) and force (slot 1), only on values that
  /// passed the basic checks.
  void stuck(InputSignal s, float v, Faults& f) noexcept {
    const int slot = s == InputSignal::kDisp ? 0 : 1;
    if (f[idx(s)] != InputFault::kNone) {
      have_last_[slot] = false;
      same_run_[slot] = 0;
      return;
    }
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
    if (have_last_[slot] && bits == last_bits_[slot]) {
      if (same_run_[slot] < kNever) ++same_run_[slot];
    } else {
      same_run_[slot] = 0;
    }
    last_bits_[slot] = bits;
    have_last_[slot] = true;
    // same_run_ counts the repeats after the first sample: the value has been
    // constant for same_run_ + 1 ticks (stuck_ticks ≥ 2, checked at init).
    if (same_run_[slot] >= limits_.stuck_ticks - 1u && ticks_since_shaking_ <= same_run_[slot]) {
      f[idx(s)] = InputFault::kStuck;
    }
  }
};

}  // namespace mrd::fw
