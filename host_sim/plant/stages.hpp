#pragma once
/// What passes between the plant and the devices around it, and the two
/// stages where those devices act on it:
///
/// - the sensor stage turns the plant's state at t_n into what the DAQ
///   (stroke, force, accelerations) and the drive (coil current) measure;
/// - the command stage turns the drive's output into the coil drive the
///   damper sees over the step.
///
/// Both stages here are ideal: the thesis plant's. The hardware plant
/// replaces them with the rig's sensors (hardware_sensors.hpp) and its PWM
/// drive and coil (pwm_drive.hpp, coil.hpp).

namespace mrd::plant {

/// The plant at t_n, in double: what sense() took for the tick.
struct PlantState {
  double ground_accel_m_s2 = 0.0;  ///< ground acceleration, held over the step, m/s²
  double base_disp_m = 0.0;        ///< damper stroke: base relative to the ground, m
  double base_vel_m_s = 0.0;       ///< base velocity relative to the ground, m/s
  double damper_force_n = 0.0;     ///< damper force, positive resisting a positive velocity, N
  double base_accel_m_s2 = 0.0;    ///< absolute base acceleration, m/s²
  double coil_current_a = 0.0;     ///< coil current, A
  double participant_ratio = 0.0;  ///< participant ratio PR (Eq. 5.9), fraction
};

/// One tick's sensor values, as floats (what the DAQ and the drive measure).
struct PlantSensors {
  float damper_disp_m = 0.0f;
  float damper_force_n = 0.0f;
  float ground_accel_m_s2 = 0.0f;
  float base_accel_m_s2 = 0.0f;
  float coil_current_a = 0.0f;
};

/// The drive's output over one step.
struct CoilDrive {
  double current_a = 0.0;  ///< current the drive delivers while its output is on, A
  bool output_on = false;  ///< false: the output stage is off
};

/// Sensor stage. Ideal sensors: each value rounded to float, the type the
/// CAN frames and the controller carry.
inline PlantSensors sensor_stage(const PlantState& s) noexcept {
  PlantSensors out;
  out.damper_disp_m = static_cast<float>(s.base_disp_m);
  out.damper_force_n = static_cast<float>(s.damper_force_n);
  out.ground_accel_m_s2 = static_cast<float>(s.ground_accel_m_s2);
  out.base_accel_m_s2 = static_cast<float>(s.base_accel_m_s2);
  out.coil_current_a = static_cast<float>(s.coil_current_a);
  return out;
}

/// Command stage: the current command u[n] the coil follows over the step
/// (Eq. 4.5), A. Ideal drive: the drive's current while its output is on,
/// 0 A while it is off.
inline double command_stage_a(const CoilDrive& d) noexcept { return d.output_on ? d.current_a : 0.0; }

}  // namespace mrd::plant
