#pragma once
/// The PWM servo drive that feeds the coil (§3.2): a 72 V DC bus, 15 A
/// continuous and 30 A peak, commanded by ±10 V at 1 V/A. The PWM is
/// averaged (the output is the mean bridge voltage, no ripple).
///
/// Inside, a PI current loop on the measured coil current runs at the
/// substep (0.1 ms, a 10 kHz loop):
///
/// <pre>
///   i_ref = clamp(clamp(u_V, ±10 V) · 1 A/V, ±I_lim)
///   v     = clamp(K_p e + K_i ∫e, ±72 V),   e = i_ref − i
/// </pre>
///
/// K_p = L(1 A) ω_c = 1000 V/A and K_i = R ω_c = 960 V/(A s) with
/// ω_c = 200 rad/s: the zero cancels the coil's pole at R/L(1 A), so in the
/// linear range the loop is a first-order lag of 5 ms (K_p · 0.1 ms / L stays
/// ≤ 0.2 down to the coil's 0.5 H floor, so the sampled loop is well damped); a large step
/// saturates the bridge and the current slews at (72 V − R i)/L(i). The
/// integrator stops while the output is saturated in the direction of the
/// error (anti-windup); after a saturated rise it takes over the coil's R i
/// from the proportional term with K_p/K_i = 1.04 s (2.5 A: 12 mA left at
/// the end of the rise).
///
/// Current limit: I_lim is 30 A, folded back to 15 A by an I²t budget:
/// E += (i² − I_cont²) dt, E ≥ 0; once E reaches (I_peak² − I_cont²) · 2 s
/// (2 s at peak) I_lim is I_cont until E falls back below it.
///
/// With the output off, the bridge is open and the current freewheels
/// through the diodes into the bus (−72 V sgn i) until it reaches zero.

#include "host_sim/plant/coil.hpp"
#include "host_sim/plant/stages.hpp"

namespace mrd::plant {

struct PwmDriveParams {
  double bus_v = 72.0;                  ///< DC supply, V
  double peak_current_a = 30.0;         ///< A
  double continuous_current_a = 15.0;   ///< A
  double peak_time_s = 2.0;             ///< time at peak current the I²t budget allows, s (assumption)
  double command_limit_v = 10.0;        ///< command input range, ±V
  double volts_per_amp = 1.0;           ///< command scale, V/A
  double loop_bandwidth_rad_s = 200.0;  ///< ω_c of the current loop
  double substep_s = 1.0e-4;            ///< current-loop and integration step, s
};

class PwmDrive {
 public:
  PwmDrive() = default;
  PwmDrive(const PwmDriveParams& p, const CoilParams& coil) noexcept { init(p, coil); }

  void init(const PwmDriveParams& p, const CoilParams& coil) noexcept;

  /// Holds `drive` over `step_s` (a whole number of substeps, at least one)
  /// and returns the mean of i² over it, A².
  double step(const CoilDrive& drive, double step_s) noexcept;

  /// Current reference for a command of `command_a` (command voltage at
  /// 1 V/A, clamped to ±10 V, then to the present current limit), A.
  double reference_a(double command_a) const noexcept;

  double current_a() const noexcept { return coil_.current_a(); }
  double voltage_v() const noexcept { return voltage_v_; }
  double current_limit_a() const noexcept;
  double kp_v_a() const noexcept { return kp_v_a_; }
  double ki_v_as() const noexcept { return ki_v_as_; }
  const Coil& coil() const noexcept { return coil_; }

 private:
  PwmDriveParams p_{};
  Coil coil_{};
  double kp_v_a_ = 0.0;
  double ki_v_as_ = 0.0;
  double integral_v_ = 0.0;
  double voltage_v_ = 0.0;
  double i2t_a2s_ = 0.0;
  double i2t_budget_a2s_ = 0.0;

  void substep(const CoilDrive& drive, double dt_s) noexcept;
};

}  // namespace mrd::plant
