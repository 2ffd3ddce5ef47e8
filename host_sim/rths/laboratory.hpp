#pragma once
/// The emulated laboratory of an RTHS: the control plant stepped at the loop
/// rate under a zero-order-hold command, behind converters and sensors.
///
/// - Converters: ±3.8 V, 18 bit (step 7.6 V / 2¹⁸ = 29.0 µV), the command
///   through a DAC and both measurements through ADCs; a channel's
///   calibration maps its full scale to ±3.8 V (displacement_full_scale_m,
///   force_full_scale_n) and saturates beyond it.
/// - Sensor noise: white, given as a noise power P (a power spectral density,
///   unit²/Hz, Simulink's band-limited white noise): the sampled noise's
///   variance is P / Δt = P·f_s at the loop rate (the benchmark's
///   displacement 6.25e-14 m²/Hz is σ = 16.0 µm at 4096 Hz, its force
///   1.16e-3 N²/Hz is σ = 2.18 N).
/// - A stop: when |F| exceeds the actuator's force limit (8.9 kN) or the
///   tracking error |measured − target| exceeds tracking_limit_m, the
///   actuator holds its last command from then on and the laboratory reports
///   the reason.

#include <random>
#include <string>

#include "host_sim/rths/lab_plant.hpp"
#include "host_sim/rths/state_space.hpp"

namespace mrd::rths {

struct LaboratorySpec {
  double converter_range_v = 3.8;
  int converter_bits = 18;
  double displacement_full_scale_m = 0.038;  ///< ±3.8 V ↔ ±38 mm (10 mm/V)
  double force_full_scale_n = 8.9e3;         ///< ±3.8 V ↔ ±8.9 kN, the actuator's limit
  double displacement_noise_power_m2_hz = 6.25e-14;
  double force_noise_power_n2_hz = 1.16e-3;
  double force_limit_n = 8.9e3;
  double tracking_limit_m = 0.01;  ///< stop beyond 10 mm of tracking error
  std::uint64_t noise_seed = 1;
};

/// Why the laboratory stopped (kNone: it did not).
enum class LabStop { kNone, kForceLimit, kTrackingLimit, kNotFinite };
const char* lab_stop_name(LabStop s);

/// One sample of the laboratory's sensors, as the RTHS loop reads them.
struct LabMeasurement {
  double displacement_m = 0.0;
  double force_n = 0.0;
};

class Laboratory {
 public:
  Laboratory(const LabPlantParams& plant, const LaboratorySpec& spec, double dt_s);

  /// Quantizes `value` to the converter of full scale `full_scale`: clipped to
  /// ±full_scale, rounded to the nearest of 2^bits levels over the span.
  static double quantize(double value, double full_scale, double range_v, int bits);

  /// The sensors now (noise and quantization), without advancing.
  LabMeasurement measure();
  /// Sends `command_m` (through the DAC) and advances one step; `target_m`
  /// is used only for the tracking stop. Once stopped, the command is held.
  void step(double command_m, double target_m);

  LabStop stopped() const noexcept { return stop_; }
  /// The true (noise-free) displacement and force, for the report.
  double true_displacement_m() const;
  double true_force_n() const;
  double peak_force_n() const noexcept { return peak_force_n_; }

 private:
  LaboratorySpec spec_;
  DiscreteSystem sys_;
  Vector z_, z_next_;
  double held_command_m_ = 0.0;
  LabStop stop_ = LabStop::kNone;
  double peak_force_n_ = 0.0;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  double sigma_x_m_;
  double sigma_f_n_;
};

}  // namespace mrd::rths
