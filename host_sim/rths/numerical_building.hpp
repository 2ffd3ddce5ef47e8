#pragma once
/// The numerical substructure of the thesis's RTHS set-up (damper_rths.hpp):
/// the whole building, stepped tick by tick as the closed loop's plant steps
/// it (plant::Plant::advance): the linear part by the exact zero-order hold,
/// and for a building with isolators their hysteresis in
/// plant::structural_substeps equal sub-steps per tick, each holding the
/// isolators' hysteretic force at the sub-step's start beside the forces
/// given for the tick. Without isolators a tick is one exact step.
///
/// Copyable: a copy predicts the building's response ahead (the isolators'
/// hysteretic states included) without touching the original; that is what
/// IsolatedCommandPredictor does for a building with isolators (the linear
/// DamperCommandPredictor of thesis_actuator.hpp serves the others).

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "host_sim/plant/plant.hpp"
#include "host_sim/rths/thesis_actuator.hpp"
#include "host_sim/structure/discrete_building.hpp"
#include "host_sim/structure/isolators.hpp"

namespace mrd::rths {

class NumericalBuilding {
 public:
  /// Discretizes `b` for ticks of `step_s` and resets to rest. Throws
  /// std::invalid_argument for an invalid building or step.
  void init(const structure::BuildingParams& b, double step_s) {
    structure::validate(b);
    substeps_ = plant::structural_substeps(b, step_s);
    linear_.init(b, step_s / substeps_);
    isolators_.init(b);
    const std::vector<int>& elements = linear_.force_elements();
    isolator_slot_ =
        isolators_.empty() ? -1
                           : static_cast<int>(std::lower_bound(elements.begin(), elements.end(), structure::kBaseDof) -
                                              elements.begin());
    forces_.assign(elements.size(), 0.0);
  }

  /// One tick with the ground acceleration and `element_forces_n` (one per
  /// force_elements(), N) held over it.
  void step(double ground_accel_m_s2, const double* element_forces_n) {
    if (isolator_slot_ < 0) {
      linear_.step(ground_accel_m_s2, element_forces_n);
      return;
    }
    std::copy(element_forces_n, element_forces_n + forces_.size(), forces_.begin());
    const auto slot = static_cast<std::size_t>(isolator_slot_);
    const double given_on_base_n = forces_[slot];
    for (int k = 0; k < substeps_; ++k) {
      const double u0_m = linear_.base_disp_m();
      forces_[slot] = given_on_base_n + isolators_.hysteretic_force_n(linear_.base_vel_m_s());
      linear_.step(ground_accel_m_s2, forces_.data());
      isolators_.advance(linear_.base_disp_m() - u0_m);
    }
  }

  /// The linear part at the last sub-step (states, deformations,
  /// accelerations as DiscreteBuilding gives them).
  const structure::DiscreteBuilding& linear() const noexcept { return linear_; }
  const std::vector<int>& force_elements() const noexcept { return linear_.force_elements(); }
  /// Sub-steps per tick (1 without isolators).
  int substeps() const noexcept { return substeps_; }

 private:
  structure::DiscreteBuilding linear_;
  structure::IsolatorBank isolators_;
  std::vector<double> forces_;
  int isolator_slot_ = -1;
  int substeps_ = 1;
};

/// The model-based command of DamperCommandPredictor (thesis_actuator.hpp),
/// the same steps, over a copy of the numerical building with its isolators:
/// the damper element's deformation and rate D ticks ahead under the
/// record's future ground acceleration, the damper's force from the specimen
/// model along the prediction (its current held), then the lag's continuous
/// inverse. Allocates a copy of the building per prediction (host runs).
class IsolatedCommandPredictor {
 public:
  /// `params`: one damper placement. Throws std::invalid_argument otherwise,
  /// or for a negative delay or lag or a tick ≤ 0.
  IsolatedCommandPredictor(const structure::BuildingParams& params, const NumericalBuilding& building, double step_s,
                           double delay_s, double lag_s, double model_force_scale = 1.0)
      : lag_s_(lag_s), step_s_(step_s), force_scale_(model_force_scale) {
    if (params.dampers.size() != 1) throw std::invalid_argument("IsolatedCommandPredictor: one damper placement");
    if (!(delay_s >= 0.0 && lag_s >= 0.0 && step_s > 0.0))
      throw std::invalid_argument("IsolatedCommandPredictor: negative delay or lag, or a tick <= 0");
    element_ = static_cast<int>(params.dampers.front().element);
    count_ = params.dampers.front().count;
    const auto& e = building.force_elements();
    slot_ = static_cast<std::size_t>(std::lower_bound(e.begin(), e.end(), element_) - e.begin());
    steps_ahead_ = static_cast<int>(std::lround(delay_s / step_s));
    forces_.assign(e.size(), 0.0);
  }

  /// As DamperCommandPredictor::predict, from `now` at t_{n+1} (`from` = n + 1).
  ServoCommand predict(const NumericalBuilding& now, const std::vector<double>& ag, std::size_t from,
                       physics::MrDamper model, double current_a) {
    NumericalBuilding z = now;
    double v_before = rate(z), x_at = deformation(z), v_at = rate(z);
    for (int j = 0; j <= steps_ahead_; ++j) {
      const std::size_t k = from + static_cast<std::size_t>(j);
      if (j < steps_ahead_) v_before = rate(z);
      forces_[slot_] = count_ * force_scale_ * model.force_n(rate(z), deformation(z));
      model.step(current_a, rate(z), deformation(z));
      z.step(k < ag.size() ? ag[k] : 0.0, forces_.data());
      if (j + 1 == steps_ahead_) {
        x_at = deformation(z);
        v_at = rate(z);
      }
    }
    if (steps_ahead_ == 0) v_before = v_at;  // forward difference from the present
    const double accel = (rate(z) - v_before) / (steps_ahead_ == 0 ? step_s_ : 2.0 * step_s_);
    return ServoCommand{x_at + lag_s_ * v_at, v_at + lag_s_ * accel};
  }

 private:
  double deformation(const NumericalBuilding& b) const noexcept { return b.linear().element_deformation_m(element_); }
  double rate(const NumericalBuilding& b) const noexcept { return b.linear().element_rate_m_s(element_); }

  double lag_s_, step_s_, force_scale_;
  int element_ = 0, steps_ahead_ = 0;
  double count_ = 1.0;
  std::size_t slot_ = 0;
  std::vector<double> forces_;
};

}  // namespace mrd::rths
