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

/// The actuator: a whole-step delay line, then 1/(τ s + 1) by exact ZOH.
class DelayedServo {
 public:
  DelayedServo(double delay_s, double lag_s, double step_s)
      : line_(static_cast<std::size_t>(std::lround(delay_s / step_s)), 0.0),
        lag_s_(lag_s),
        decay_(lag_s > 0.0 ? std::exp(-step_s / lag_s) : 0.0) {}
  /// Holds `command` over the step and advances.
  void step(double command_m) {
    line_.push_back(command_m);
    held_ = line_.front();
    line_.pop_front();
    x_ = decay_ * x_ + (1.0 - decay_) * held_;
  }
  double position_m() const { return x_; }
  /// ẋ = (u − x)/τ at the sample: the mean of its left (u the value held
  /// over the step just ended) and right (u the value held next) limits,
  /// where the held command steps; without a lag, the position's last
  /// change over the step.
  double velocity_m_s(double step_s) const {
    return lag_s_ > 0.0 ? (0.5 * (held_ + next_held()) - x_) / lag_s_ : (x_ - prev_) / step_s;
  }
  void remember() { prev_ = x_; }

 private:
  double next_held() const { return line_.empty() ? held_ : line_.front(); }
  std::deque<double> line_;
  double lag_s_, decay_;
  double held_ = 0.0, x_ = 0.0, prev_ = 0.0;
};

}  // namespace

DamperRthsResult run_damper_rths(const DamperRthsSpec& spec, const std::vector<double>& ground_accel_m_s2,
                                 run::Controller& controller) {
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
  const int element = static_cast<int>(b.dampers.front().element);
  const std::size_t slot_of_damper = static_cast<std::size_t>(
      std::lower_bound(building.force_elements().begin(), building.force_elements().end(), element) -
      building.force_elements().begin());
  // The command c_n, made from the state at t_{n+1}, is held over
  // [t_{n+D}, t_{n+D+1}] (D whole steps of delay), so the servo's position at
  // t_{n+D+1} is a·x(t_{n+D}) + (1 − a)·c_n (a = e^{−T/τ}). The numerical
  // building is known: its state D − 1 and D steps ahead is predicted by its
  // own exact ZOH steps, with the record's own future ground acceleration
  // (prescribed) and the damper's force held at the last measured value, and
  // c_n = (x̂(t_{n+D+1}) − a·x̂(t_{n+D}))/(1 − a) inverts the lag.
  const int steps_ahead = static_cast<int>(std::lround(spec.delay_s / t));
  const double a_lag = spec.lag_s > 0.0 ? std::exp(-t / spec.lag_s) : 0.0;
  const auto predicted_command = [&](const structure::DiscreteBuilding& now, const std::vector<double>& ag,
                                     std::size_t from, double force_n) {
    structure::Vector z = now.state();
    structure::Vector u = structure::Vector::Zero(now.gamma().cols());
    u(1 + static_cast<Eigen::Index>(slot_of_damper)) = force_n;
    const auto deformation = [&](const structure::Vector& s) {
      return element == 0 ? s(0) : s(element) - s(element - 1);
    };
    double before = deformation(z);
    for (int j = 0; j < steps_ahead; ++j) {
      const std::size_t k = from + static_cast<std::size_t>(j);
      u(0) = k < ag.size() ? ag[k] : 0.0;
      before = deformation(z);
      z = now.phi() * z + now.gamma() * u;
    }
    return (deformation(z) - a_lag * before) / (1.0 - a_lag);
  };

  const double count = b.dampers.front().count;
  std::vector<double> forces(building.force_elements().size(), 0.0);
  const auto& elements = building.force_elements();
  const std::size_t slot =
      static_cast<std::size_t>(std::lower_bound(elements.begin(), elements.end(), element) - elements.begin());
  std::vector<double> accel(static_cast<std::size_t>(b.dofs()), 0.0);

  DamperRthsResult r;
  double e2 = 0.0, x2 = 0.0;
  for (std::size_t n = 0; n < ground_accel_m_s2.size(); ++n) {
    const double target_m = building.element_deformation_m(element);
    const double x_a = servo.position_m();
    const double v_a = servo.velocity_m_s(t);
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
    damper.step(plant::command_stage_a(plant::CoilDrive{static_cast<double>(out.current_command_a), out.drive_enable}),
                v_a, x_a);
    forces[slot] = count * f;
    r.peak_base_displacement_m = std::max(r.peak_base_displacement_m, std::fabs(building.base_disp_m()));
    r.peak_damper_force_n = std::max(r.peak_damper_force_n, std::fabs(f));
    r.peak_tracking_error_m = std::max(r.peak_tracking_error_m, std::fabs(x_a - target_m));
    e2 += (x_a - target_m) * (x_a - target_m);
    x2 += target_m * target_m;
    building.step(ground_accel_m_s2[n], forces.data());
    servo.remember();
    servo.step(spec.compensate ? predicted_command(building, ground_accel_m_s2, n + 1, count * f)
                               : building.element_deformation_m(element));
  }
  r.rms_tracking_error_pct = x2 > 0.0 ? 100.0 * std::sqrt(e2 / x2) : 0.0;
  return r;
}

}  // namespace mrd::rths
