#pragma once
/// The sensors of the test rig (§3.2), sampled once per control tick (1 kHz):
/// the actuator's internal LVDT (stroke), the MTS load cell (force) and the
/// drive's coil-current monitor. Each reading is
///
/// <pre>
///   value + offset + white Gaussian noise → quantized to span / 2^bits → saturated at ±range → float
/// </pre>
///
/// with span = 2 · range. The accelerometers stay ideal. The noise comes
/// from one seeded generator: the same seed gives the same readings.

#include <cstdint>
#include <random>

#include "host_sim/plant/stages.hpp"

namespace mrd::plant {

/// One converter channel.
struct SensorChannel {
  double range = 1.0;      ///< full scale, ± in the channel's unit
  int bits = 16;           ///< converter resolution over the span 2·range
  double noise_rms = 0.0;  ///< white noise, RMS, channel's unit
  double offset = 0.0;     ///< added to every reading, channel's unit

  /// Quantization step: span / 2^bits.
  double step() const noexcept;
  /// value → quantized → saturated at ±range (noise and offset already added).
  double convert(double value) const noexcept;
};

/// Defaults of the rig's sensors (units in the names of the fields they set).
struct HardwareSensorSpec {
  /// LVDT: stroke 0.5842 m (±0.2921 m, Table 3.1), 16 bit → 8.9 µm; 2 µm RMS noise.
  double lvdt_range_m = 0.2921;
  int lvdt_bits = 16;
  double lvdt_noise_rms_m = 2.0e-6;
  double lvdt_offset_m = 0.0;
  /// Load cell: ±250 kN, 16 bit → 7.6 N; 0.1 % of range = 250 N RMS noise.
  double load_cell_range_n = 250.0e3;
  int load_cell_bits = 16;
  double load_cell_noise_rms_n = 250.0;
  double load_cell_offset_n = 0.0;
  /// Coil current: ±15 A (the drive's continuous rating), 12 bit → 7.3 mA; 5 mA RMS noise.
  double current_range_a = 15.0;
  int current_bits = 12;
  double current_noise_rms_a = 5.0e-3;
  double current_offset_a = 0.0;
  std::uint64_t seed = 1;  ///< of the noise generator
};

class HardwareSensors {
 public:
  HardwareSensors() = default;
  explicit HardwareSensors(const HardwareSensorSpec& s) { init(s); }

  void init(const HardwareSensorSpec& s);

  /// What the rig measures of `s` (stroke includes `stroke_offset_m`, the
  /// position the damper is parked at).
  PlantSensors measure(const PlantState& s, double stroke_offset_m = 0.0);

  const SensorChannel& lvdt() const noexcept { return lvdt_; }
  const SensorChannel& load_cell() const noexcept { return load_cell_; }
  const SensorChannel& current() const noexcept { return current_; }

 private:
  SensorChannel lvdt_{}, load_cell_{}, current_{};
  std::mt19937_64 rng_{};
  std::normal_distribution<double> unit_{0.0, 1.0};

  double read(const SensorChannel& c, double value);
};

}  // namespace mrd::plant
