#include "host_sim/plant/pwm_drive.hpp"

#include <algorithm>
#include <cmath>

namespace mrd::plant {

void PwmDrive::init(const PwmDriveParams& p, const CoilParams& coil) noexcept {
  p_ = p;
  coil_.init(coil);
  kp_v_a_ = coil.inductance_1a_h * p.loop_bandwidth_rad_s;
  ki_v_as_ = coil.resistance_ohm * p.loop_bandwidth_rad_s;
  integral_v_ = 0.0;
  voltage_v_ = 0.0;
  i2t_a2s_ = 0.0;
  i2t_budget_a2s_ =
      (p.peak_current_a * p.peak_current_a - p.continuous_current_a * p.continuous_current_a) * p.peak_time_s;
}

double PwmDrive::current_limit_a() const noexcept {
  return i2t_a2s_ >= i2t_budget_a2s_ ? p_.continuous_current_a : p_.peak_current_a;
}

double PwmDrive::reference_a(double command_a) const noexcept {
  const double command_v = std::clamp(command_a * p_.volts_per_amp, -p_.command_limit_v, p_.command_limit_v);
  const double limit_a = current_limit_a();
  return std::clamp(command_v / p_.volts_per_amp, -limit_a, limit_a);
}

void PwmDrive::substep(const CoilDrive& drive, double dt_s) noexcept {
  const double i = coil_.current_a();
  if (!drive.output_on) {
    // Bridge open: the current freewheels into the bus until it reaches zero.
    integral_v_ = 0.0;
    voltage_v_ = i > 0.0 ? -p_.bus_v : (i < 0.0 ? p_.bus_v : 0.0);
    coil_.step(voltage_v_, dt_s);
    if ((i > 0.0 && coil_.current_a() < 0.0) || (i < 0.0 && coil_.current_a() > 0.0)) coil_.set_current_a(0.0);
  } else {
    const double e = reference_a(drive.current_a) - i;
    const double unsat_v = kp_v_a_ * e + integral_v_;
    voltage_v_ = std::clamp(unsat_v, -p_.bus_v, p_.bus_v);
    const bool pushing_further = (unsat_v > p_.bus_v && e > 0.0) || (unsat_v < -p_.bus_v && e < 0.0);
    if (!pushing_further) integral_v_ += ki_v_as_ * e * dt_s;
    coil_.step(voltage_v_, dt_s);
  }
  const double i_end = coil_.current_a();
  const double cont2 = p_.continuous_current_a * p_.continuous_current_a;
  i2t_a2s_ = std::max(0.0, i2t_a2s_ + (i_end * i_end - cont2) * dt_s);
}

double PwmDrive::step(const CoilDrive& drive, double step_s) noexcept {
  const int n = std::max(1, static_cast<int>(std::lround(step_s / p_.substep_s)));
  const double dt_s = step_s / n;
  double sum_sq = 0.0;
  for (int k = 0; k < n; ++k) {
    const double i0 = coil_.current_a();
    substep(drive, dt_s);
    const double i1 = coil_.current_a();
    sum_sq += (i0 * i0 + i0 * i1 + i1 * i1) / 3.0;  // mean of i² for i linear over the substep
  }
  return sum_sq / n;
}

}  // namespace mrd::plant
