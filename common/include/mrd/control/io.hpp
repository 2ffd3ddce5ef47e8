#pragma once
/// The values that cross the boundary of the control core: what the board
/// (or the simulator, or a unit test) hands it every tick, and what it hands
/// back. Plain structs of SI floats and flags, no behaviour: the same
/// structs travel through the in-process simulator and, encoded, over CAN.

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string_view>

namespace mrd::control {

enum class ControlMode : std::uint8_t {
  kPassiveOff = 0,  ///< 0 A: the damper acts as a viscous damper
  kPassiveOn = 1,   ///< constant nominal current (2.5 A)
  kSemiActive = 2,  ///< causal RILD (Eq. 6.1) + ODBDCO (§6.3)
};

/// Sensor-validity and fault flags of one tick's input.
struct InputFlags {
  bool disp_valid = true;
  bool force_valid = true;
  bool ground_accel_valid = true;
  bool base_accel_valid = true;
  bool drive_fault = false;  ///< the drive's fault line is asserted
};

struct ControllerInput {
  std::uint64_t tick = 0;             ///< integer control ticks since start
  float damper_disp_m = 0.0f;         ///< damper stroke (base relative to ground), m
  float damper_force_n = 0.0f;        ///< load-cell force, N, positive resisting positive velocity
  float ground_accel_m_s2 = 0.0f;     ///< ground acceleration, m/s²
  float base_accel_m_s2 = 0.0f;       ///< absolute base acceleration, m/s²
  float coil_current_a = 0.0f;        ///< coil current measured by the drive, A
  InputFlags flags{};
};

struct ControllerOutput {
  float current_command_a = 0.0f;  ///< command to the PWM drive, A (negative = back-drive)
  bool drive_enable = true;        ///< drive-enable line
  float desired_force_n = 0.0f;    ///< what the control law asked for (0 in passive modes), N
};

/// Name used on the command line and in reports.
constexpr const char* mode_name(ControlMode m) noexcept {
  switch (m) {
    case ControlMode::kPassiveOff: return "passive-off";
    case ControlMode::kPassiveOn: return "passive-on";
    case ControlMode::kSemiActive: return "semi-active";
  }
  return "unknown";
}

/// The mode named `text` ("passive-off" | "passive-on" | "semi-active", as
/// mode_name() spells them), or nothing.
constexpr std::optional<ControlMode> parse_mode_name(std::string_view text) noexcept {
  for (ControlMode m : {ControlMode::kPassiveOff, ControlMode::kPassiveOn, ControlMode::kSemiActive}) {
    if (text == mode_name(m)) return m;
  }
  return std::nullopt;
}

}  // namespace mrd::control
