#pragma once
/// Physical ranges of a current drive's quantities (§3.2): what a drive file
/// (drive_file.hpp) may hold, each with the reason for its ends.

#include "host_sim/discrepancy/physical_ranges.hpp"

namespace mrd::drive {

using discrepancy::PhysicalRange;

/// The DC bus: from 1 V, below any coil drive's, to 1 kV, the top of
/// industrial DC buses (the thesis's 72 V, §3.2).
inline constexpr PhysicalRange kBusVoltageRange{1.0, 1000.0, "V", "a voltage"};
/// The command input's range, ±V: from 0.1 V to 100 V, ten times the ±10 V
/// of analog servo inputs (the thesis's ±10 V, §3.2).
inline constexpr PhysicalRange kCommandRangeVoltageRange{0.1, 100.0, "V", "a voltage"};
/// The command scale: from 1 mV/A to 1 kV/A (the thesis's 1 V/A, §3.2).
inline constexpr PhysicalRange kCommandScaleRange{1e-3, 1e3, "V/A", "a command scale"};
/// The continuous and peak currents: from 1 mA to 1 kA (the thesis's 15 A
/// and 30 A, §3.2; MR damper coils take 0.5–5 A).
inline constexpr PhysicalRange kDriveCurrentRange{1e-3, 1e3, "A", "a current"};
/// The time the I²t budget allows at the peak current: from 0 (no time above
/// the continuous current) to an hour (the thesis drive's 2 s, an assumption).
inline constexpr PhysicalRange kPeakTimeRange{0.0, 3600.0, "s", "a time"};
/// The current loop's bandwidth ω_c: from 1 rad/s, slower than any coil, to
/// 1e6 rad/s, beyond any PWM drive's (the thesis drive's 200 rad/s).
inline constexpr PhysicalRange kLoopBandwidthRange{1.0, 1e6, "rad/s", "a bandwidth"};
/// The current loop's period: from 0.1 µs (a 10 MHz loop, beyond any PWM
/// drive's) to 10 ms, ten times the control step (the thesis drive's 0.1 ms).
inline constexpr PhysicalRange kLoopPeriodRange{1e-7, 1e-2, "s", "a time"};

/// The sampled current loop moves the coil current by K_p·T/L of its error
/// per period (K_p = L(1 A) ω_c); above 1 it overshoots and rings, and the
/// simulated drive would not be the drive the file describes. The thesis
/// drive's is 0.2 at the coil's saturated floor (pwm_drive.hpp).
inline constexpr double kMaxLoopStepGain = 1.0;

}  // namespace mrd::drive
