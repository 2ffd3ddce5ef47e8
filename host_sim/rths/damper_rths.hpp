#pragma once
/// The thesis's own RTHS (§3.3, §6.4), emulated: the building numerical, the
/// MR damper physical behind a servo-hydraulic actuator, the damper
/// controller (ODBDCO or a passive mode) running beside it exactly as in the
/// closed loop (run::closed_loop_tick's sensing and command order).
///
/// Per tick n (step T):
/// 1. the target stroke x_t[n] = the damper element's deformation of the
///    numerical building at t_n;
/// 2. after the building's step, the command for the next one, a position
///    and a rate: without compensation the target's deformation and rate;
///    with it, the numerical building's own prediction over the delay (its
///    exact ZOH steps with the record's future ground acceleration, which
///    an RTHS knows, and the damper's force from the compensator's model of
///    the specimen: an MrDamper driven by the measured stroke and rate and
///    the commanded current, its current held over the prediction), through
///    the servo lag's continuous inverse (c = x̂ + τ ẋ̂, ċ = ẋ̂ + τ ẍ̂);
/// 3. the actuator: the commands delayed by a whole number of steps
///    (delay_s), interpolated over each step (cubic Hermite through the
///    positions and rates), then a first-order servo lag (lag_s) solved
///    exactly over the cubic: position and velocity continuous;
/// 4. the damper (physics::MrDamper, with its idle effects) at the
///    actuator's stroke and velocity gives the measured force; the
///    controller senses the actuator's stroke, the force, the ground and the
///    building's base acceleration and the coil current, as in the closed
///    loop; the damper's coil follows its command;
/// 5. the building advances one tick with the measured force (one exact ZOH
///    step; with isolators the closed loop's sub-steps).
///
/// A building with isolators is stepped as the closed loop steps it (their
/// hysteresis in the plant's sub-steps, numerical_building.hpp), and the
/// prediction steps a copy of it; one damper placement (count may be > 1).

#include <vector>

#include "host_sim/plant/plant.hpp"
#include "host_sim/run/controller.hpp"

namespace mrd::rths {

struct DamperRthsSpec {
  plant::PlantSpec plant;      ///< building, damper, settling, step (kind must be kThesis)
  double delay_s = 0.015;      ///< the actuator's pure delay, s (whole steps)
  double lag_s = 0.002;        ///< its first-order servo lag, s (0: none)
  bool compensate = true;      ///< the model-based prediction above
  /// The compensator's specimen model's force over the specimen's (1: the
  /// model is exact; otherwise an identification error of the force law).
  double model_force_scale = 1.0;
};

struct DamperRthsResult {
  double peak_base_displacement_m = 0.0;  ///< max |x_0| of the numerical building
  double peak_damper_force_n = 0.0;
  double rms_tracking_error_pct = 0.0;    ///< 100·rms(x_a − x_t)/rms(x_t)
  double peak_tracking_error_m = 0.0;
  double rms_velocity_error_pct = 0.0;    ///< 100·rms(ẋ_a − ẋ_t)/rms(ẋ_t), the rates the specimen and the building's element see
};

/// Time series at every tick n (optional): the state at t_n and what tick n
/// made.
struct DamperRthsRecord {
  std::vector<double> time_s;
  std::vector<double> target_m;               ///< the building element's deformation x_t[n]
  std::vector<double> actuator_m;             ///< the actuator's (specimen's) stroke x_a[n]
  std::vector<double> actuator_velocity_m_s;  ///< its rate
  std::vector<double> command_m;              ///< the position command made at tick n (for the next step)
  std::vector<double> force_n;                ///< the measured force of one damper
  std::vector<double> current_a;              ///< the coil current command stage's output u[n]
  std::vector<double> base_displacement_m;    ///< x_0[n] of the numerical building
};

/// Runs it over `ground_accel_m_s2` at spec.plant.step_s, after resetting
/// `controller`; fills `record` when given. Throws std::invalid_argument for
/// more than one damper placement, a hardware plant or a negative delay or
/// lag.
DamperRthsResult run_damper_rths(const DamperRthsSpec& spec, const std::vector<double>& ground_accel_m_s2,
                                 run::Controller& controller, DamperRthsRecord* record = nullptr);

}  // namespace mrd::rths
