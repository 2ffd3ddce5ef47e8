#pragma once
/// The baseline damper model (baseline.hpp: the thesis's chapter-4 model or
/// a calibrated Bingham, Bouc–Wen or Spencer model) driven by a measured record, with
/// any set of catalogue effects added. Built for many evaluations of one
/// record: the coil current of Eq. 4.5 and the current-dependent laws are
/// computed once; an evaluation is one pass over the samples.
///
/// Per sample k (step dt_k = t_{k+1} − t_k, inputs held over the step):
/// <pre>
///   i[k+1]   = Eq. 4.5 (ZOH-exact, unity DC gain), τ's scaled by tau_scale   (coil_lag)
///              or one first-order lag, τ = lag_tau_scale (w_s τ_s + w_f τ_f)   (coil_lag, single_lag)
///              from the command; from a measured coil current i_m, only the
///              slow branch (the field lagging the current, as the hardware
///              plant's coil): i[k] = w_fast i_m[k] + w_slow slow[k]
///   x_d, v_d = actuator motion through a play operator of width free_play whose
///              last contact_share of the gap is a compliant stop (the rod takes
///              up the motion over that length), the engagement averaged over
///              ±3 ms                                                          (backlash)
///            = the same through a progressive stop: the rod's share of the actuator's
///              motion ½(1 + tanh((w − h)/ℓ)), w the actuator's position past the rod
///              toward the side, ℓ = engagement_share × free_play   (backlash, progressive)
///              (every form: the rod starts against the side of the play the actuator
///              first moves to, the play taken up by the motion before the record)
///            = the rod pushed through a contact spring at the end of the play:
///              F_Bingham(v_d) = dz(x̄_a − r − dt v_d) / s, backward Euler centred on the
///              sample (r the rod at t_k − dt/2, x̄_a the actuator at t_k + dt/2),
///              s = stop_deflection_m / force_scale   (backlash, impact_spring; the
///              rod's motion from the Bingham law whatever the baseline's form)
///   PR[k]    = b_PR + (a_PR − b_PR) exp(−c_PR ∫Q dt),  Eq. 5.6–5.9           (idle_settling)
///            = 1 − (1 − a_PR) exp(−∫Q dt / V_r), ∫Q dt in m³        (idle_settling, full_recovery)
///   φ_y, φ_v = 1 − α_y ΔT, 1 − α_v ΔT,  ΔT = E[k] / C                        (thermal_fade)
///   F_b[k]   = TF(v_d) (φ_y Y(i, PR) sgn v_d + φ_v C(i, PR) v_d),  Eq. 4.1–4.4, 5.10–5.12   (bingham)
///            = φ_y Y(i, PR) tanh(v_d / v_TF) + φ_v C(i, PR) v_d     (bingham, tanh transition)
///              with v_TF + τ|ā[k]| for TF's band, ā the actuator's acceleration
///              averaged over ±5 ms (the baseline's transition time τ, baseline.hpp)
///            = φ_y Y(i, PR) z[k] + φ_v C(i, PR) v_d + k_0 x_d,  z[k+1] = bouc_wen_step   (bouc_wen)
///            = c_1 ẏ[k] + k_1 (x_d − x_0), Eq. (8)–(10) of Spencer et al. (1997) with α ×φ_y,
///              c_0, c_1 ×φ_v at (i, PR); (y, z)[k+1] = spencer_state_after   (spencer;
///              y starts at x_d[0], z at 0; a preyield_hysteresis effect leaves it as it is)
///   F_b[k]  ×= (1 − r) + r e_lm[k]   (the baseline's lost motion, width λ Y(i) on x_d, baseline.hpp)
///   F_b[k]  ×= 1 + a sgn v_d                                                   (direction_asymmetry)
///   F_b[k]   = the above at u[k] = v_d[k] − (F_b[k] − F_b[k−1]) k_s⁻¹ / dt_{k−1}, solved for F_b[k]
///              from k = 1 on (the baseline's series compliance 1/k_s, bingham; baseline.hpp)
///   F_b: the bouc_wen form with x_y fitted, on either baseline              (preyield_hysteresis)
///   F[k]     = F_b[k] + k_gas x_d[k] + F_0                                   (gas_spring, force_offset)
///   E[k+1]   = E[k] + F_b[k] v_d[k] dt_k;   ∫Q += |v_d| A dt_k
///   F_meas(t) = F(t − τ − τ_b)   (linear interpolation; before the record, F[0])   (time_delay;
///              τ_b: the baseline's force_delay_s)
/// </pre>
/// Without effects and with the thesis baseline this is
/// damper_force_n(Table 4.1, i[k], v[k]) with PR = 1.

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "host_sim/discrepancy/baseline.hpp"
#include "host_sim/discrepancy/effects.hpp"
#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/motion_timescale.hpp"

namespace mrd::discrepancy {

/// What drives the model: time, actuator motion and commanded current.
struct ModelInput {
  std::vector<double> time_s;
  std::vector<double> disp_m;   ///< actuator displacement (smoothed when measured)
  std::vector<double> vel_m_s;  ///< actuator velocity (derived when not measured)
  std::vector<double> current_cmd_a;
  bool velocity_derived = false;
  /// |ā|: the actuator's acceleration (central difference of vel_m_s)
  /// averaged over ±kTransitionAccelHalfWindow_s, m/s², for the baseline's
  /// transition time. Filled once per record by model_input(); a
  /// DamperModel fills it when it is empty and its baseline needs it.
  std::vector<double> accel_abs_m_s2;
  /// The record's measured coil current, A (MeasuredData::current_a); empty when none.
  std::vector<double> current_meas_a;
};

/// Half width of the averaging of the backlash engagement (contact
/// compliance): 3 ms.
inline constexpr double kContactHalfWindow_s = 0.003;

/// Model input from a measured record: displacement smoothed and velocity
/// derived by smooth_motion() unless the record has a velocity column, over
/// ±smoothing_half_window_s or less when the record moves faster
/// (smoothing_half_window_for, motion_timescale.hpp).
[[nodiscard]] ModelInput model_input(const MeasuredData& data,
                                     double smoothing_half_window_s = kDefaultSmoothingHalfWindow_s);

/// A current law's exponential e = exp(−rate·|i|^q) at every sample of a
/// coil current (Eq. 4.2–4.3; Eq. 5.10–5.11 are Y = Y_a e + PR Y_b (1 − e)),
/// and the rate and exponent it was computed for (NaN: none).
struct CurrentLawExps {
  std::vector<double> e;
  double rate_per_a = std::numeric_limits<double>::quiet_NaN();
  double current_exponent = std::numeric_limits<double>::quiet_NaN();
  /// For another current: the next law_exps() recomputes `e` in its buffer.
  void forget() noexcept { rate_per_a = std::numeric_limits<double>::quiet_NaN(); }
};

/// Scratch space for one thread's evaluations.
struct ModelWorkspace {
  std::vector<double> current_a, disp_m, vel_m_s, engaged, force_n;
  CurrentLawExps e_y, e_c;  ///< the yield and viscous laws' exponentials of current_a (a coil_lag's current)
  std::vector<double> lm_half_gap, lm_driven, lm_engaged, lm_factor;  ///< the baseline's lost motion
};

class DamperModel {
 public:
  explicit DamperModel(ModelInput input, Baseline baseline = thesis_baseline());

  [[nodiscard]] const ModelInput& input() const noexcept { return in_; }
  [[nodiscard]] std::size_t size() const noexcept { return in_.time_s.size(); }
  [[nodiscard]] const Baseline& baseline() const noexcept { return p_; }
  /// Puts the model on another baseline, as if constructed with it: the
  /// coil current is recomputed only when the coil's constants changed (a
  /// fit that varies the laws evaluates many baselines on the same record).
  void set_baseline(Baseline baseline);
  /// force_scale_n() of the baseline over that of the thesis damper: the
  /// factor on the effects' force-valued bounds.
  [[nodiscard]] double force_ratio() const noexcept { return force_ratio_; }
  /// What the effects' bounds depend on: force_ratio() and whether the coil was identified.
  [[nodiscard]] ParamScale param_scale() const noexcept { return {force_ratio_, p_.coil_identified}; }
  /// Coil current of Eq. 4.5 from the commanded current, A.
  [[nodiscard]] const std::vector<double>& baseline_current_a() const noexcept { return base_current_a_; }

  /// Force at every sample, N. `params` holds the physical parameters of
  /// `set` packed in its order (EffectSet::offset). Values slightly outside
  /// the bounds are evaluated (finite differences step there): negative gaps,
  /// delays and fade coefficients act as zero, tau_scale below 1 as faster.
  void simulate(const EffectSet& set, std::span<const double> params, ModelWorkspace& ws,
                std::vector<double>& force_n) const;

  /// Force at the samples `index` only (ascending), N.
  void simulate_at(const EffectSet& set, std::span<const double> params, ModelWorkspace& ws,
                   std::span<const std::size_t> index, std::span<double> force_n) const;

  /// Coil current with both time constants of Eq. 4.5 scaled by `tau_scale`.
  void coil_current(double tau_scale, std::vector<double>& current_a) const;
  /// Coil current through one first-order lag of time constant `tau_s`
  /// (coil_lag's single_lag form), ZOH-exact, steady at the first input.
  void single_lag_current(double tau_s, std::vector<double>& current_a) const;
  /// Eq. 4.5's mean delay, (w_s τ_s + w_f τ_f)/(w_s + w_f), s: the unit of
  /// the single lag's time constant.
  [[nodiscard]] double coil_mean_delay_s() const noexcept;

 private:
  /// Fills ws.force_n with F[k] before any delay.
  void raw_force(const EffectSet& set, std::span<const double> params, ModelWorkspace& ws) const;
  /// Fills ws.disp_m and ws.vel_m_s with the rod's motion when the mounting
  /// has a free play of ±half_gap_m (backlash) whose last contact_share of
  /// the gap is a compliant stop; uses ws.engaged.
  /// `progressive`: a stop that engages progressively over contact_share of the whole play (backlash's
  /// progressive form) instead.
  void backlash_motion(double half_gap_m, double contact_share, ModelWorkspace& ws, bool progressive) const;
  /// `law`'s exponentials at every sample of `current_a` into `exps`,
  /// unless `exps` already holds them for the law's rate and exponent (the
  /// caller calls exps.forget() when the current changes).
  static void law_exps(const std::vector<double>& current_a, const CurrentLaw& law, CurrentLawExps& exps);

  ModelInput in_;
  double play_start_side_ = 0.0;  ///< +1, −1 or 0: the side of a mounting's play the rod starts against
  Baseline p_;
  double force_ratio_ = 1.0;
  std::vector<double> step_s_;  ///< dt_k; the last entry repeats the one before
  bool uniform_ = false;
  std::vector<double> base_current_a_;
  CurrentLawExps base_e_y_, base_e_c_;  ///< the yield and viscous laws' exponentials of base_current_a_
};

/// `force_n` (sampled at `time_s`) delayed by `delay_s` at the samples
/// `index` (ascending): linear interpolation, the first value before the
/// record, the last after it. A delay of 0 copies.
void delay_force(std::span<const double> time_s, std::span<const double> force_n, double delay_s,
                 std::span<const std::size_t> index, std::span<double> out);

/// Normalized RMS of a − b over the samples: sqrt(Σ(a−b)² / Σ a²).
[[nodiscard]] double normalized_rms_gap(std::span<const double> measured, std::span<const double> model);

/// Samples [begin, end) of a record.
struct SampleRange {
  std::size_t begin = 0;
  std::size_t end = 0;
  [[nodiscard]] std::size_t size() const noexcept { return end - begin; }
};

/// Share of a record's peak |v| above which the actuator counts as moving.
inline constexpr double kMovingShare = 0.02;

/// The samples over which the actuator moves: from the first to the last
/// sample whose |v| exceeds kMovingShare of the record's peak |v|, with the
/// reversals in between. A characterization record usually starts and ends
/// with the actuator standing (the lab records keep 0.5 s each side); there
/// the measured force is what the damper holds at standstill, set by the
/// motion before the record or the load cell's zero, not the damper's law,
/// and the fits and gaps leave those samples out. The whole record when
/// nothing moves.
[[nodiscard]] SampleRange moving_span(std::span<const double> vel_m_s);

}  // namespace mrd::discrepancy
