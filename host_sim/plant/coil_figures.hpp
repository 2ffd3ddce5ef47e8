#pragma once
/// Figures of the coil over a run, for every plant: the current the coil
/// carried, how long it ran above the damper's rated current
/// (MrDamperParams::rating), how often the controller changed its command,
/// and how hot the coil got.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "mrd/physics/mr_damper.hpp"

namespace mrd::plant {

/// Rated coil current of the thesis damper, A: the passive-on current of
/// §6.4 (physics::DamperRating's default). A counter built without a rating counts against it.
inline constexpr double kRatedCoilCurrent_a = physics::DamperRating{}.current_a;

struct CoilFigures {
  double peak_coil_current_a = 0.0;           ///< max |i| over the ticks
  double rms_coil_current_a = 0.0;            ///< sqrt(mean i²) over the ticks
  double time_above_rated_s = 0.0;            ///< time with |i| above the damper's rated current, s
  double command_changes_per_s = 0.0;         ///< command changes between consecutive ticks per s of run
  double peak_coil_temperature_rise_k = 0.0;  ///< max coil temperature above ambient, K
};

/// Accumulates CoilFigures tick by tick.
class CoilFigureCounter {
 public:
  CoilFigureCounter() = default;
  /// Counts the time above `rated_current_a` (the damper's rating.current_a), A.
  explicit CoilFigureCounter(double rated_current_a) noexcept : rated_a_(rated_current_a) {}

  /// One tick: the coil current at t_n, the command u[n] the coil was given
  /// over the step, and the coil temperature rise reached at t_{n+1}.
  void add(double coil_current_a, double command_a, double temperature_rise_k) noexcept {
    const double i = std::fabs(coil_current_a);
    peak_a_ = std::max(peak_a_, i);
    sum_sq_a2_ += coil_current_a * coil_current_a;
    if (i > rated_a_) ++ticks_above_;
    if (command_a != last_command_a_) ++changes_;
    last_command_a_ = command_a;
    peak_rise_k_ = std::max(peak_rise_k_, temperature_rise_k);
    ++ticks_;
  }

  /// The figures over `ticks` steps of `step_s`.
  CoilFigures figures(double step_s) const noexcept {
    CoilFigures f;
    f.peak_coil_current_a = peak_a_;
    f.peak_coil_temperature_rise_k = peak_rise_k_;
    if (ticks_ == 0) return f;
    const double duration_s = static_cast<double>(ticks_) * step_s;
    f.rms_coil_current_a = std::sqrt(sum_sq_a2_ / static_cast<double>(ticks_));
    f.time_above_rated_s = static_cast<double>(ticks_above_) * step_s;
    f.command_changes_per_s = static_cast<double>(changes_) / duration_s;
    return f;
  }

 private:
  double rated_a_ = kRatedCoilCurrent_a;
  double peak_a_ = 0.0;
  double sum_sq_a2_ = 0.0;
  double peak_rise_k_ = 0.0;
  double last_command_a_ = 0.0;
  std::uint64_t ticks_ = 0;
  std::uint64_t ticks_above_ = 0;
  std::uint64_t changes_ = 0;
};

}  // namespace mrd::plant
