#pragma once
/// The damper model of the thesis as one discrete-time block: a force law
/// (the thesis's Bingham plastic with transition function, Eq. 4.1–4.4, or
/// one `mrd calibrate` fitted, damper_laws.hpp), participant ratio from idle
/// time and mixing (Eq. 5.5–5.12), and coil-current dynamics (Eq. 4.5, unity
/// DC gain). Pure, allocation-free, exception-free.
///
/// One step of period T, with the command u[n], the damper velocity v[n]
/// and its stroke x[n] held over the step:
/// <pre>
///   f_c[n], c_0[n] = f_c(|i[n]|, PR[n]), c_0(|i[n]|, PR[n])                      Eq. 5.10–5.11
///   F[n]      = TF(v[n]) · ( f_c[n] sgn v[n] + c_0[n] v[n] )                     kBingham: Eq. 4.4, 5.12
///             = f_c[n] tanh(v[n]/v_TF) + c_0[n] v[n]                            kBinghamTanh: baseline.hpp
///               (either bent by MrDamperParams::shape, bingham.hpp's LawShape)
///             = f_c[n] z[n] + c_0[n] v[n] + k_0 x[n]                            kBoucWen: baseline.hpp
///             = c_1 ẏ(y[n], z_s[n], x[n], v[n]) + k_1 (x[n] − x_0)               kSpencer: spencer_law.hpp
///   z[n]      = Z(z[n−1], x[n] − x[n−1]),  z = 0 at x = 0 on reset             bouc_wen_z_after
///   (y, z_s)[n+1] = RK4 of Eq. (9)–(10) from x[n] at v[n] over T,  0 on reset  spencer_state_after
///   i[n+1]    = CurrentDynamics(i[n], u[n])                                       Eq. 4.5 (ZOH-exact)
///   ∫Q[n+1]   = ∫Q[n] + |v[n]| · A · T                                             Eq. 5.9
///   PR[n+1]   = b_PR + (a_PR − b_PR) exp(−c_PR ∫Q[n+1] / unit)                     Eq. 5.9
/// </pre>
/// so the force at step n uses the coil current and participant ratio reached
/// at the start of that step, and the Bouc–Wen variable at the stroke x[n]
/// (exact at the samples for a stroke that does not reverse within a step:
/// z depends on the stroke path only). A caller that knows only the velocity
/// (step(u, v)) moves the stroke by v[n]·T after the force, as
/// discrepancy::DamperModel moves z by v·dt. The Bingham laws ignore the stroke.
///
/// kSpencer (Spencer et al. 1997's modified Bouc–Wen model) has its own
/// current laws (SpencerParams, evaluated at |i[n]| and PR[n]); Eq. 4.5's
/// coil with equal time constants τ is the paper's first-order filter
/// u̇ = −η (u − v) with η = 1/τ. Its state (y, z) is integrated from the
/// stroke x[n] at the velocity v[n] over the step (what
/// discrepancy::DamperModel does per sample), so the force at step n + 1
/// takes the state the motion reached. Its laws are polynomials fitted over
/// the records' currents (the laboratory's α turns negative at 1.3 A), so
/// above the rated current (rating.current_a) they are held at their value
/// there, as a field that saturates: the coil current itself is not limited.
///
/// A calibrated damper's shape (LawShape: current exponents, viscous
/// exponent, spring, transition time, lost motion) acts as in the
/// calibration (discrepancy::DamperModel), with two differences, both
/// because a causal model cannot look ahead:
///  - the transition time widens the band by τ|a| with a the damper's
///    acceleration over the last step, (v[n] − v[n−1])/T (v[−1] = 0 after a
///    reset), where the calibration averages a measured record's |a| over
///    ±5 ms to keep the derivative's noise out (a simulated velocity has none);
///  - the lost motion's engagement e[n] is, as in the calibration, the
///    play's engaged share (r[k+1] − r[k−1])/(x[k+1] − x[k−1]) clamped to
///    [0, 1] (r the play's driven side) averaged over the steps k within
///    ±kLostMotionHalfWindow_s of n (3 either side at 1 kHz), where the
///    strokes after x[n] are not known yet: they are extrapolated at the
///    last step's increment, x[n+j] = x[n] + j (x[n] − x[n−1]), so the
///    engagement is the calibration's for a motion that keeps its velocity
///    over the half window (3 ms; exact for a linear stroke).
/// The spring and the play act on the stroke x[n] (step(u, v) moves it by
/// v[n]·T); the play starts centred on the first step's stroke, as the
/// calibration's on a record's first sample. A series compliance
/// (series_compliance.hpp) solves each step's law force (its lost motion
/// included, the spring not) from the last step's, F[−1] = 0 after a reset
/// (the damper unloaded), as the calibration does from a record's second
/// sample on (its first takes the law at that velocity: a record starts at
/// rest).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "mrd/physics/bingham.hpp"
#include "mrd/physics/coil_heat.hpp"
#include "mrd/physics/current_dynamics.hpp"
#include "mrd/physics/damper_laws.hpp"
#include "mrd/physics/lost_motion_play.hpp"
#include "mrd/physics/participant_ratio.hpp"
#include "mrd/physics/series_compliance.hpp"
#include "mrd/physics/spencer_law.hpp"

namespace mrd::physics {

/// The force law of a damper file's [model] law (host_sim/damper): the
/// thesis's Bingham law, or one `mrd calibrate` fitted.
enum class ForceLaw : unsigned char {
  kBingham,      ///< Eq. 4.4: TF(v)·(f_c sgn v + c_0 v), TF = |v|/v_TF below v_TF, 1 above
  kBinghamTanh,  ///< f_c·tanh(v/v_TF) + c_0·v
  kBoucWen,      ///< f_c·z + c_0·v + k_0·x, z the normalized Bouc–Wen variable of width x_y
  kSpencer,      ///< Spencer et al. (1997)'s modified Bouc–Wen model with its own current laws
};

/// The law's name as a damper file and `mrd calibrate` spell it: "bingham",
/// "bingham_tanh", "bouc_wen", "spencer".
constexpr const char* force_law_name(ForceLaw law) noexcept {
  switch (law) {
    case ForceLaw::kBinghamTanh: return "bingham_tanh";
    case ForceLaw::kBoucWen: return "bouc_wen";
    case ForceLaw::kSpencer: return "spencer";
    case ForceLaw::kBingham: break;
  }
  return "bingham";
}

/// The Bouc–Wen law's two constants (ForceLaw::kBoucWen).
struct BoucWenDamperParams {
  double yield_disp_m = 0.0;   ///< x_y: the stroke over which z saturates, m
  double stiffness_n_m = 0.0;  ///< k_0: the accumulator's stiffness, N/m
};

/// What a damper is rated for (Table 3.1, §3.1, §6.4 for the thesis damper).
struct DamperRating {
  double current_a = 2.5;          ///< rated coil current: Table 4.1's laws span 0–2.5 A; §6.4's passive-on
  double force_n = 200.0e3;        ///< rated force, N (the 200 kN damper, §3.1)
  double stroke_m = 0.2921;        ///< ± stroke from the centre: half Table 3.1's 0.5842 m total
  double velocity_m_s = 0.2491;    ///< Table 3.1's maximum velocity
};

struct MrDamperParams {
  BinghamParams bingham{};
  CurrentDynamicsParams coil{};
  ParticipantRatioParams pr{};
  ForceLaw law = ForceLaw::kBingham;
  BoucWenDamperParams bouc_wen{};
  SpencerParams spencer{};  ///< ForceLaw::kSpencer: its model and current laws (SI)
  /// A calibrated damper's shape of the law (current exponents and lost
  /// motion: every law but kSpencer; the rest: kBingham and kBinghamTanh);
  /// the default bends nothing.
  LawShape shape{};
  DamperRating rating{};
  /// The coil's resistance and heating (the closed loop's coil temperature,
  /// the firmware's I²t time constant); not part of the force.
  CoilHeatParams coil_heat{};
  /// The coil's inductance L(i) (the hardware plant's drive works against it);
  /// not part of the force either.
  CoilInductance coil_inductance{};
};

class MrDamper {
 public:
  MrDamper() = default;
  MrDamper(const MrDamperParams& p, double period_s, double sq) noexcept { init(p, period_s, sq); }

  void init(const MrDamperParams& p, double period_s, double sq) noexcept {
    p_ = p;
    period_s_ = period_s;
    coil_.init(p.coil, period_s);
    pr_.init(p.pr, sq);
    z_ = 0.0;
    stroke_m_ = 0.0;
    last_velocity_m_s_ = 0.0;
    spencer_state_ = SpencerState{};
    law_force_n_ = 0.0;
    fluid_velocity_m_s_ = 0.0;
    const bool bingham = p.law == ForceLaw::kBingham || p.law == ForceLaw::kBinghamTanh;
    lost_ = p.law != ForceLaw::kSpencer && p.shape.has_lost_motion();
    series_ = bingham && p.shape.series_compliance_m_per_n > 0.0;
    bent_ = lost_ || series_ ||
            (bingham && (p.shape.has_viscous_exponent() || p.shape.stiffness_n_m != 0.0 ||
                         p.shape.transition_time_s != 0.0));
    play_.init(period_s);
    update_coefficients();
  }

  /// Starts an episode: settling quotient `sq` (0 fully mixed, 1 fully
  /// settled), a coil current already steady at `current_a`, and the damper
  /// at the centre of its stroke, unloaded (x = 0, z = 0).
  void reset(double sq, double current_a = 0.0) noexcept {
    pr_.reset(sq);
    coil_.reset(current_a);
    z_ = 0.0;
    stroke_m_ = 0.0;
    last_velocity_m_s_ = 0.0;
    spencer_state_ = SpencerState{};
    law_force_n_ = 0.0;
    fluid_velocity_m_s_ = 0.0;
    play_.reset();
    update_coefficients();
  }

  /// Damper force for velocity `velocity_m_s` at stroke `stroke_m` (m from
  /// the centre, positive with positive velocity) at the present coil current
  /// and participant ratio, without advancing the state. N, positive when
  /// resisting positive velocity. For kBingham the same value as
  /// damper_force_n(bingham, i, v, PR) (Eq. 4.4, 5.10–5.12), with f_c and
  /// c_0 evaluated once per step rather than per call; the Bingham laws
  /// ignore the stroke unless bent by a spring (shape); kBoucWen takes z from
  /// the last step's stroke to this one.
  double force_n(double velocity_m_s, double stroke_m) const noexcept {
    if (bent_) {
      const double z =
          p_.law == ForceLaw::kBoucWen ? bouc_wen_z_after(z_, stroke_m - stroke_m_, p_.bouc_wen.yield_disp_m) : 0.0;
      return shaped_force_n(velocity_m_s, stroke_m, z);
    }
    switch (p_.law) {
      case ForceLaw::kBinghamTanh: return tanh_force_n(velocity_m_s);
      case ForceLaw::kBoucWen:
        return bouc_wen_force_at_n(velocity_m_s, stroke_m, bouc_wen_z_after(z_, stroke_m - stroke_m_,
                                                                            p_.bouc_wen.yield_disp_m));
      case ForceLaw::kSpencer: return spencer_force_n(spencer_, spencer_state_, stroke_m, velocity_m_s);
      case ForceLaw::kBingham: break;
    }
    return bingham_force_n(velocity_m_s);
  }

  /// force_n at the stroke the damper is at (stroke_m()).
  double force_n(double velocity_m_s) const noexcept { return force_n(velocity_m_s, stroke_m_); }

  /// Returns the force over this step at velocity `velocity_m_s` and stroke
  /// `stroke_m` (force_n), then moves z to that stroke and advances coil
  /// current and PR.
  double step(double command_a, double velocity_m_s, double stroke_m) noexcept {
    double f = 0.0;
    if (p_.law == ForceLaw::kBoucWen) {
      z_ = bouc_wen_z_after(z_, stroke_m - stroke_m_, p_.bouc_wen.yield_disp_m);
      stroke_m_ = stroke_m;
      f = bent_ ? shaped_force_n(velocity_m_s, stroke_m, z_) : bouc_wen_force_at_n(velocity_m_s, stroke_m, z_);
    } else {
      SeriesStep next{law_force_n_, fluid_velocity_m_s_};
      f = bent_ ? shaped_force_n(velocity_m_s, stroke_m, 0.0, &next) : force_n(velocity_m_s, stroke_m);
      law_force_n_ = next.law_force_n;
      fluid_velocity_m_s_ = next.fluid_velocity_m_s;
      if (bent_) stroke_m_ = stroke_m;
      if (p_.law == ForceLaw::kSpencer) {
        spencer_state_ = spencer_state_after(spencer_, spencer_state_, stroke_m, velocity_m_s, period_s_);
        stroke_m_ = stroke_m;
      }
    }
    if (lost_) commit_play(stroke_m);
    advance(command_a, velocity_m_s);
    return f;
  }

  /// Returns the force over this step at the present stroke, then advances
  /// coil current and PR and (kBoucWen) moves the stroke by v·T, z with it.
  double step(double command_a, double velocity_m_s) noexcept {
    SeriesStep next{law_force_n_, fluid_velocity_m_s_};
    const double f = bent_ && p_.law != ForceLaw::kBoucWen ? shaped_force_n(velocity_m_s, stroke_m_, 0.0, &next)
                                                           : force_n(velocity_m_s);
    law_force_n_ = next.law_force_n;
    fluid_velocity_m_s_ = next.fluid_velocity_m_s;
    if (lost_) commit_play(stroke_m_);
    if (p_.law == ForceLaw::kBoucWen) {
      const double dx_m = velocity_m_s * period_s_;
      z_ = bouc_wen_z_after(z_, dx_m, p_.bouc_wen.yield_disp_m);
      stroke_m_ += dx_m;
    } else if (p_.law == ForceLaw::kSpencer) {
      spencer_state_ = spencer_state_after(spencer_, spencer_state_, stroke_m_, velocity_m_s, period_s_);
      stroke_m_ += velocity_m_s * period_s_;
    } else if (bent_) {
      stroke_m_ += velocity_m_s * period_s_;
    }
    advance(command_a, velocity_m_s);
    return f;
  }

  double current_a() const noexcept { return coil_.current_a(); }
  double participant_ratio() const noexcept { return pr_.pr(); }
  double displaced_volume_m3() const noexcept { return pr_.displaced_volume_m3(); }
  /// Stroke of the last step (kBoucWen, kSpencer, a bent Bingham law; 0 for the thesis's Bingham laws), m.
  double stroke_m() const noexcept { return stroke_m_; }
  /// Bouc–Wen variable at stroke_m() (kBoucWen; 0 for the Bingham laws).
  double bouc_wen_z() const noexcept { return z_; }
  /// Spencer's internal displacement y and variable z (kSpencer), m.
  const SpencerState& spencer_state() const noexcept { return spencer_state_; }
  const ParticipantRatio& mixing() const noexcept { return pr_; }
  ParticipantRatio& mixing() noexcept { return pr_; }
  const MrDamperParams& params() const noexcept { return p_; }
  double period_s() const noexcept { return period_s_; }

 private:
  MrDamperParams p_{};
  double period_s_ = 1.0e-3;
  CurrentDynamics coil_{};
  ParticipantRatio pr_{};
  double fc_n_ = 0.0;      ///< f_c(|i|, PR), Eq. 5.10
  double c0_ns_m_ = 0.0;   ///< c_0(|i|, PR), Eq. 5.11
  double z_ = 0.0;         ///< Bouc–Wen variable at stroke_m_ (kBoucWen)
  double stroke_m_ = 0.0;  ///< stroke z_ belongs to, m (kBoucWen)
  SpencerCoefficients spencer_{};      ///< kSpencer: the model at |i| and PR
  SpencerState spencer_state_{};       ///< kSpencer: (y, z) after the last step
  double last_velocity_m_s_ = 0.0;     ///< v[n−1]: the last step's velocity (the transition time's |a|)
  bool bent_ = false;  ///< a law shaped by m, k, τ or the lost motion (the current exponents act in f_c, c_0)
  bool lost_ = false;  ///< shape's lost motion acts
  bool series_ = false;  ///< shape's series compliance acts (a Bingham law)
  /// What a series compliance carries from one step to the next.
  struct SeriesStep {
    double law_force_n = 0.0;         ///< the law's force (behind the compliance), N
    double fluid_velocity_m_s = 0.0;  ///< the fluid's velocity, m/s
  };
  double law_force_n_ = 0.0;         ///< the law's force of the last step behind the series compliance, N
  double fluid_velocity_m_s_ = 0.0;  ///< the fluid's velocity of the last step behind it, m/s
  double yield_pr1_n_ = 0.0;  ///< |f_c(|i|, PR = 1)|: the lost motion's play is λ times it
  /// The lost motion's play (its committed strokes and driven sides).
  LostMotionPlay play_{};

  /// The play's half width at the present current: λ |f_c(|i|, PR = 1)| / 2, m.
  double play_half_width_m() const noexcept { return 0.5 * p_.shape.lost_motion_m_per_n * yield_pr1_n_; }

  /// e[n] at this step's stroke (LostMotionPlay::engaged_mean).
  double engaged_mean(double stroke_m) const noexcept { return play_.engaged_mean(stroke_m, play_half_width_m()); }

  /// Commits this step's stroke and driven side (after the force used them).
  void commit_play(double stroke_m) noexcept { play_.commit(stroke_m, play_half_width_m()); }

  /// The law shaped by p_.shape (LawShape), in discrepancy::DamperModel's
  /// order: the law's part (Bouc–Wen's f_c z + c_0 v; a Bingham law's with
  /// the band v_TF + τ|a| and c_0 (|v|/v_r)^(m−1)), the lost motion on it,
  /// a Bingham law's behind the series compliance, then the spring (k_0 x or
  /// k x). `z` is Bouc–Wen's variable at the stroke. `next`, when given,
  /// receives the series compliance's law force and fluid velocity of this
  /// step (left as it is without a series compliance).
  double shaped_force_n(double velocity_m_s, double stroke_m, double z, SeriesStep* next = nullptr) const noexcept {
    const LawShape& sh = p_.shape;
    double elastic = 0.0;
    const double e = lost_ ? engaged_mean(stroke_m) : 1.0;
    if (p_.law == ForceLaw::kBoucWen) {
      elastic = p_.bouc_wen.stiffness_n_m * stroke_m;
      return lost_motion_on(fc_n_ * z + c0_ns_m_ * velocity_m_s, 0.0, velocity_m_s, e).force_n + elastic;
    }
    elastic = sh.stiffness_n_m * stroke_m;
    // The band widens with the piston's acceleration over the last step.
    const double band =
        sh.transition_time_s != 0.0
            ? p_.bingham.v_tf_m_s + sh.transition_time_s * (std::fabs(velocity_m_s - last_velocity_m_s_) / period_s_)
            : p_.bingham.v_tf_m_s;
    const double m = sh.has_viscous_exponent() ? sh.viscous_exponent : 1.0;
    const auto law_at = [&](double u) {
      const double c_eff = bent_viscous_ns_m(u);
      if (!series_) return lost_motion_on(bent_bingham_law_n(u, band, c_eff), 0.0, u, e);
      if (p_.law == ForceLaw::kBinghamTanh) {
        const double t = tanh_by_exp(u / band);  // as the calibration's solve
        return lost_motion_on(fc_n_ * t + c_eff * u, bingham_tanh_slope_ns_m(fc_n_, c_eff, m, t, band), u, e);
      }
      return lost_motion_on(bent_bingham_law_n(u, band, c_eff), bingham_slope_ns_m(fc_n_, c_eff, m, u, band), u, e);
    };
    if (!series_) return law_at(velocity_m_s).force_n + elastic;
    double u = fluid_velocity_m_s_ + (velocity_m_s - last_velocity_m_s_);
    const double fb = series_force_n(velocity_m_s, law_force_n_, sh.series_compliance_m_per_n / period_s_, law_at, u);
    if (next != nullptr) *next = {fb, u};
    return fb + elastic;
  }

  /// The lost motion (engagement `e`) on a law's force `fb` at velocity v and on its slope `slope`.
  ForceSlope lost_motion_on(double fb, double slope, double velocity_m_s, double e) const noexcept {
    if (!lost_) return {fb, slope};
    const LawShape& sh = p_.shape;
    const double share = std::clamp(sh.lost_motion_share, 0.0, 1.0);
    fb *= (1.0 - share) + share * e;
    slope *= (1.0 - share) + share * e;
    if (sh.lost_motion_band_m_s > 0.0) {
      const double t = std::tanh(velocity_m_s / sh.lost_motion_band_m_s);
      fb += (1.0 - e) * fc_n_ * t;
      slope += (1.0 - e) * fc_n_ * (1.0 - t * t) / sh.lost_motion_band_m_s;
    }
    return {fb, slope};
  }

  /// c_0 (|v|/v_r)^(m−1): the viscous coefficient bent by m at v (LawShape), N·s/m.
  double bent_viscous_ns_m(double velocity_m_s) const noexcept {
    const LawShape& sh = p_.shape;
    const double av = std::fabs(velocity_m_s);
    return sh.has_viscous_exponent()
               ? (av > 0.0 ? c0_ns_m_ * std::pow(av / sh.viscous_ref_m_s, sh.viscous_exponent - 1.0) : 0.0)
               : c0_ns_m_;
  }

  /// A Bingham law's part at velocity v with the band `band` (v_TF + τ|a|)
  /// and the viscous coefficient `c_eff` (bent_viscous_ns_m(v)).
  double bent_bingham_law_n(double velocity_m_s, double band, double c_eff) const noexcept {
    if (p_.law == ForceLaw::kBinghamTanh) return physics::bingham_tanh_force_n(fc_n_, c_eff, velocity_m_s, band);
    const double av = std::fabs(velocity_m_s);
    const double sgn = velocity_m_s > 0.0 ? 1.0 : (velocity_m_s < 0.0 ? -1.0 : 0.0);
    const double tf = av < band ? av / band : 1.0;
    return tf * (fc_n_ * sgn + c_eff * velocity_m_s);
  }

  /// Eq. 4.4 × Eq. 5.12: TF(v) · (f_c sgn v + c_0 v).
  double bingham_force_n(double velocity_m_s) const noexcept {
    const double sgn = velocity_m_s > 0.0 ? 1.0 : (velocity_m_s < 0.0 ? -1.0 : 0.0);
    return transition_factor(p_.bingham, velocity_m_s) * (fc_n_ * sgn + c0_ns_m_ * velocity_m_s);
  }

  /// baseline.hpp's tanh transition: f_c tanh(v/v_TF) + c_0 v.
  double tanh_force_n(double velocity_m_s) const noexcept {
    return physics::bingham_tanh_force_n(fc_n_, c0_ns_m_, velocity_m_s, p_.bingham.v_tf_m_s);
  }

  /// baseline.hpp's Bouc–Wen form: f_c z + c_0 v + k_0 x.
  double bouc_wen_force_at_n(double velocity_m_s, double stroke_m, double z) const noexcept {
    return bouc_wen_force_n(fc_n_, c0_ns_m_, p_.bouc_wen.stiffness_n_m, z, velocity_m_s, stroke_m);
  }

  /// Coil current (Eq. 4.5) and PR (Eq. 5.9) to the next step, then f_c and c_0.
  void advance(double command_a, double velocity_m_s) noexcept {
    last_velocity_m_s_ = velocity_m_s;
    coil_.step(command_a);
    pr_.step(velocity_m_s, period_s_);
    update_coefficients();
  }

  void update_coefficients() noexcept {
    fc_n_ = coulomb_force_n(p_.bingham, coil_.current_a(), pr_.pr(), p_.shape.yield_current_exponent);
    c0_ns_m_ = viscous_coeff_ns_m(p_.bingham, coil_.current_a(), pr_.pr(), p_.shape.viscous_current_exponent);
    if (lost_) yield_pr1_n_ = std::fabs(coulomb_force_n(p_.bingham, coil_.current_a(), 1.0, p_.shape.yield_current_exponent));
    if (p_.law == ForceLaw::kSpencer)
      spencer_ = p_.spencer.at(std::min(std::fabs(coil_.current_a()), p_.rating.current_a), pr_.pr());
  }
};

}  // namespace mrd::physics
