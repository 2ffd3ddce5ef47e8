#pragma once
/// The damper on its test rig in continuous time, with any set of physical
/// effects, integrated on a fine time grid (the record's rate times an
/// oversampling factor): coil current (Eq. 4.5) exact for a command that
/// steps at any instant, rod motion through free play (hard or smooth) or a
/// series compliance, displaced volume and participant ratio (chapter 5),
/// fluid temperature, the fluid column's inertia, and the force channel
/// (offset, low-pass, delay).

#include <cstddef>
#include <vector>

#include "signals.hpp"

namespace indep {

/// Every effect's parameters; each default is the value at which the effect
/// is absent.
struct EffectParams {
  // idle_settling: settling quotient of Eq. 5.5 as a fraction (0 = fully mixed).
  double settling_quotient = 0.0;
  // idle_settling's second form (> 0): a settled layer that remixes fully,
  // PR = 1 − (1 − a_PR(SQ)) e^(−V / V_r) with its own recovery volume V_r, L,
  // instead of Eq. 5.9's PR = b_PR + (a_PR − b_PR) e^(−c_PR V) (which keeps a
  // lasting deficit 1 − b_PR and recovers at c_PR(SQ)).
  double settling_recovery_l = 0.0;
  // backlash: total free play between actuator and rod, m; a contact length
  // > 0 makes the engagement smooth (tanh of the penetration over it), given
  // as a fraction of the free play. The rod starts against the side the
  // actuator first moves towards.
  double free_play_m = 0.0;
  double contact_fraction = 0.0;
  // backlash with impact stiffness (> 0, hard play only): at the end of the
  // play the actuator pushes the rod through a contact spring of this
  // stiffness, N/m (a rubber or polymer pad, a bolt in bending).
  double contact_stiffness_n_m = 0.0;
  // gas_spring: F += F_p + k x (1 + ε x²), x the rod's displacement, F_p the
  // accumulator's preload (gas pressure on the rod's area at x = 0).
  double gas_stiffness_n_m = 0.0;
  double gas_nonlinearity_per_m2 = 0.0;
  double gas_preload_n = 0.0;
  // thermal_fade: ΔT from dissipated power into heat capacity C, cooling with
  // time constant τ_cool (0 = adiabatic); yield and viscosity multiplied by
  // 1 − α ΔT (linear) or exp(−α ΔT) (exponential).
  double fade_yield_per_k = 0.0;
  double fade_viscous_per_k = 0.0;
  bool fade_exponential = false;
  double heat_capacity_j_per_k = 60.0e3;
  double cooling_time_s = 0.0;
  // time_delay: the force channel lags by this much, s; in its second form
  // behind a first-order anti-alias filter of the acquisition (time constant, s).
  double force_delay_s = 0.0;
  double delay_filter_s = 0.0;
  // coil_lag: both time constants of Eq. 4.5 multiplied by this; with
  // coil_single_lag, one first-order lag (an L/R coil) of time constant
  // kCoilMeanTau_s times this instead (Eq. 4.5's mean delay ½·0.7 + ½·0.03 s).
  double coil_tau_scale = 1.0;
  bool coil_single_lag = false;
  // force_offset: load-cell zero, N.
  double force_offset_n = 0.0;
  // direction_asymmetry: the damper's force multiplied by 1 + a while
  // extending (rod velocity > 0) and by 1 − a while compressing, about the
  // damper's mean characteristic.
  double asymmetry = 0.0;
  // Outside the workflow's catalogue:
  /// > 0: F = tanh(v / v0)(f_c sgn v + c_0 v) instead of Eq. 4.4's transition function.
  double tanh_velocity_m_s = 0.0;
  /// First-order low-pass of the force channel (anti-alias filter), time constant, s.
  double force_filter_s = 0.0;
  /// Series compliance of the fluid column between actuator and piston:
  /// spring (0 = rigid) in parallel with a dashpot.
  double series_stiffness_n_m = 0.0;
  double series_damping_n_s_m = 0.0;
  /// Inertia of the fluid column: F += m a_rod. The fluid in the valve's gap
  /// moves (A_p / A_gap) times faster than the piston, so the effective mass
  /// is ρ L_gap A_p² / A_gap, kg.
  double fluid_mass_kg = 0.0;
};

/// What the rig does over one run.
struct Scenario {
  Motion motion;
  CurrentProgram current;
  EffectParams effects;
  double duration_s = 20.0;
  double rate_hz = 1000.0;
  int oversample = 10;
};

/// The run on the fine grid t_j = j h, j = 0 … n−1, covering the duration
/// plus one output step. With Channels::force_only, only force_channel_n is
/// filled and the other channels stay empty.
struct FineRun {
  double step_s = 0.0;
  std::vector<double> force_channel_n;  ///< what the load cell sees, before the delay
  std::vector<double> coil_current_a;
  std::vector<double> rod_disp_m;
  std::vector<double> rod_vel_m_s;
  std::vector<double> participant_ratio;
  std::vector<double> temperature_rise_k;
};

/// Which channels a run keeps. A record needs only the force channel; the
/// states are kept for the generator's own tests. Both integrate alike.
enum class Channels { all, force_only };

/// Integrates the scenario. Throws std::invalid_argument for a scenario out
/// of range (non-positive duration, rate or oversampling; free play together
/// with a series compliance).
[[nodiscard]] FineRun simulate(const Scenario& s, Channels channels = Channels::all);

/// The force channel at instants `t_s` (any, within the run), delayed by
/// `delay_s`, linearly interpolated between fine-grid points; before the run
/// starts, its first value. N.
[[nodiscard]] std::vector<double> sample_force(const FineRun& run, const std::vector<double>& t_s, double delay_s);

}  // namespace indep
