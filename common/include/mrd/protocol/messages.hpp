#pragma once
/// The messages of the mrd CAN protocol, one struct per message, in SI units.
/// The byte layout, scaling, ranges, rates and timeouts are specified in
/// common/protocol/CAN_PROTOCOL.md and mirrored in common/protocol/mrd.dbc;
/// codec.hpp is the only code that packs or unpacks them.
///
/// Identifier layout (11-bit, CAN 2.0A): id = msg_id << 4 | sender node id.
/// Lower message ids win arbitration, so the current command goes first.

#include <cstdint>

#include "mrd/control/io.hpp"

namespace mrd::protocol {

/// Message ids (bits 10..4 of the CAN id).
enum class MsgId : std::uint8_t {
  kCurrentCommand = 0x01,    ///< controller → drive, every control tick
  kDriveStatus = 0x02,       ///< drive → controller, every control tick
  kDaqMotion = 0x03,         ///< DAQ → controller: damper stroke and force
  kDaqAccel = 0x04,          ///< DAQ → controller: ground and base acceleration
  kMixingCommand = 0x05,     ///< controller → mixing actuator
  kMixingStatus = 0x06,      ///< mixing actuator → controller
  kControllerStatus = 0x07,  ///< controller heartbeat
  kIdleStatus = 0x08,        ///< controller → all: idle-time estimate and mixing scheduler, with the heartbeat
  // RTHS (real-time hybrid simulation, host_sim/rths_board): the runtime on the
  // board and the laboratory; their structs and codec are in rths_frames.hpp.
  kRthsCommand = 0x10,       ///< RTHS runtime → laboratory: actuator command and target, every loop tick
  kRthsMeasurement = 0x11,   ///< RTHS laboratory → runtime: measured displacement and force, after each command
  kRthsLabStatus = 0x12,     ///< RTHS laboratory → runtime: state, stop reason and step rate
  kRthsRunStatus = 0x13,     ///< RTHS runtime → laboratory: how the run ended and its ticks
  kSimCoilState = 0x70,      ///< simulation only: plant → drive, coil current
  kSimCoilDrive = 0x71,      ///< simulation only: drive → plant, current the drive applies
};

/// Node ids (bits 3..0 of the CAN id): the sender. 0 is never a valid sender.
struct NodeIds {
  std::uint8_t controller = 1;
  std::uint8_t drive = 2;
  std::uint8_t daq = 3;
  std::uint8_t actuator = 4;
};

inline constexpr std::uint8_t kMaxNodeId = 15;
/// Every frame of the protocol is 8 bytes; byte 6 is a rolling counter and
/// byte 7 a CRC-8 over the identifier and bytes 0..6.
inline constexpr std::uint8_t kFrameDlc = 8;

constexpr std::uint32_t can_id(MsgId m, std::uint8_t node) noexcept {
  return (static_cast<std::uint32_t>(m) << 4) | (node & 0x0Fu);
}
constexpr std::uint8_t node_of(std::uint32_t id) noexcept { return static_cast<std::uint8_t>(id & 0x0Fu); }
constexpr std::uint8_t msg_of(std::uint32_t id) noexcept { return static_cast<std::uint8_t>((id >> 4) & 0x7Fu); }

/// Current command to the PWM drive (§3.2: ±10 V at 1 V/A → ±10 A).
struct CurrentCommand {
  float current_a = 0.0f;  ///< coil current set point, A, [−10, 10], 1 mA resolution
  bool enable = false;     ///< drive output stage enabled
  control::ControlMode mode = control::ControlMode::kPassiveOff;  ///< informative
  std::uint8_t counter = 0;
};

/// Drive states reported in DriveStatus.
enum class DriveState : std::uint8_t {
  kDisabled = 0,  ///< output off: enable low or commanded off
  kFollowing = 1, ///< regulating to the last valid command
  kSafe = 2,      ///< no valid command within the timeout: safe current
  kFault = 3,     ///< output off because of a drive fault
};

/// Fault bits of DriveStatus.faults.
namespace drive_fault {
inline constexpr std::uint8_t kOverCurrent = 0x01;      ///< |measured| above the 30 A peak rating
inline constexpr std::uint8_t kOverTemperature = 0x02;
inline constexpr std::uint8_t kUnderVoltage = 0x04;
inline constexpr std::uint8_t kCommandTimeout = 0x08;   ///< safe current active
inline constexpr std::uint8_t kCommandRejected = 0x10;  ///< a bad command frame since the last status
inline constexpr std::uint8_t kFaultLine = 0x20;        ///< the fault output line is asserted
inline constexpr std::uint8_t kAll = 0x3F;
}  // namespace drive_fault

struct DriveStatus {
  float measured_current_a = 0.0f;  ///< coil current, A, [−30, 30]
  float setpoint_a = 0.0f;          ///< current the drive regulates to now, A, [−30, 30]
  std::uint8_t faults = 0;          ///< drive_fault bits
  DriveState state = DriveState::kDisabled;
  std::uint8_t counter = 0;
};

/// Damper stroke and load-cell force, sampled together.
struct DaqMotion {
  float damper_disp_m = 0.0f;   ///< base relative to ground, m, [−0.5, 0.5], 0.1 µm resolution
  bool disp_valid = true;       ///< false is sent as the "not available" code
  float damper_force_n = 0.0f;  ///< N, positive resisting positive velocity, [−800e3, 800e3], 0.1 N
  bool force_valid = true;
  std::uint8_t counter = 0;
};

/// Ground and absolute base acceleration, sampled with DaqMotion.
struct DaqAccel {
  float ground_accel_m_s2 = 0.0f;  ///< m/s², [−80, 80], 1e-5 m/s² resolution
  bool ground_valid = true;
  float base_accel_m_s2 = 0.0f;    ///< absolute, m/s², [−80, 80]
  bool base_valid = true;
  std::uint8_t counter = 0;
};

enum class MixingAction : std::uint8_t { kStop = 0, kStart = 1 };

/// Request to the mixing actuator (thesis: ±76.2 mm at 0.2 Hz).
struct MixingCommand {
  MixingAction action = MixingAction::kStop;
  float amplitude_m = 0.0f;   ///< [0, 0.2] m, 0.01 mm resolution
  float frequency_hz = 0.0f;  ///< [0, 2.0] Hz, 0.01 Hz resolution
  float duration_s = 0.0f;    ///< [0, 7200] s, 1 s resolution
  std::uint8_t counter = 0;
};

enum class MixingState : std::uint8_t { kIdle = 0, kRunning = 1, kDone = 2, kAborted = 3, kFault = 4 };

namespace mixing_fault {
inline constexpr std::uint8_t kStrokeLimit = 0x01;   ///< request beyond the actuator's stroke
inline constexpr std::uint8_t kVelocityLimit = 0x02; ///< request beyond the actuator's velocity
inline constexpr std::uint8_t kCommandTimeout = 0x04;
inline constexpr std::uint8_t kAll = 0x07;
}  // namespace mixing_fault

struct MixingStatus {
  MixingState state = MixingState::kIdle;
  float elapsed_s = 0.0f;      ///< time in the present cycle, s, [0, 65535], 1 s
  float amplitude_m = 0.0f;    ///< measured stroke amplitude, m, [0, 0.2], 0.01 mm
  std::uint8_t faults = 0;     ///< mixing_fault bits
  std::uint8_t counter = 0;
};

/// Flag bits of ControllerStatus.flags.
namespace controller_flag {
inline constexpr std::uint8_t kDriveEnabled = 0x01;
inline constexpr std::uint8_t kSensorTimeout = 0x02;   ///< DAQ frames missing: safe current
inline constexpr std::uint8_t kDriveFault = 0x04;      ///< fault line or drive fault bits
inline constexpr std::uint8_t kDriveSilent = 0x08;     ///< no DriveStatus within the timeout
inline constexpr std::uint8_t kBusError = 0x10;        ///< bus passive or off since the last heartbeat
inline constexpr std::uint8_t kMaintenanceDue = 0x20;
inline constexpr std::uint8_t kAll = 0x3F;
}  // namespace controller_flag

/// Controller heartbeat.
struct ControllerStatus {
  control::ControlMode mode = control::ControlMode::kPassiveOff;
  std::uint8_t flags = 0;            ///< controller_flag bits
  std::uint16_t overruns = 0;        ///< control periods missed since start (saturates)
  std::uint16_t rejected_frames = 0; ///< frames dropped by the codec since start (saturates)
  std::uint8_t counter = 0;
};

/// States of the mixing scheduler as IdleStatus carries them (the values of
/// fw::SchedulerState, firmware/core/mixing_scheduler.hpp).
namespace scheduler_state {
inline constexpr std::uint8_t kIdle = 0;
inline constexpr std::uint8_t kDue = 1;
inline constexpr std::uint8_t kRequested = 2;
inline constexpr std::uint8_t kRunning = 3;
inline constexpr std::uint8_t kConfirmed = 4;
inline constexpr std::uint8_t kAborted = 5;
inline constexpr std::uint8_t kMaintenanceRequired = 6;
}  // namespace scheduler_state

/// Flag bits of IdleStatus.flags.
namespace idle_flag {
inline constexpr std::uint8_t kAssumedSettled = 0x01;  ///< no usable record or clock at boot: worst case assumed
inline constexpr std::uint8_t kClockInvalid = 0x02;    ///< no valid real-time clock at boot or a backward jump
inline constexpr std::uint8_t kSaveFailed = 0x04;      ///< the last save of the state failed
inline constexpr std::uint8_t kAll = 0x07;
}  // namespace idle_flag

/// The idle-time estimator and the mixing scheduler, sent with the
/// heartbeat when the controller runs them.
struct IdleStatus {
  std::uint32_t equivalent_idle_h = 0;  ///< equivalent idle time τ (Eq. 5.5), h, [0, 16777215]
  float participant_ratio = 1.0f;       ///< PR (Eq. 5.9), [0, 1], 0.004 resolution
  float capacity_fraction = 1.0f;       ///< force capacity relative to fully mixed, [0, 1], 0.004
  std::uint8_t scheduler = scheduler_state::kIdle;  ///< scheduler_state value, 0–6
  std::uint8_t flags = 0;               ///< idle_flag bits
  std::uint8_t counter = 0;
};

/// Simulation only: the coil current of the simulated damper, the drive's
/// current sensor. In lockstep the counter is the plant tick modulo 256.
struct SimCoilState {
  float coil_current_a = 0.0f;  ///< A, [−30, 30], 10 µA resolution
  std::uint8_t counter = 0;
};

/// Simulation only: the current the drive applies to the coil over the tick
/// named by the counter (what a PWM stage would drive into the coil).
struct SimCoilDrive {
  float applied_current_a = 0.0f;  ///< A, [−30, 30], 1 mA resolution (as the command)
  bool output_on = false;
  std::uint8_t counter = 0;
};

}  // namespace mrd::protocol
