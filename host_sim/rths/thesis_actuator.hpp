#pragma once
/// The actuator and the model-based command of the thesis's RTHS set-up
/// (damper_rths.hpp), as parts a board program can hold: the laboratory's
/// servo and the runtime's prediction over its delay.
///
/// - DelayedServo: each command is a position and a rate; after a whole-step
///   delay the servo's controller interpolates them over the step (cubic
///   Hermite) and the actuator follows through a first-order lag solved
///   exactly over the cubic: position and velocity continuous.
/// - LookaheadServo: the same actuator fed positions only (what a command
///   frame carries): it holds one command more and takes each point's rate
///   as the central difference of its neighbours, so the total delay stays
///   `delay_s` (at least one step).
/// - DamperCommandPredictor: the numerical building's own exact ZOH steps
///   over the delay with the record's future ground acceleration, the
///   damper's force from a model of the specimen (an MrDamper driven along
///   the prediction, its current held), then the lag's continuous inverse
///   (c = x̂ + τ ẋ̂, ċ = ẋ̂ + τ ẍ̂).
///
/// Nothing here allocates after construction except
/// DamperCommandPredictor::predict's copy of the specimen model.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "host_sim/structure/discrete_building.hpp"
#include "mrd/physics/mr_damper.hpp"

namespace mrd::rths {

class DelayedServo {
 public:
  /// Throws std::invalid_argument for a negative delay or lag or a step ≤ 0.
  DelayedServo(double delay_s, double lag_s, double step_s)
      : lag_s_(lag_s), step_s_(step_s), decay_(lag_s > 0.0 ? std::exp(-step_s / lag_s) : 0.0) {
    if (!(delay_s >= 0.0 && lag_s >= 0.0 && step_s > 0.0))
      throw std::invalid_argument("DelayedServo: negative delay or lag, or a step <= 0");
    line_.assign(static_cast<std::size_t>(std::lround(delay_s / step_s)), Point{});
  }
  /// Takes the command (`command_m`, `command_rate_m_s`) and advances one
  /// step over the segment from the point that arrived last to the one that
  /// arrives now (the delay line is a ring: nothing allocates).
  void step(double command_m, double command_rate_m_s) noexcept {
    Point p1{command_m, command_rate_m_s};
    if (!line_.empty()) {
      std::swap(p1, line_[head_]);
      head_ = (head_ + 1) % line_.size();
    }
    const double t = step_s_;
    // c(s) = a0 + a1 s + a2 s² + a3 s³ over [0, T].
    const double a0 = last_.c, a1 = last_.rate;
    const double a2 = (3.0 * (p1.c - last_.c) / t - 2.0 * last_.rate - p1.rate) / t;
    const double a3 = (2.0 * (last_.c - p1.c) / t + last_.rate + p1.rate) / (t * t);
    if (lag_s_ > 0.0) {
      const double tau = lag_s_;
      // Particular solution x_p = c − τ ċ + τ² c̈ − τ³ c⃛ and its rate at s = 0 and s = T.
      const auto xp = [&](double s) {
        const double c = a0 + s * (a1 + s * (a2 + s * a3));
        const double d1 = a1 + s * (2.0 * a2 + 3.0 * s * a3);
        const double d2 = 2.0 * a2 + 6.0 * s * a3;
        return c - tau * d1 + tau * tau * d2 - tau * tau * tau * 6.0 * a3;
      };
      const auto xp_rate = [&](double s) {
        const double d1 = a1 + s * (2.0 * a2 + 3.0 * s * a3);
        const double d2 = 2.0 * a2 + 6.0 * s * a3;
        return d1 - tau * d2 + tau * tau * 6.0 * a3;
      };
      const double h0 = x_ - xp(0.0);
      x_ = xp(t) + h0 * decay_;
      v_ = xp_rate(t) - h0 * decay_ / tau;
    } else {
      x_ = p1.c;
      v_ = p1.rate;
    }
    last_ = p1;
  }
  double position_m() const noexcept { return x_; }
  double velocity_m_s() const noexcept { return v_; }

 private:
  struct Point {
    double c = 0.0, rate = 0.0;
  };
  std::vector<Point> line_;
  std::size_t head_ = 0;
  double lag_s_, step_s_, decay_;
  Point last_;
  double x_ = 0.0, v_ = 0.0;
};

class LookaheadServo {
 public:
  /// Throws std::invalid_argument for a delay under one step (the rate of a
  /// point needs the command after it), a negative lag or a step ≤ 0.
  LookaheadServo(double delay_s, double lag_s, double step_s)
      : servo_(checked_inner_delay_s(delay_s, step_s), lag_s, step_s), step_s_(step_s) {}
  /// Takes command c[n]; the point c[n−1] enters the servo with the rate
  /// (c[n] − c[n−2]) / 2T.
  void step(double command_m) noexcept {
    servo_.step(c1_, (command_m - c2_) / (2.0 * step_s_));
    c2_ = c1_;
    c1_ = command_m;
  }
  double position_m() const noexcept { return servo_.position_m(); }
  double velocity_m_s() const noexcept { return servo_.velocity_m_s(); }

 private:
  static double checked_inner_delay_s(double delay_s, double step_s) {
    if (!(step_s > 0.0) || !(std::lround(delay_s / step_s) >= 1))
      throw std::invalid_argument("LookaheadServo: the delay must be at least one step");
    return delay_s - step_s;
  }
  DelayedServo servo_;
  double step_s_;
  double c1_ = 0.0, c2_ = 0.0;
};

/// A command for the servo: a position and its rate.
struct ServoCommand {
  double position_m = 0.0;
  double rate_m_s = 0.0;
};

class DamperCommandPredictor {
 public:
  /// `building` initialised on `params` (one damper placement, no
  /// isolators), the actuator's delay and lag, and the model's force over the
  /// specimen's (1: exact). Throws std::invalid_argument otherwise.
  DamperCommandPredictor(const structure::BuildingParams& params, const structure::DiscreteBuilding& building,
                         double delay_s, double lag_s, double model_force_scale = 1.0)
      : lag_s_(lag_s), dt_s_(building.dt_s()), force_scale_(model_force_scale) {
    if (params.dampers.size() != 1 || !params.isolators.empty())
      throw std::invalid_argument("DamperCommandPredictor: one damper placement and no isolators");
    if (!(delay_s >= 0.0 && lag_s >= 0.0 && dt_s_ > 0.0))
      throw std::invalid_argument("DamperCommandPredictor: negative delay or lag, or no step");
    element_ = static_cast<int>(params.dampers.front().element);
    count_ = params.dampers.front().count;
    dofs_ = building.dofs();
    const auto& e = building.force_elements();
    slot_ = static_cast<std::size_t>(std::lower_bound(e.begin(), e.end(), element_) - e.begin());
    steps_ahead_ = static_cast<int>(std::lround(delay_s / dt_s_));
    z_.resize(2 * dofs_);
    next_.resize(2 * dofs_);
    u_.setZero(building.gamma().cols());
  }

  int element() const noexcept { return element_; }
  double count() const noexcept { return count_; }
  /// The force slot of the damper's element in DiscreteBuilding::step's forces.
  std::size_t slot() const noexcept { return slot_; }

  /// The command made after `now` stepped to t_{n+1} (`from` = n + 1): the
  /// prediction of the damper element's deformation and rate D steps ahead
  /// through the lag's inverse. `model` is the specimen model's state now
  /// (copied), `current_a` the coil current held over the prediction.
  ServoCommand predict(const structure::DiscreteBuilding& now, const std::vector<double>& ag, std::size_t from,
                       physics::MrDamper model, double current_a) {
    z_ = now.state();
    double v_before = rate(z_), x_at = deformation(z_), v_at = rate(z_);
    for (int j = 0; j <= steps_ahead_; ++j) {
      const std::size_t k = from + static_cast<std::size_t>(j);
      u_(0) = k < ag.size() ? ag[k] : 0.0;
      if (j < steps_ahead_) v_before = rate(z_);
      u_(1 + static_cast<Eigen::Index>(slot_)) = count_ * force_scale_ * model.force_n(rate(z_), deformation(z_));
      model.step(current_a, rate(z_), deformation(z_));
      next_.noalias() = now.phi() * z_;
      next_.noalias() += now.gamma() * u_;
      z_.swap(next_);
      if (j + 1 == steps_ahead_) {
        x_at = deformation(z_);
        v_at = rate(z_);
      }
    }
    if (steps_ahead_ == 0) v_before = v_at;  // forward difference from the present
    const double accel = (rate(z_) - v_before) / (steps_ahead_ == 0 ? dt_s_ : 2.0 * dt_s_);
    return ServoCommand{x_at + lag_s_ * v_at, v_at + lag_s_ * accel};
  }

 private:
  double deformation(const structure::Vector& s) const noexcept {
    return element_ == 0 ? s(0) : s(element_) - s(element_ - 1);
  }
  double rate(const structure::Vector& s) const noexcept {
    return element_ == 0 ? s(dofs_) : s(dofs_ + element_) - s(dofs_ + element_ - 1);
  }

  double lag_s_, dt_s_, force_scale_;
  int element_ = 0, dofs_ = 0, steps_ahead_ = 0;
  double count_ = 1.0;
  std::size_t slot_ = 0;
  structure::Vector z_, next_, u_;
};

}  // namespace mrd::rths
