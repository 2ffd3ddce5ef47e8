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
#include <initializer_list>
#include <type_traits>

#include "firmware/core/numeric_formats.hpp"
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

/// One tick's input to N controllers side by side (LanePolicy<N>, lane set `Set`): each
/// field of control::ControllerInput, one lane per controller; flags are
/// masks.
template <class Set>
struct LaneControllerInput {
  typename Set::Tick tick{};
  typename Set::Sample damper_disp_m{};
  typename Set::Sample damper_force_n{};
  typename Set::Sample ground_accel_m_s2{};
  typename Set::Sample base_accel_m_s2{};
  typename Set::Sample coil_current_a{};
  struct Flags {
    typename Set::Mask disp_valid = num::all_set<typename Set::Mask>();
    typename Set::Mask force_valid = num::all_set<typename Set::Mask>();
    typename Set::Mask ground_accel_valid = num::all_set<typename Set::Mask>();
    typename Set::Mask base_accel_valid = num::all_set<typename Set::Mask>();
    typename Set::Mask drive_fault{};
  } flags{};
};

/// One tick's output of N controllers side by side.
template <class Set>
struct LaneControllerOutput {
  typename Set::Sample current_command_a{};
  typename Set::Mask drive_enable = num::all_set<typename Set::Mask>();
  typename Set::Sample desired_force_n{};
};

/// The input and output types for a lane set (one lane:
/// control::ControllerInput and control::ControllerOutput).
template <class Set>
struct ControlIo {
  using Input = LaneControllerInput<Set>;
  using Output = LaneControllerOutput<Set>;
};
template <>
struct ControlIo<LaneSet<1>> {
  using Input = control::ControllerInput;
  using Output = control::ControllerOutput;
};

/// The guard for a lane set (`InputGuard` for one controller); the checks
/// are written with masks, one source for both.
template <class Set>
class BasicInputGuard {
 public:
  static constexpr int N = Set::kLanes;
  using Mask = typename Set::Mask;
  using Count = typename Set::Count;
  using Sample = typename Set::Sample;
  using Bits = typename Set::Bits;
  /// A signal's fault: InputFault, or its code per lane.
  using Fault = std::conditional_t<N == 1, InputFault, typename Set::Int>;
  using Faults = std::array<Fault, kInputSignals>;
  using Input = typename ControlIo<Set>::Input;

  void init(const InputGuardLimits& limits) noexcept {
    limits_ = limits;
    // An infinite limit as the largest float: |v| ≤ limit (basic()) then
    // still leaves ±∞ outside, to be named infinite, as every finite v is inside.
    for (float* l : {&limits_.disp_limit_m, &limits_.force_limit_n, &limits_.accel_limit_m_s2,
                     &limits_.coil_current_limit_a}) {
      if (*l > kLargestFloat) *l = kLargestFloat;
    }
    reset();
  }

  void reset(Mask m = num::all_set<Mask>()) noexcept {
    for (int k = 0; k < 2; ++k) {
      last_bits_[k] = num::select(m, Bits{}, last_bits_[k]);
      same_run_[k] = num::select(m, Count{}, same_run_[k]);
      have_last_[k] = num::select(m, Mask{}, have_last_[k]);
    }
    ticks_since_shaking_ = num::select(m, num::splat<Count>(kNever), ticks_since_shaking_);
  }

  /// Checks one tick's input and returns each signal's fault; `clean` is
  /// set when no signal of any lane has one (every fault kNone).
  Faults check(const Input& in, bool& clean) noexcept {
    Faults f{};
    // Flags and the basic checks at once, without a branch between them (&,
    // not &&: the scalar build's masks are bools); each signal's fault only
    // when some lane has one.
    const Mask disp_inside = inside(in.damper_disp_m, limits_.disp_limit_m);
    const Mask force_inside = inside(in.damper_force_n, limits_.force_limit_n);
    const Mask ground_inside = inside(in.ground_accel_m_s2, limits_.accel_limit_m_s2);
    const Mask base_inside = inside(in.base_accel_m_s2, limits_.accel_limit_m_s2);
    const Mask current_inside = inside(in.coil_current_a, limits_.coil_current_limit_a);
    const bool basic_clean =
        num::all(in.flags.disp_valid & in.flags.force_valid & in.flags.ground_accel_valid &
                 in.flags.base_accel_valid & disp_inside & force_inside & ground_inside & base_inside &
                 current_inside);
    if (!basic_clean) [[unlikely]] {
      f[idx(InputSignal::kDisp)] = basic(in.damper_disp_m, in.flags.disp_valid, limits_.disp_limit_m);
      f[idx(InputSignal::kForce)] = basic(in.damper_force_n, in.flags.force_valid, limits_.force_limit_n);
      f[idx(InputSignal::kGroundAccel)] =
          basic(in.ground_accel_m_s2, in.flags.ground_accel_valid, limits_.accel_limit_m_s2);
      f[idx(InputSignal::kBaseAccel)] =
          basic(in.base_accel_m_s2, in.flags.base_accel_valid, limits_.accel_limit_m_s2);
      f[idx(InputSignal::kCoilCurrent)] =
          basic(in.coil_current_a, num::all_set<Mask>(), limits_.coil_current_limit_a);
    }

    // Shaking seen by a valid ground-acceleration sensor.
    const Count t = ticks_since_shaking_;
    const Mask shaking = f[idx(InputSignal::kGroundAccel)] == fault(InputFault::kNone) &&
                         !(in.ground_accel_m_s2 < limits_.shaking_threshold_m_s2 &&
                           -limits_.shaking_threshold_m_s2 < in.ground_accel_m_s2);
    ticks_since_shaking_ = num::select(shaking, Count{}, num::select(t < kNever, t + 1u, t));
    const Mask disp_stuck = stuck(0, in.damper_disp_m, f[idx(InputSignal::kDisp)]);
    const Mask force_stuck = stuck(1, in.damper_force_n, f[idx(InputSignal::kForce)]);
    clean = basic_clean && !num::any(disp_stuck | force_stuck);
    return f;
  }
  /// check() when the caller does not need to know whether the tick was clean.
  Faults check(const Input& in) noexcept {
    bool clean = false;
    return check(in, clean);
  }

  static constexpr int idx(InputSignal s) noexcept { return static_cast<int>(s); }
  /// The fault `k` as a Fault (every lane `k`).
  static constexpr Fault fault(InputFault k) noexcept { return num::splat<Fault>(k); }

 private:
  static constexpr std::uint32_t kNever = 0xffffffffu;
  static constexpr float kLargestFloat = 3.40282347e38f;
  InputGuardLimits limits_{};
  std::array<Bits, 2> last_bits_{};
  std::array<Count, 2> same_run_{};
  std::array<Mask, 2> have_last_{};
  Count ticks_since_shaking_ = num::splat<Count>(kNever);

  /// |v| ≤ limit, false for NaN: the same as v ≤ limit && −limit ≤ v for
  /// every v and limit (the sign bit cleared is |v|, NaN stays NaN); ±∞,
  /// whose fault basic() names, is outside since limit is finite (init()).
  static constexpr Mask inside(Sample v, float limit) noexcept {
    return __builtin_bit_cast(Sample, __builtin_bit_cast(Bits, v) & 0x7fffffffu) <= limit;
  }

  static constexpr Fault basic(Sample v, Mask flagged_valid, float limit) noexcept {
    const Bits bits = __builtin_bit_cast(Bits, v);
    const Mask inside = BasicInputGuard::inside(v, limit);
    Fault f = fault(InputFault::kNone);
    if (!num::all(inside)) [[unlikely]] {
      const Mask special = (bits & 0x7f800000u) == 0x7f800000u;  // NaN or infinite (classify_float)
      f = num::select(inside, f, fault(InputFault::kOutOfRange));
      f = num::select(special,
                      num::select((bits & 0x007fffffu) != 0u, fault(InputFault::kNotANumber),
                                  fault(InputFault::kInfinite)),
                      f);
    }
    if (!num::all(flagged_valid)) f = num::select(flagged_valid, f, fault(InputFault::kFlagged));
    return f;
  }

  /// Stuck test for stroke (slot 0) and force (slot 1), only on values that
  /// passed the basic checks; returns where it set the fault.
  Mask stuck(int slot, Sample v, Fault& f) noexcept {
    const Mask bad = f != fault(InputFault::kNone);
    const Bits bits = __builtin_bit_cast(Bits, v);
    const Count run = same_run_[slot];
    const Mask same = have_last_[slot] && bits == last_bits_[slot];
    same_run_[slot] = num::select(bad || !same, Count{}, num::select(run < kNever, run + 1u, run));
    last_bits_[slot] = num::select(bad, last_bits_[slot], bits);
    have_last_[slot] = !bad;
    // same_run_ counts the repeats after the first sample: the value has been
    // constant for same_run_ + 1 ticks (stuck_ticks ≥ 2, checked at init).
    const Mask stuck_now = !bad && same_run_[slot] >= limits_.stuck_ticks - 1u &&
                           ticks_since_shaking_ <= same_run_[slot];
    f = num::select(stuck_now, fault(InputFault::kStuck), f);
    return stuck_now;
  }
};

using InputGuard = BasicInputGuard<LaneSet<1>>;

}  // namespace mrd::fw
