#pragma once
/// Coil I²t: a first-order estimate of the coil's heating from the measured
/// coil current, and the steady current ceiling it allows.
///
/// The coil is one thermal mass behind one thermal resistance (R_th, τ):
/// its temperature rise is θ = R_th·R·m, where m is the coil current's
/// mean square through a first-order low-pass of time constant τ. The
/// rating is the rise at the rated current I_r held continuously,
/// θ_r = R_th·R·I_r², so the estimate needs neither R nor R_th, only τ:
/// <pre>
///   every N = 16 ticks:  m ← m + α (mean of i² over the N ticks − m),   α = 1 − exp(−N T / τ)
///   θ/θ_r = m / I_r²
///   ceiling = I_r                                 while m ≤ f·I_r²          (f = derate fraction)
///           = I_r − (m − f·I_r²) / ((1 − f) I_r)  above, clamped to [0, I_r] (0 at m = I_r²: the rating)
/// </pre>
/// Defaults (ControllerConfig) match the coil of the hardware plant
/// (host_sim/plant: R_th = 2 K/W, τ = 20 min, 60 K at 2.5 A continuous):
/// τ = 1200 s, I_r = 2.5 A, f = 0.8 (derating starts at 48 K estimated rise
/// and reaches 0 A at 60 K). Over-drive needs a target above zero, so with
/// the ceiling at 0 A the coil only cools. The estimate starts at ambient
/// (m = 0) at reset().
///
/// Units: currents in the controller's s_I A, squares in s_I² A²
/// (numeric_formats.hpp: s_I puts I_r in (1.77, 3.54] units; 1 for the
/// thesis's 2.5 A coil). θ/θ_r = m/I_r² does not depend on the unit.
///
/// Fixed point: m in Q9.22 s_I² A²; each tick adds i²/16, formed as i² in
/// Q13.18 (saturating at 8192 s_I² A², i = 90 s_I A, beyond the current
/// sensor's limit) read as Q9.22, so the 16-tick mean cannot leave Q9.22
/// (512 s_I² A²: a current held at the command limit, ≤ 22.6 s_I A by
/// validate_config, fits); α = 1.33e−5 in Q2.29 (7158 LSB). Rounding
/// lets m settle up to 0.5 LSB/α = 9e−3 s_I² A² from the exact value, 0.09 K
/// of the thesis's 60 K rating, at most 0.3 % of the rated rise for any
/// I_r.

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "firmware/core/numeric_formats.hpp"

namespace mrd::fw {

/// Ticks averaged per I²t update.
inline constexpr std::uint32_t kCoilI2tDecimation = 16;
static_assert(kCoilI2tDecimation == 16, "CoilI2t::sixteenth_of_square divides by 16");

template <class Policy>
class CoilI2t {
 public:
  using Current = typename Formats<Policy>::Current;
  using Square = typename Formats<Policy>::Square;
  using Coef = typename Formats<Policy>::Coef;
  using Mask = typename LaneTypes<Policy>::Mask;
  using Count = typename LaneTypes<Policy>::Count;

  /// `time_constant_s` τ, `period_s` T, `rated_a` I_r, `derate_fraction` f in (0, 1).
  void init(double time_constant_s, double period_s, double rated_a, double derate_fraction) noexcept {
    alpha_ = num::from_double<Coef>(
        1.0 - std::exp(-static_cast<double>(kCoilI2tDecimation) * period_s / time_constant_s));
    rated_a_ = num::from_double<Current>(rated_a);
    rated_square_ = num::from_double<Square>(rated_a * rated_a);
    derate_from_ = num::from_double<Square>(derate_fraction * rated_a * rated_a);
    slope_ = num::from_double<Current>(1.0 / ((1.0 - derate_fraction) * rated_a));
    reset();
  }

  void reset(Mask m = num::all_set<Mask>()) noexcept {
    mean_square_ = num::select(m, Square{}, mean_square_);
    sum_ = num::select(m, Square{}, sum_);
    count_ = num::select(m, Count{}, count_);
    ceiling_a_ = num::select(m, rated_a_, ceiling_a_);
  }

  /// One tick with the measured coil current (in the lanes of `m`; the
  /// others keep their state).
  void step(Current coil_a, Mask m = num::all_set<Mask>()) noexcept {
    sum_ = num::select(m, sum_ + sixteenth_of_square(coil_a), sum_);
    count_ = num::select(m, count_ + 1u, count_);
    const Mask full = count_ >= kCoilI2tDecimation;
    if (!num::any(full)) return;
    count_ = num::select(full, Count{}, count_);
    mean_square_ = num::select(full, mean_square_ + num::mul<Square>(alpha_, sum_ - mean_square_), mean_square_);
    sum_ = num::select(full, Square{}, sum_);
    const Square excess = mean_square_ - derate_from_;
    ceiling_a_ = num::select(
        full,
        num::select(excess < Square{}, rated_a_,
                    num::clamp(rated_a_ - num::mul<Current>(slope_, excess), Current{}, rated_a_)),
        ceiling_a_);
  }

  /// The steady current allowed now: I_r, derated as the coil heats.
  Current ceiling_a() const noexcept { return ceiling_a_; }
  /// m, A².
  Square mean_square_a2() const noexcept { return mean_square_; }
  /// θ/θ_r = m / I_r², the estimated rise as a fraction of the rated rise.
  double heating_fraction() const noexcept { return num::to_double(mean_square_) / num::to_double(rated_square_); }

 private:
  /// i²/16 in the Square format. Fixed point: i² rounded once into Q13.18,
  /// whose raw bits read as Q9.22 are i²/16 (no second product).
  static Square sixteenth_of_square(Current i) noexcept {
    if constexpr (std::is_floating_point_v<Square> || num::LaneVector<Square>) {
      return i * i * num::splat<Square>(0.0625f);
    } else {
      return Square::from_raw(num::mul<num::Fixed<13, 18>>(i, i).raw());
    }
  }

  Coef alpha_{};
  Current rated_a_{};
  Square rated_square_{};
  Square derate_from_{};
  Current slope_{};  ///< A per A²
  Square mean_square_{};
  Square sum_{};
  Count count_{};
  Current ceiling_a_{};
};

}  // namespace mrd::fw
