#include "host_sim/rths/laboratory.hpp"

#include <algorithm>
#include <cmath>

namespace mrd::rths {

const char* lab_stop_name(LabStop s) {
  switch (s) {
    case LabStop::kNone: return "none";
    case LabStop::kForceLimit: return "force_limit";
    case LabStop::kTrackingLimit: return "tracking_limit";
    case LabStop::kNotFinite: return "not_finite";
  }
  return "?";
}

Laboratory::Laboratory(const LabPlantParams& plant, const LaboratorySpec& spec, double dt_s)
    : spec_(spec),
      sys_(zero_order_hold(lab_plant_model(plant), dt_s)),
      z_(Vector::Zero(5)),
      z_next_(Vector::Zero(5)),
      rng_(spec.noise_seed),
      sigma_x_m_(std::sqrt(spec.displacement_noise_power_m2_hz / dt_s)),
      sigma_f_n_(std::sqrt(spec.force_noise_power_n2_hz / dt_s)) {}

double Laboratory::quantize(double value, double full_scale, double range_v, int bits) {
  const double volts = std::clamp(value / full_scale * range_v, -range_v, range_v);
  const double step_v = 2.0 * range_v / std::ldexp(1.0, bits);
  return std::round(volts / step_v) * step_v / range_v * full_scale;
}

double Laboratory::true_displacement_m() const { return sys_.c.row(0).dot(z_); }
double Laboratory::true_force_n() const { return sys_.c.row(1).dot(z_); }

LabMeasurement Laboratory::measure() {
  LabMeasurement m;
  m.displacement_m = quantize(true_displacement_m() + sigma_x_m_ * normal_(rng_), spec_.displacement_full_scale_m,
                              spec_.converter_range_v, spec_.converter_bits);
  m.force_n = quantize(true_force_n() + sigma_f_n_ * normal_(rng_), spec_.force_full_scale_n,
                       spec_.converter_range_v, spec_.converter_bits);
  return m;
}

void Laboratory::step(double command_m, double target_m) {
  if (stop_ == LabStop::kNone) {
    if (!std::isfinite(command_m)) {
      stop_ = LabStop::kNotFinite;
    } else {
      held_command_m_ = quantize(command_m, spec_.displacement_full_scale_m, spec_.converter_range_v,
                                 spec_.converter_bits);
      if (std::fabs(true_displacement_m() - target_m) > spec_.tracking_limit_m) stop_ = LabStop::kTrackingLimit;
    }
  }
  z_next_.noalias() = sys_.phi * z_;
  z_next_ += sys_.gamma.col(0) * held_command_m_;
  z_.swap(z_next_);
  const double f = std::fabs(true_force_n());
  peak_force_n_ = std::max(peak_force_n_, f);
  if (stop_ == LabStop::kNone && f > spec_.force_limit_n) stop_ = LabStop::kForceLimit;
  if (stop_ == LabStop::kNone && !z_.allFinite()) stop_ = LabStop::kNotFinite;
}

}  // namespace mrd::rths
