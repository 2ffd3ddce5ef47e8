#include "host_sim/rths/damper_rths.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <stdexcept>

#include "host_sim/plant/stages.hpp"
#include "host_sim/structure/discrete_building.hpp"
#include "mrd/physics/mr_damper.hpp"

namespace mrd::rths {
namespace {

/// The actuator: each command is a position and a velocity; the servo's
/// controller interpolates them over the step (cubic Hermite, so the command
/// c(t) and ċ(t) are continuous), after a whole-step delay; the actuator
/// follows c through a first-order lag 1/(τ s + 1), solved exactly over the
/// cubic (x_p = c − τ ċ + τ² c̈ − τ³ c⃛ plus the decaying homogeneous part).
/// Its position and velocity are continuous, so the specimen sees the
/// velocity of a smooth motion at the sample, as the building's damper does.
class DelayedServo {
 public:
  DelayedServo(double delay_s, double lag_s, double step_s)
      : line_(static_cast<std::size_t>(std::lround(delay_s / step_s)), Point{}),
        lag_s_(lag_s),
        step_s_(step_s),
        decay_(lag_s > 0.0 ? std::exp(-step_s / lag_s) : 0.0) {}
  /// Takes the command (`command_m`, `command_rate_m_s`) and advances one
  /// step over the segment from the point that arrived last to the one that
  /// arrives now.
  void step(double command_m, double command_rate_m_s) {
    line_.push_back(Point{command_m, command_rate_m_s});
    const Point p1 = line_.front();
    line_.pop_front();
    const double t = step_s_;
    // c(s) = a0 + a1 s + a2 s² + a3 s³ over [0, T].
    const double a0 = last_.c, a1 = last_.rate;
    const double a2 = (3.0 * (p1.c - last_.c) / t - 2.0 * last_.rate - p1.rate) / t;
    const double a3 = (2.0 * (last_.c - p1.c) / t + last_.rate + p1.rate) / (t * t);
    if (lag_s_ > 0.0) {
      const double tau = lag_s_;
      // Particular solution x_p and its rate at s = 0 and s = T.
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
  double position_m() const { return x_; }
  double velocity_m_s() const { return v_; }

 private:
  struct Point {
    double c = 0.0, rate = 0.0;
  };
  std::deque<Point> line_;
  double lag_s_, step_s_, decay_;
  Point last_;
  double x_ = 0.0, v_ = 0.0;
};

}  // namespace

DamperRthsResult run_damper_rths(const DamperRthsSpec& spec, const std::vector<double>& ground_accel_m_s2,
                                 run::Controller& controller, DamperRthsRecord* record) {
  const structure::BuildingParams& b = spec.plant.building;
  if (!b.isolators.empty()) throw std::invalid_argument("run_damper_rths: a building with isolators");
  if (b.dampers.size() != 1) throw std::invalid_argument("run_damper_rths: one damper placement");
  if (spec.plant.kind != plant::PlantKind::kThesis) throw std::invalid_argument("run_damper_rths: thesis plant only");
  if (!(spec.delay_s >= 0.0 && spec.lag_s >= 0.0)) throw std::invalid_argument("run_damper_rths: negative delay or lag");
  const double t = spec.plant.step_s;
  structure::validate(b);
  structure::DiscreteBuilding building;
  building.init(b, t);
  physics::MrDamper damper;
  damper.init(spec.plant.damper, t, physics::settling_quotient_after_idle(spec.plant.idle_time_s, spec.plant.settling));
  controller.reset();
  DelayedServo servo(spec.delay_s, spec.lag_s, t);
  // The compensator's model of the specimen, driven by what the laboratory
  // knows (the measured stroke and rate and the commanded current).
  physics::MrDamper model = damper;
  const int element = static_cast<int>(b.dampers.front().element);
  const std::size_t slot_of_damper = static_cast<std::size_t>(
      std::lower_bound(building.force_elements().begin(), building.force_elements().end(), element) -
      building.force_elements().begin());
  // The command made at tick n from the state at t_{n+1} arrives at the
  // servo at t_{n+1+D} (D whole steps of delay). The numerical building is
  // known: its state D and D ± 1 steps ahead is predicted by its own exact
  // ZOH steps, with the record's own future ground acceleration (prescribed)
  // and the damper's force held at the last measured value. The lag's
  // continuous inverse c = x̂ + τ ẋ̂, ċ = ẋ̂ + τ ẍ̂ (ẍ̂ by the central
  // difference of the predicted rates) makes the actuator follow x̂.
  const int steps_ahead = static_cast<int>(std::lround(spec.delay_s / t));
  const double count = b.dampers.front().count;
  const int dofs = b.dofs();
  const auto deformation = [&](const structure::Vector& s) {
    return element == 0 ? s(0) : s(element) - s(element - 1);
  };
  const auto rate = [&](const structure::Vector& s) {
    return element == 0 ? s(dofs) : s(dofs + element) - s(dofs + element - 1);
  };
  struct Command {
    double c_m, rate_m_s;
  };
  const auto predicted_command = [&](const structure::DiscreteBuilding& now, const std::vector<double>& ag,
                                     std::size_t from, physics::MrDamper model, double current_a) {
    structure::Vector z = now.state();
    structure::Vector u = structure::Vector::Zero(now.gamma().cols());
    double v_before = rate(z), x_at = deformation(z), v_at = rate(z);
    for (int j = 0; j <= steps_ahead; ++j) {
      const std::size_t k = from + static_cast<std::size_t>(j);
      u(0) = k < ag.size() ? ag[k] : 0.0;
      if (j < steps_ahead) v_before = rate(z);
      u(1 + static_cast<Eigen::Index>(slot_of_damper)) = count * spec.model_force_scale * model.force_n(rate(z), deformation(z));
      model.step(current_a, rate(z), deformation(z));
      z = now.phi() * z + now.gamma() * u;
      if (j + 1 == steps_ahead) {
        x_at = deformation(z);
        v_at = rate(z);
      }
    }
    if (steps_ahead == 0) v_before = v_at;  // forward difference from the present
    const double accel = (rate(z) - v_before) / (steps_ahead == 0 ? t : 2.0 * t);
    return Command{x_at + spec.lag_s * v_at, v_at + spec.lag_s * accel};
  };

  std::vector<double> forces(building.force_elements().size(), 0.0);
  const auto& elements = building.force_elements();
  const std::size_t slot =
      static_cast<std::size_t>(std::lower_bound(elements.begin(), elements.end(), element) - elements.begin());
  std::vector<double> accel(static_cast<std::size_t>(b.dofs()), 0.0);

  DamperRthsResult r;
  double e2 = 0.0, x2 = 0.0, ev2 = 0.0, v2 = 0.0;
  for (std::size_t n = 0; n < ground_accel_m_s2.size(); ++n) {
    const double target_m = building.element_deformation_m(element);
    const double x_a = servo.position_m();
    const double v_a = servo.velocity_m_s();
    const double f = damper.force_n(v_a, x_a);
    building.abs_accel_m_s2(accel.data());
    control::ControllerInput in;
    in.tick = n;
    in.damper_disp_m = static_cast<float>(x_a);
    in.damper_force_n = static_cast<float>(f);
    in.ground_accel_m_s2 = static_cast<float>(ground_accel_m_s2[n]);
    in.base_accel_m_s2 = static_cast<float>(accel[0]);
    in.coil_current_a = static_cast<float>(damper.current_a());
    const control::ControllerOutput out = controller.step(in);
    const double current_a =
        plant::command_stage_a(plant::CoilDrive{static_cast<double>(out.current_command_a), out.drive_enable});
    damper.step(current_a, v_a, x_a);
    model.step(current_a, v_a, x_a);
    forces[slot] = count * f;
    const double base_before_m = building.base_disp_m();
    r.peak_base_displacement_m = std::max(r.peak_base_displacement_m, std::fabs(base_before_m));
    r.peak_damper_force_n = std::max(r.peak_damper_force_n, std::fabs(f));
    r.peak_tracking_error_m = std::max(r.peak_tracking_error_m, std::fabs(x_a - target_m));
    e2 += (x_a - target_m) * (x_a - target_m);
    x2 += target_m * target_m;
    const double target_rate_m_s = building.element_rate_m_s(element);
    ev2 += (v_a - target_rate_m_s) * (v_a - target_rate_m_s);
    v2 += target_rate_m_s * target_rate_m_s;
    building.step(ground_accel_m_s2[n], forces.data());
    const Command c = spec.compensate ? predicted_command(building, ground_accel_m_s2, n + 1, model, current_a)
                                      : Command{building.element_deformation_m(element), building.element_rate_m_s(element)};
    servo.step(c.c_m, c.rate_m_s);
    if (record != nullptr) {
      record->time_s.push_back(static_cast<double>(n) * t);
      record->target_m.push_back(target_m);
      record->actuator_m.push_back(x_a);
      record->actuator_velocity_m_s.push_back(v_a);
      record->command_m.push_back(c.c_m);
      record->force_n.push_back(f);
      record->current_a.push_back(current_a);
      record->base_displacement_m.push_back(base_before_m);
    }
  }
  // The last state reached counts too (as in the closed loop's summary).
  r.peak_base_displacement_m = std::max(r.peak_base_displacement_m, std::fabs(building.base_disp_m()));
  r.rms_tracking_error_pct = x2 > 0.0 ? 100.0 * std::sqrt(e2 / x2) : 0.0;
  r.rms_velocity_error_pct = v2 > 0.0 ? 100.0 * std::sqrt(ev2 / v2) : 0.0;
  return r;
}

}  // namespace mrd::rths
