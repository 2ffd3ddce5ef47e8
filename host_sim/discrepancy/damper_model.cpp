#include "host_sim/discrepancy/damper_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "mrd/physics/damper_laws.hpp"
#include "mrd/physics/series_compliance.hpp"

namespace mrd::discrepancy {
namespace {

/// Mean of `x` over ±half_window_s around every sample (at least one sample
/// each side; a sample exactly half_window_s away counts).
void windowed_mean(std::span<const double> time_s, std::span<const double> x, double half_window_s,
                   std::vector<double>& out) {
  const std::size_t n = std::min(time_s.size(), x.size());
  out.assign(n, 0.0);
  std::size_t lo = 0;
  std::size_t hi = 0;
  double sum = 0.0;
  // The window's edge with a nanosecond's slack, so that a sample exactly
  // half_window_s away counts on both sides whatever the rounding of the
  // time stamps.
  const double half = half_window_s + 1e-9;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = time_s[k];
    while (hi < n && (time_s[hi] - t <= half || hi <= k + 1)) sum += x[hi++];
    while (lo < k && (t - time_s[lo] > half && lo + 1 < k)) sum -= x[lo++];
    out[k] = sum / static_cast<double>(hi - lo);
  }
}

/// |ā| at every sample: the central difference of `vel_m_s` averaged over
/// ±kTransitionAccelHalfWindow_s, m/s².
std::vector<double> averaged_abs_acceleration(std::span<const double> time_s, std::span<const double> vel_m_s) {
  std::vector<double> out;
  windowed_mean(time_s, central_difference(time_s, vel_m_s), kTransitionAccelHalfWindow_s, out);
  for (double& x : out) x = std::fabs(x);
  return out;
}

}  // namespace

ModelInput model_input(const MeasuredData& data, double smoothing_half_window_s) {
  ModelInput in;
  in.time_s = data.time_s;
  in.current_cmd_a = data.current_cmd_a;
  in.current_meas_a = data.current_a;
  const double half_window_s = smoothing_half_window_for(data.time_s, data.displacement_m, smoothing_half_window_s);
  SmoothedMotion s = smooth_motion(data.time_s, data.displacement_m, half_window_s);
  in.disp_m = std::move(s.displacement_m);
  if (data.velocity_m_s.empty()) {
    in.vel_m_s = std::move(s.velocity_m_s);
    in.velocity_derived = true;
  } else {
    in.vel_m_s = data.velocity_m_s;
  }
  in.accel_abs_m_s2 = averaged_abs_acceleration(in.time_s, in.vel_m_s);
  return in;
}

namespace {

/// The side of a mounting's free play the rod starts against: the direction
/// of the actuator's first stroke, the sign of its first excursion from the
/// first sample by more than 5 % of the record's peak-to-peak displacement
/// (0 when it never moves that far). A record that starts in motion was in
/// motion before it: the actuator had taken up the play toward the side it
/// moves to, and the rod is pushed; a rod centred in the play would transmit
/// no force until the actuator had crossed half of it, which no moving
/// mounting does. The excursion, not the first sample's velocity, decides:
/// a record that starts at rest has a velocity of sensor noise there, whose
/// sign says nothing of the stroke to come; 5 % of the stroke is far above
/// a displacement sensor's noise and short of a sine's first quarter period.
double playing_start_side(std::span<const double> disp_m) {
  if (disp_m.empty()) return 0.0;
  const auto [lo, hi] = std::minmax_element(disp_m.begin(), disp_m.end());
  const double threshold_m = 0.05 * (*hi - *lo);
  if (!(threshold_m > 0.0)) return 0.0;
  for (const double x : disp_m) {
    const double d = x - disp_m.front();
    if (std::fabs(d) > threshold_m) return d > 0.0 ? 1.0 : -1.0;
  }
  return 0.0;
}

}  // namespace

DamperModel::DamperModel(ModelInput input, Baseline baseline)
    : in_(std::move(input)), play_start_side_(playing_start_side(in_.disp_m)) {
  const std::size_t n = in_.time_s.size();
  step_s_.resize(n);
  for (std::size_t k = 0; k + 1 < n; ++k) step_s_[k] = in_.time_s[k + 1] - in_.time_s[k];
  if (n >= 2) step_s_[n - 1] = step_s_[n - 2];
  uniform_ = true;
  for (std::size_t k = 0; k < n; ++k) {
    if (std::fabs(step_s_[k] - step_s_[0]) > 1e-6 * step_s_[0]) {
      uniform_ = false;
      break;
    }
  }
  set_baseline(std::move(baseline));
}

void DamperModel::set_baseline(Baseline baseline) {
  const physics::CurrentDynamicsParams& was = p_.coil;
  const physics::CurrentDynamicsParams& now = baseline.coil;
  const bool same_coil = base_current_a_.size() == size() && was.tau_slow_s == now.tau_slow_s &&
                         was.tau_fast_s == now.tau_fast_s && was.weight_slow == now.weight_slow &&
                         was.weight_fast == now.weight_fast;
  p_ = std::move(baseline);
  const double scale = p_.force_scale_n();
  force_ratio_ = scale > 0.0 ? scale / thesis_force_scale_n() : 1.0;
  if (!same_coil) {
    coil_current(1.0, base_current_a_);
    base_e_y_.forget();
    base_e_c_.forget();
  }
  // The fits change one parameter at a time (a Jacobian's column): the
  // exponentials of a law whose rate and exponent stayed are the same doubles.
  law_exps(base_current_a_, p_.yield_n, base_e_y_);
  law_exps(base_current_a_, p_.viscous_ns_m, base_e_c_);
  if (p_.has_transition_time() && in_.accel_abs_m_s2.size() != size())
    in_.accel_abs_m_s2 = averaged_abs_acceleration(in_.time_s, in_.vel_m_s);
}

void DamperModel::coil_current(double tau_scale, std::vector<double>& current_a) const {
  // Eq. 4.5 with unity DC gain, exact for a command held over each step (see
  // physics/current_dynamics.hpp); the coil starts steady at the first command.
  // A measured coil current is the drive's and the coil's answer to the
  // command: it stands for the fast branch, and the field lags it by the slow
  // one (the resolution of hardware_damper_params, host_sim/plant/plant.hpp, for §3's drive).
  const bool measured = !in_.current_meas_a.empty();
  const std::vector<double>& u_a = measured ? in_.current_meas_a : in_.current_cmd_a;
  const std::size_t n = size();
  current_a.resize(n);
  if (n == 0) return;
  const double scale = std::max(tau_scale, kAssumedCoilMinScale);
  const double tau_s = p_.coil.tau_slow_s * scale;
  const double tau_f = p_.coil.tau_fast_s * scale;
  const double ws = p_.coil.weight_slow;
  const double wf = p_.coil.weight_fast;
  double ys = u_a[0];
  double yf = u_a[0];
  double as = std::exp(-step_s_[0] / tau_s);
  double af = std::exp(-step_s_[0] / tau_f);
  for (std::size_t k = 0; k < n; ++k) {
    const double u = u_a[k];
    current_a[k] = ws * ys + wf * (measured ? u : yf);
    if (!uniform_) {
      as = std::exp(-step_s_[k] / tau_s);
      af = std::exp(-step_s_[k] / tau_f);
    }
    ys = as * ys + (1.0 - as) * u;
    yf = af * yf + (1.0 - af) * u;
  }
}

double DamperModel::coil_mean_delay_s() const noexcept {
  const double w = p_.coil.weight_slow + p_.coil.weight_fast;
  return w > 0.0 ? (p_.coil.weight_slow * p_.coil.tau_slow_s + p_.coil.weight_fast * p_.coil.tau_fast_s) / w
                 : p_.coil.tau_slow_s;
}

void DamperModel::single_lag_current(double tau_s, std::vector<double>& current_a) const {
  // di/dt = (u − i)/τ with u held over each step: i[k+1] = a i[k] + (1 − a) u[k], a = e^(−dt/τ);
  // steady at the first input. From a measured coil current as from the command.
  const std::vector<double>& u_a = in_.current_meas_a.empty() ? in_.current_cmd_a : in_.current_meas_a;
  const std::size_t n = size();
  current_a.resize(n);
  if (n == 0) return;
  const double tau = std::max(tau_s, 1e-6);
  double y = u_a[0];
  double a = std::exp(-step_s_[0] / tau);
  for (std::size_t k = 0; k < n; ++k) {
    current_a[k] = y;
    if (!uniform_) a = std::exp(-step_s_[k] / tau);
    y = a * y + (1.0 - a) * u_a[k];
  }
}

void DamperModel::law_exps(const std::vector<double>& current_a, const CurrentLaw& law, CurrentLawExps& cache) {
  const std::size_t n = current_a.size();
  if (cache.e.size() == n && cache.rate_per_a == law.rate_per_a && cache.current_exponent == law.current_exponent)
    return;
  cache.e.resize(n);
  // A current held from one sample to the next (a constant-current test, a
  // settled coil) reuses the previous sample's exponential.
  double i_prev = std::numeric_limits<double>::quiet_NaN();
  double e = 1.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double i = std::fabs(current_a[k]);
    if (i != i_prev) {
      e = std::exp(-law.rate_per_a * (law.current_exponent == 1.0 ? i : std::pow(i, law.current_exponent)));
      i_prev = i;
    }
    cache.e[k] = e;
  }
  cache.rate_per_a = law.rate_per_a;
  cache.current_exponent = law.current_exponent;
}

namespace {

/// One step of the play with a soft contact: the actuator moves by dx from a
/// position u = x − rod inside the gap. Toward a side, u first grows freely
/// until it is c short of the side, then the contact takes up the motion
/// linearly with penetration, d rod/dx = 1 − (h − w)/c (w = u·sgn dx), so
/// h − w decays as exp(−s/c) with the actuator's travel s: the rod reaches
/// the actuator's velocity over a few contact lengths (a compliant stop).
/// c → 0 is the hard play. Solved exactly over the step. Returns the rod's
/// new position, given the actuator's new position x_new.
/// Beyond 700 contact lengths of travel the rest, (h − w)·e^−700 with
/// e^−700 = 9.9e−305, is far below half an ulp of h: w is h exactly, and the
/// exp's underflow (libm's slow path, which sets errno) is not taken.
double soft_contact_step(double dx, double u, double h, double c, double x_new) {
  if (dx == 0.0) return x_new - u;
  const double sgn = dx > 0.0 ? 1.0 : -1.0;
  double w = u * sgn;         // position toward the moving side
  double s = std::fabs(dx);   // actuator travel over the step
  const double knee = h - c;  // where the contact starts
  if (w < knee) {
    const double free = std::min(s, knee - w);
    w += free;
    s -= free;
  }
  if (s > 0.0) {
    const double lengths = s / c;
    w = lengths < 700.0 ? h - (h - std::min(w, h)) * std::exp(-lengths) : h;
  }
  return x_new - w * sgn;
}

/// One step of the play against a progressive stop (backlash, progressive
/// form): toward a side, the rod takes the share e = ½(1 + tanh(y)) of the
/// actuator's motion, y = (w − h)/ℓ the actuator's position past the rod
/// (w = u·sgn dx) beyond the half width h, in engagement lengths ℓ. The stop
/// engages smoothly and is never fully engaged: dy/ds = (1 − e)/ℓ =
/// 1/(ℓ(1 + e^{2y})) integrates over the actuator's travel s to
///   y + e^{2y}/2 = y₀ + e^{2y₀}/2 + s/ℓ,
/// so far from the stop y grows with s (the rod stands still) and past it the
/// rod's share of the velocity lacks ℓ/(2 s'), s' the travel since
/// engagement: a tail over many engagement lengths, where the contact stop's
/// (soft_contact_step) dies out as e^(−s'/c). Solved by Newton's method from
/// above (the left side is convex and increasing, and both R and ½ ln 2R for
/// R ≥ ½ lie at or above its root), to the last bits. Returns the rod's new
/// position, given the actuator's new position x_new.
double progressive_contact_step(double dx, double u, double h, double ell, double x_new) {
  if (dx == 0.0) return x_new - u;
  const double sgn = dx > 0.0 ? 1.0 : -1.0;
  const double y0 = (u * sgn - h) / ell;
  // e^{2y₀}/2 for y₀ above 300 would overflow; y grows as ½ ln(2 s/ℓ) and never gets there.
  const double r = y0 + 0.5 * std::exp(std::min(2.0 * y0, 600.0)) + std::fabs(dx) / ell;
  double y = r >= 0.5 ? std::min(r, 0.5 * std::log(2.0 * r)) : r;
  for (int it = 0; it < 60; ++it) {
    const double e2 = std::exp(std::min(2.0 * y, 600.0));
    const double step = (y + 0.5 * e2 - r) / (1.0 + e2);
    y -= step;
    if (!(std::fabs(step) > 1e-15 * std::max(1.0, std::fabs(y)))) break;
  }
  return x_new - (h + ell * y) * sgn;
}

/// The rod's velocity over one step through free play of half width h_m
/// ending in a contact spring of compliance s_m_per_n: backward Euler on
///   F(v) = dz(u − dt v) / s,   u = x_a(t + dt) − x_rod(t),
/// dz the dead zone of ±h_m, F the Bingham law Y sgn v + C v, its yield
/// taken up linearly over |v| < v_tf (Eq. 4.4), at the step's Y and C. F is odd
/// and increasing and the spring's side falls with v, so the root is unique:
/// 0 inside the dead zone; beyond it, with w = |u| − h_m, s F(v) + dt v = w,
/// closed form on either piece of F. s = 0 is the hard play (v = w/dt).
double impact_rod_velocity(double u_m, double h_m, double s_m_per_n, double dt_s, double yield_n, double visc_ns_m,
                           double v_tf_m_s) {
  const double w = std::fabs(u_m) - h_m;
  if (w <= 0.0 || dt_s <= 0.0) return 0.0;
  const double sgn = u_m > 0.0 ? 1.0 : -1.0;
  // Beyond the band: s (Y + C v) + dt v = w.
  double v = (w - s_m_per_n * yield_n) / (s_m_per_n * visc_ns_m + dt_s);
  if (!(v >= v_tf_m_s) && v_tf_m_s > 0.0) {
    // In the band: a v² + b v − w = 0, a = s C / v_tf, b = s Y / v_tf + dt; the positive root.
    const double a = s_m_per_n * visc_ns_m / v_tf_m_s;
    const double b = s_m_per_n * yield_n / v_tf_m_s + dt_s;
    v = 2.0 * w / (b + std::sqrt(b * b + 4.0 * a * w));
  }
  return sgn * std::max(v, 0.0);
}

/// Play operator of half width half_gap_m on x, with a soft contact over the
/// last `contact_share` of the gap: the driven side's
/// displacement (`driven`), its engaged fraction per sample (`engaged`, the
/// driven side's share of the driving side's central difference, continuous
/// in the gap) and that fraction averaged over ±kContactHalfWindow_s, at
/// least one sample each side (`engaged_avg`): contact is not instantaneous,
/// the driven side takes up the motion over a few milliseconds. The average
/// also keeps the force smooth in the gap and in the delay between samples,
/// which the fit needs (a one-sample jump leaves sample-spaced local minima).
/// `half_gap_m` holds one value (a constant gap) or one per sample.
/// `progressive`: the stop engages as progressive_contact_step does, over an
/// engagement length of contact_share times the whole play.
/// `start_side` (+1, −1 or 0): the side of the play the driven side starts
/// against, the record's first motion having taken up the play toward it
/// (DamperModel's play_start_side_); 0 starts it centred. A progressive stop starts as
/// after a travel of the whole play past it.
void play_operator(std::span<const double> time_s, std::span<const double> x, std::span<const double> half_gap_m,
                   double contact_share, std::vector<double>& driven, std::vector<double>& engaged,
                   std::vector<double>& engaged_avg, bool progressive = false, double start_side = 0.0) {
  const std::size_t n = x.size();
  driven.resize(n);
  double rod = n > 0 ? x[0] : 0.0;
  const double share = std::clamp(contact_share, 0.0, 1.0);
  if (n > 0 && start_side != 0.0) {
    const double h0 = half_gap_m.empty() ? 0.0 : half_gap_m[0];
    const double c0 = share * 2.0 * h0;
    rod = progressive && c0 > 0.0 ? progressive_contact_step(start_side * 2.0 * h0, start_side * h0, h0, c0, x[0])
                                  : x[0] - start_side * h0;
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double h = half_gap_m.size() == 1 ? half_gap_m[0] : half_gap_m[k];
    const double c = share * 2.0 * h;  // contact length, m
    if (k == 0) {
      // As initialised: centred, or against the start side.
    } else if (c <= 0.0) {
      if (x[k] - rod > h) {
        rod = x[k] - h;
      } else if (rod - x[k] > h) {
        rod = x[k] + h;
      }
    } else if (progressive) {
      rod = progressive_contact_step(x[k] - x[k - 1], x[k - 1] - rod, h, c, x[k]);
    } else {
      rod = soft_contact_step(x[k] - x[k - 1], x[k - 1] - rod, h, c, x[k]);
    }
    driven[k] = rod;
  }
  engaged.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k > 0 ? k - 1 : 0;
    const std::size_t b = k + 1 < n ? k + 1 : n - 1;
    const double dx = x[b] - x[a];
    const double dr = driven[b] - driven[a];
    double e = 1.0;
    const double h = half_gap_m.size() == 1 ? half_gap_m[0] : half_gap_m[k];
    if (std::fabs(dx) > 1e-15) e = std::clamp(dr / dx, 0.0, 1.0);
    else if (dr == 0.0 && h > 0.0) e = 0.0;
    engaged[k] = e;
  }
  // A progressive stop takes up the motion smoothly by itself: its engagement is not averaged.
  if (progressive && contact_share > 0.0) {
    engaged_avg = engaged;
  } else {
    windowed_mean(time_s, engaged, kContactHalfWindow_s, engaged_avg);
  }
}


/// The law raw_force's loop steps: Bingham (Eq. 4.1 with its transition),
/// the normalized Bouc–Wen, or Spencer et al.'s model.
enum class LoopLaw { bingham, bouc_wen, spencer };

/// What DamperModel::raw_force's per-sample loop reads, fixed over the
/// record: the per-sample inputs, where it writes, and the laws' constants.
struct RawForceLoop {
  std::size_t n = 0;
  const double* e_y = nullptr;  ///< the yield law's exp(−rate·|i|^q) per sample
  const double* e_c = nullptr;  ///< the viscous law's
  double y_at_zero_n = 0.0, y_limit_n = 0.0;        ///< Eq. 5.10: Y = Y_a e + PR Y_b (1 − e), N
  double c_at_zero_ns_m = 0.0, c_limit_ns_m = 0.0;  ///< Eq. 5.11's, N·s/m
  const double* coil_a = nullptr;     ///< coil current, A
  const double* xd = nullptr;         ///< the damper's displacement, m (rod_disp_m with an impact spring)
  const double* vd = nullptr;         ///< the damper's velocity, m/s (rod_vel_m_s with an impact spring)
  const double* step_s = nullptr;     ///< dt_k, s
  const double* act_disp_m = nullptr;  ///< the actuator's displacement, m
  const double* act_vel_m_s = nullptr;  ///< the actuator's velocity, m/s
  const double* accel_abs_m_s2 = nullptr;  ///< |ā| (timed transition only), m/s²
  const double* lm_factor = nullptr;  ///< the lost motion's engagement (lost motion only)
  double* force_n = nullptr;
  double* rod_disp_m = nullptr;  ///< impact spring only
  double* rod_vel_m_s = nullptr;
  double rod_m = 0.0;  ///< the rod's first position through an impact spring's play, m
  double impact_half_gap_m = 0.0;
  double impact_compliance_m_per_n = 0.0;
  physics::PrCoefficients pr_c{};
  double q_per_m = 0.0;
  double alpha_y_per_j = 0.0;
  double alpha_v_per_j = 0.0;
  double k_gas_n_m = 0.0;
  double offset_n = 0.0;
  double v_tf_m_s = 0.0;
  bool timed = false;
  bool tanh_shape = false;
  double tau_s = 0.0;
  double k_bingham_n_m = 0.0;
  bool power_viscous = false;
  double v_r_m_s = 0.0;
  double m_minus_1 = 0.0;
  double x_y_m = 0.0;
  double asym = 0.0;
  double k_0_n_m = 0.0;
  double share = 0.0;
  double play_band_m_s = 0.0;
  double series_per_n = 0.0;
  const physics::SpencerParams* spencer = nullptr;
};

/// The loop of DamperModel::raw_force, compiled for each law and each
/// combination of the effects that change its body (settling, thermal fade,
/// an impact spring, the lost motion, a series compliance): the flags are
/// constants there, so a body holds only what its effects use and keeps its
/// state in registers. Every combination performs the same floating-point
/// operations in the same order as the general loop would, so the force is
/// the same to the bit.
template <LoopLaw Law, bool Idle, bool Thermal, bool Impact, bool LostMotion, bool Series>
void raw_force_loop(const RawForceLoop& loop) {
  constexpr bool spencer = Law == LoopLaw::spencer;
  constexpr bool bouc_wen = Law == LoopLaw::bouc_wen;
  const RawForceLoop c = loop;  // a local copy: the stores to the force do not alias it
  const std::size_t n = c.n;
  const double* xd = c.xd;
  const double* vd = c.vd;
  double rod_m = c.rod_m;
  double fb_prev = 0.0;        // the law's force at the sample before, N
  double fluid_vel_m_s = 0.0;  // the fluid's velocity behind the series compliance, m/s
  double energy_j = 0.0;
  double pr = 1.0;
  double decay = 1.0;  // exp(−c_PR ∫Q dt), ∫Q dt in volume units, updated by a factor per step
  double z = 0.0;      // Bouc–Wen variable; the record starts unloaded
  // spencer: (y, z) from rest at the first stroke, its coefficients
  // recomputed when the current, the participant ratio or the fade changes.
  // The rod's first position (through a mounting's play, against the side of the first motion).
  physics::SpencerState sp{n > 0 ? (Impact ? rod_m : xd[0]) : 0.0, 0.0};
  physics::SpencerCoefficients sc;
  double sc_key[4] = {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0, 0.0};
  for (std::size_t k = 0; k < n; ++k) {
    if constexpr (Idle) pr = c.pr_c.b_pr + (c.pr_c.a_pr - c.pr_c.b_pr) * decay;  // Eq. 5.9
    double fy = c.y_at_zero_n * c.e_y[k] + pr * (c.y_limit_n * (1.0 - c.e_y[k]));             // Eq. 5.10
    double cv = c.c_at_zero_ns_m * c.e_c[k] + pr * (c.c_limit_ns_m * (1.0 - c.e_c[k]));       // Eq. 5.11
    if constexpr (Thermal) {
      fy *= std::max(1.0 - c.alpha_y_per_j * energy_j, 0.0);
      cv *= std::max(1.0 - c.alpha_v_per_j * energy_j, 0.0);
    }
    const double dt = c.step_s[k];
    if constexpr (Impact) {
      // The step centred on the sample: rod_m is the rod at t_k − dt/2, the
      // actuator's target at t_k + dt/2, so that v_rod is the velocity at t_k
      // (on a hard stop, the actuator's central difference) and not half a
      // step ahead of it.
      const double x_half = k + 1 < n ? 0.5 * (c.act_disp_m[k] + c.act_disp_m[k + 1])
                                      : c.act_disp_m[k] + 0.5 * dt * c.act_vel_m_s[k];
      const double v_rod = impact_rod_velocity(x_half - rod_m, c.impact_half_gap_m, c.impact_compliance_m_per_n, dt,
                                               std::fabs(fy), std::fabs(cv), c.v_tf_m_s);
      c.rod_disp_m[k] = rod_m + 0.5 * dt * v_rod;
      c.rod_vel_m_s[k] = v_rod;
      rod_m += dt * v_rod;
    }
    const double v = vd[k];
    double fb = 0.0;
    double elastic = 0.0;
    if constexpr (spencer) {
      const double phi_y = Thermal ? std::max(1.0 - c.alpha_y_per_j * energy_j, 0.0) : 1.0;
      const double phi_v = Thermal ? std::max(1.0 - c.alpha_v_per_j * energy_j, 0.0) : 1.0;
      if (!(sc_key[0] == c.coil_a[k] && sc_key[1] == pr && sc_key[2] == phi_y && sc_key[3] == phi_v)) {
        sc = c.spencer->at(c.coil_a[k], pr);
        sc.alpha_n_m *= phi_y;
        sc.c0_ns_m *= phi_v;
        sc.c1_ns_m *= phi_v;
        sc_key[0] = c.coil_a[k];
        sc_key[1] = pr;
        sc_key[2] = phi_y;
        sc_key[3] = phi_v;
      }
      // Eq. (8) less its spring, which joins the elastic part.
      fb = sc.c1_ns_m * physics::spencer_y_rate(sc, sp, xd[k], v);
      elastic = sc.k1_n_m * (xd[k] - sc.x0_m);
      sp = physics::spencer_state_after(sc, sp, xd[k], v, dt);
    } else if constexpr (bouc_wen) {
      fb = fy * z + cv * v;
      elastic = c.k_0_n_m * xd[k];
      z = bouc_wen_step(z, v, dt, c.x_y_m);
    }
    // The baseline's lost motion and a direction asymmetry on a law force
    // f at velocity u, with its slope df (N·s/m).
    const auto shaped = [&](double f, double df, double u) {
      if constexpr (LostMotion) {
        const double e = c.lm_factor[k];
        f *= (1.0 - c.share) + c.share * e;
        df *= (1.0 - c.share) + c.share * e;
        // Fully engaged (e = 1) the band adds 0 · Y tanh(u/v_p), ±0, to a
        // force (and a slope) that is not zero: they stay as they are, bit
        // for bit, and the tanh is not taken.
        if (c.play_band_m_s > 0.0 && !(e == 1.0 && f != 0.0 && (!Series || df != 0.0))) {
          const double t = std::tanh(u / c.play_band_m_s);
          f += (1.0 - e) * fy * t;
          if constexpr (Series) df += (1.0 - e) * fy * (1.0 - t * t) / c.play_band_m_s;  // the slope only where it is solved for
        }
      }
      if (c.asym != 0.0) {
        const double g = u > 0.0 ? 1.0 + c.asym : (u < 0.0 ? 1.0 - c.asym : 1.0);
        f *= g;
        df *= g;
      }
      return physics::ForceSlope{f, df};
    };
    if constexpr (!spencer && !bouc_wen) {
      const double band = c.timed ? c.v_tf_m_s + c.tau_s * c.accel_abs_m_s2[k] : c.v_tf_m_s;
      // The law at the fluid's velocity u (the piston's, without a series
      // compliance), and its slope for the series compliance's solve.
      const auto law_at = [&](double u) {
        const double au = std::fabs(u);
        // C v_r (|u|/v_r)^m sgn u as C (|u|/v_r)^(m−1) u; its slope m C (|u|/v_r)^(m−1).
        const double c_eff = c.power_viscous ? (au > 0.0 ? cv * std::pow(au / c.v_r_m_s, c.m_minus_1) : 0.0) : cv;
        const double m = c.power_viscous ? c.m_minus_1 + 1.0 : 1.0;
        // Eq. 4.1, 4.4, 5.12, or the tanh transition (baseline.hpp), and its slope when solved for.
        if (c.tanh_shape) {
          // bingham_tanh_force_n; behind a series compliance with the faster tanh it solves with.
          const double t = Series ? physics::tanh_by_exp(u / band) : std::tanh(u / band);
          const double f = fy * t + c_eff * u;
          return shaped(f, Series ? physics::bingham_tanh_slope_ns_m(fy, c_eff, m, t, band) : 0.0, u);
        }
        const double f = bingham_force_n(u, fy, c_eff, band);
        const double df = Series ? physics::bingham_slope_ns_m(fy, c_eff, m, u, band) : 0.0;
        return shaped(f, df, u);
      };
      // Behind a series compliance: F = f(v − Ḟ/k_s), over the step from the sample before.
      if (Series && k > 0) {
        fluid_vel_m_s += v - vd[k - 1];
        fb = physics::series_force_n(v, fb_prev, c.series_per_n / c.step_s[k - 1], law_at, fluid_vel_m_s);
      } else {
        fb = law_at(v).force_n;
        fluid_vel_m_s = v;
      }
      fb_prev = fb;
      elastic = c.k_bingham_n_m * xd[k];
    } else {
      fb = shaped(fb, 0.0, v).force_n;
    }
    c.force_n[k] = fb + elastic + c.k_gas_n_m * xd[k] + c.offset_n;
    if constexpr (Idle) decay *= std::exp(-c.pr_c.c_pr * std::fabs(v) * c.q_per_m * dt);
    if constexpr (Thermal) energy_j += fb * v * dt;
  }
}

/// Calls f with std::bool_constant<b>.
template <class F>
void with_flag(bool b, F&& f) {
  if (b) {
    f(std::true_type{});
  } else {
    f(std::false_type{});
  }
}

/// raw_force_loop for the law and the effects at run time.
void run_raw_force_loop(const RawForceLoop& loop, LoopLaw law, bool idle, bool thermal, bool impact, bool lost_motion,
                        bool series) {
  with_flag(idle, [&](auto i) {
    with_flag(thermal, [&](auto t) {
      with_flag(impact, [&](auto m) {
        if (law == LoopLaw::spencer) {
          // The spencer law has neither a lost motion nor a series compliance (Baseline).
          raw_force_loop<LoopLaw::spencer, decltype(i)::value, decltype(t)::value, decltype(m)::value, false, false>(loop);
        } else if (law == LoopLaw::bouc_wen) {
          // A series compliance only changes the slope, which the Bouc–Wen law does not solve for.
          with_flag(lost_motion, [&](auto l) { raw_force_loop<LoopLaw::bouc_wen, decltype(i)::value, decltype(t)::value, decltype(m)::value, decltype(l)::value, false>(loop); });
        } else {
          with_flag(lost_motion, [&](auto l) {
            with_flag(series, [&](auto s) { raw_force_loop<LoopLaw::bingham, decltype(i)::value, decltype(t)::value, decltype(m)::value, decltype(l)::value, decltype(s)::value>(loop); });
          });
        }
      });
    });
  });
}

}  // namespace

void DamperModel::backlash_motion(double half_gap_m, double contact_share, ModelWorkspace& ws,
                                  bool progressive) const {
  // The rod stays put until the actuator reaches a side of the gap; it moves
  // at the actuator's velocity times the averaged engagement.
  play_operator(in_.time_s, in_.disp_m, std::span<const double>(&half_gap_m, 1), contact_share, ws.disp_m, ws.engaged,
                ws.vel_m_s, progressive, play_start_side_);
  for (std::size_t k = 0; k < size(); ++k) ws.vel_m_s[k] *= in_.vel_m_s[k];
}

void DamperModel::raw_force(const EffectSet& set, std::span<const double> params, ModelWorkspace& ws) const {
  const std::size_t n = size();
  const auto param = [&](Effect e, std::size_t i, double fallback) {
    const auto off = set.offset(e);
    return off ? params[*off + i] : fallback;
  };
  const double tau_scale = param(Effect::coil_lag, 0, 1.0);
  const double* e_y = base_e_y_.e.data();
  const double* e_c = base_e_c_.e.data();
  const double* coil_a = base_current_a_.data();
  if (set.contains(Effect::coil_lag)) {
    if (set.form(Effect::coil_lag) == kCoilSingleLag) {
      single_lag_current(tau_scale * coil_mean_delay_s(), ws.current_a);
    } else {
      coil_current(tau_scale, ws.current_a);
    }
    ws.e_y.forget();
    ws.e_c.forget();
    law_exps(ws.current_a, p_.yield_n, ws.e_y);
    law_exps(ws.current_a, p_.viscous_ns_m, ws.e_c);
    e_y = ws.e_y.e.data();
    e_c = ws.e_c.e.data();
    coil_a = ws.current_a.data();
  }

  // Damper motion: the actuator's, or through the free play of the mounting.
  const double* xd = in_.disp_m.data();
  const double* vd = in_.vel_m_s.data();
  // With an impact spring at the end of the play the rod's motion follows the
  // force, and is found sample by sample in the loop below.
  const bool impact = set.contains(Effect::backlash) && set.form(Effect::backlash) == kBacklashImpactSpring;
  const double impact_half_gap_m = impact ? 0.5 * std::max(param(Effect::backlash, 0, 0.0), 0.0) : 0.0;
  const double impact_compliance_m_per_n =
      impact ? std::max(param(Effect::backlash, 1, 0.0), 0.0) / std::max(p_.force_scale_n(), 1e-9) : 0.0;
  // The rod starts against the side of the play the actuator first moves to (play_start_side_).
  double rod_m = n > 0 ? in_.disp_m[0] - play_start_side_ * impact_half_gap_m : 0.0;
  if (impact) {
    ws.disp_m.resize(n);
    ws.vel_m_s.resize(n);
  } else if (set.contains(Effect::backlash)) {
    backlash_motion(0.5 * std::max(param(Effect::backlash, 0, 0.0), 0.0), param(Effect::backlash, 1, 0.0), ws,
                    set.form(Effect::backlash) == kBacklashProgressive);
    xd = ws.disp_m.data();
    vd = ws.vel_m_s.data();
  }

  if (impact) {
    xd = ws.disp_m.data();
    vd = ws.vel_m_s.data();
  }

  const bool idle = set.contains(Effect::idle_settling);
  physics::PrCoefficients pr_c;
  if (idle) pr_c = physics::pr_coefficients(p_.pr, param(Effect::idle_settling, 0, 0.0));  // Eq. 5.6–5.8
  // Full recovery over V_r: PR = 1 − (1 − a_PR) e^(−V/V_r), V = ∫|v| A dt in m³.
  const bool full_recovery = idle && set.form(Effect::idle_settling) == kSettlingFullRecovery;
  if (full_recovery) {
    pr_c.b_pr = 1.0;
    pr_c.c_pr = 1.0 / std::max(param(Effect::idle_settling, 1, 1.0), 1e-9);
  }
  // Eq. 5.9 counts ∫Q dt in its volume units; the full recovery in m³.
  const double q_per_m = full_recovery ? p_.pr.flow_area_m2 : p_.pr.flow_area_m2 / p_.pr.volume_unit_m3;

  const bool thermal = set.contains(Effect::thermal_fade);
  const double alpha_y = std::max(param(Effect::thermal_fade, 0, 0.0), 0.0) / kThermalCapacity_j_per_k;
  const double alpha_v = std::max(param(Effect::thermal_fade, 1, 0.0), 0.0) / kThermalCapacity_j_per_k;
  const double k_gas = param(Effect::gas_spring, 0, 0.0);
  const double offset = param(Effect::force_offset, 0, 0.0);
  const double v_tf = p_.v_tf_m_s;
  const bool timed = p_.has_transition_time();
  const bool tanh_shape = p_.has_tanh_transition();
  const double tau_s = p_.transition_time_s;
  // The Bingham law's spring and its viscous exponent (baseline.hpp).
  const double k_bingham = p_.has_bingham_stiffness() ? p_.stiffness_n_m : 0.0;
  const bool power_viscous = p_.has_viscous_exponent();
  const double v_r = p_.viscous_ref_m_s;
  const double m_minus_1 = p_.viscous_exponent - 1.0;
  const bool preyield = set.contains(Effect::preyield_hysteresis) && param(Effect::preyield_hysteresis, 0, 0.0) > 0.0;
  // The spencer law has its own pre-yield (Eq. (9)): a preyield_hysteresis
  // effect leaves it as it is.
  const bool spencer = p_.law == BaseLaw::spencer;
  const bool bouc_wen = !spencer && (p_.law == BaseLaw::bouc_wen || preyield);
  const double x_y = preyield ? param(Effect::preyield_hysteresis, 0, 0.0) : p_.yield_disp_m;
  const double asym = param(Effect::direction_asymmetry, 0, 0.0);
  const double k_0 = p_.stiffness_n_m;
  // Lost motion at reversals (baseline.hpp): the held-up share's engagement,
  // on the damper's own motion (after any mounting play).
  const bool lost_motion = p_.has_lost_motion();
  const double share = std::clamp(p_.lost_motion_share, 0.0, 1.0);
  const double play_band = std::max(p_.lost_motion_band_m_s, 0.0);
  if (lost_motion) {
    ws.lm_half_gap.resize(n);
    const CurrentLaw& y = p_.yield_n;
    for (std::size_t k = 0; k < n; ++k) {
      const double y_n = y.at_zero * e_y[k] + y.limit * (1.0 - e_y[k]);  // Eq. 5.10 at PR = 1
      ws.lm_half_gap[k] = 0.5 * p_.lost_motion_m_per_n * std::fabs(y_n);
    }
    // Through an impact spring the rod's motion is found in the loop: the lost motion then on the actuator's.
    play_operator(in_.time_s, std::span<const double>(impact ? in_.disp_m.data() : xd, n), ws.lm_half_gap, 0.0,
                  ws.lm_driven, ws.lm_engaged, ws.lm_factor);
  }

  // A compliance in series with the Bingham law (baseline.hpp), m/N.
  const bool series = p_.has_series_compliance() && !bouc_wen;
  ws.force_n.resize(n);
  RawForceLoop loop;
  loop.n = n;
  loop.e_y = e_y;
  loop.e_c = e_c;
  loop.y_at_zero_n = p_.yield_n.at_zero;
  loop.y_limit_n = p_.yield_n.limit;
  loop.c_at_zero_ns_m = p_.viscous_ns_m.at_zero;
  loop.c_limit_ns_m = p_.viscous_ns_m.limit;
  loop.coil_a = coil_a;
  loop.xd = xd;
  loop.vd = vd;
  loop.step_s = step_s_.data();
  loop.act_disp_m = in_.disp_m.data();
  loop.act_vel_m_s = in_.vel_m_s.data();
  loop.accel_abs_m_s2 = in_.accel_abs_m_s2.data();
  loop.lm_factor = ws.lm_factor.data();
  loop.force_n = ws.force_n.data();
  loop.rod_disp_m = ws.disp_m.data();
  loop.rod_vel_m_s = ws.vel_m_s.data();
  loop.rod_m = rod_m;
  loop.impact_half_gap_m = impact_half_gap_m;
  loop.impact_compliance_m_per_n = impact_compliance_m_per_n;
  loop.pr_c = pr_c;
  loop.q_per_m = q_per_m;
  loop.alpha_y_per_j = alpha_y;
  loop.alpha_v_per_j = alpha_v;
  loop.k_gas_n_m = k_gas;
  loop.offset_n = offset;
  loop.v_tf_m_s = v_tf;
  loop.timed = timed;
  loop.tanh_shape = tanh_shape;
  loop.tau_s = tau_s;
  loop.k_bingham_n_m = k_bingham;
  loop.power_viscous = power_viscous;
  loop.v_r_m_s = v_r;
  loop.m_minus_1 = m_minus_1;
  loop.x_y_m = x_y;
  loop.asym = asym;
  loop.k_0_n_m = k_0;
  loop.share = share;
  loop.play_band_m_s = play_band;
  loop.series_per_n = series ? p_.series_compliance_m_per_n : 0.0;
  loop.spencer = &p_.spencer;
  const LoopLaw law = spencer ? LoopLaw::spencer : (bouc_wen ? LoopLaw::bouc_wen : LoopLaw::bingham);
  run_raw_force_loop(loop, law, idle, thermal, impact, lost_motion, series);
}

void DamperModel::simulate(const EffectSet& set, std::span<const double> params, ModelWorkspace& ws,
                           std::vector<double>& force_n) const {
  std::vector<std::size_t> all(size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
  force_n.resize(size());
  simulate_at(set, params, ws, all, force_n);
}

void DamperModel::simulate_at(const EffectSet& set, std::span<const double> params, ModelWorkspace& ws,
                              std::span<const std::size_t> index, std::span<double> force_n) const {
  raw_force(set, params, ws);
  const auto off = set.offset(Effect::time_delay);
  const double delay_s = std::max(p_.force_delay_s, 0.0) + (off ? std::max(params[*off], 0.0) : 0.0);
  delay_force(in_.time_s, ws.force_n, delay_s, index, force_n);
}

void delay_force(std::span<const double> time_s, std::span<const double> force_n, double delay_s,
                 std::span<const std::size_t> index, std::span<double> out) {
  if (delay_s == 0.0) {
    for (std::size_t j = 0; j < index.size(); ++j) out[j] = force_n[index[j]];
    return;
  }
  const auto& t = time_s;
  const std::size_t n = t.size();
  std::size_t p = 0;  // t[p] <= target, moving forward with ascending targets
  for (std::size_t j = 0; j < index.size(); ++j) {
    const double target = t[index[j]] - delay_s;
    if (target <= t[0]) {
      out[j] = force_n[0];
      continue;
    }
    while (p + 1 < n && t[p + 1] <= target) ++p;
    if (p + 1 >= n) {
      out[j] = force_n[n - 1];
      continue;
    }
    const double w = (target - t[p]) / (t[p + 1] - t[p]);
    out[j] = force_n[p] + w * (force_n[p + 1] - force_n[p]);
  }
}

double normalized_rms_gap(std::span<const double> measured, std::span<const double> model) {
  double se = 0.0;
  double ss = 0.0;
  for (std::size_t k = 0; k < measured.size(); ++k) {
    const double d = measured[k] - model[k];
    se += d * d;
    ss += measured[k] * measured[k];
  }
  return ss > 0.0 ? std::sqrt(se / ss) : 0.0;
}

SampleRange moving_span(std::span<const double> vel_m_s) {
  const std::size_t n = vel_m_s.size();
  double peak = 0.0;
  for (const double v : vel_m_s) peak = std::max(peak, std::fabs(v));
  const auto moving = [&](double v) { return std::fabs(v) > kMovingShare * peak; };
  if (!(peak > 0.0) || !std::isfinite(peak)) return {0, n};
  std::size_t begin = 0;
  while (begin < n && !moving(vel_m_s[begin])) ++begin;
  std::size_t end = n;
  while (end > begin && !moving(vel_m_s[end - 1])) --end;
  return {begin, end};
}

}  // namespace mrd::discrepancy
