#include "plant.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "damper_physics.hpp"

namespace indep {
namespace {

double sgn(double x) { return (x > 0.0) - (x < 0.0); }

/// Coil state of Eq. 4.5: two first-order lags, advanced exactly over an
/// interval in which the command may step at known instants.
struct Coil {
  double tau_slow_s, tau_fast_s;
  double slow_a, fast_a;

  [[nodiscard]] double current_a() const { return kCoilWeightSlow * slow_a + kCoilWeightFast * fast_a; }

  void hold(double command_a, double dt_s) {
    if (dt_s <= 0.0) return;
    const double es = std::exp(-dt_s / tau_slow_s);
    const double ef = std::exp(-dt_s / tau_fast_s);
    slow_a = command_a + (slow_a - command_a) * es;
    fast_a = command_a + (fast_a - command_a) * ef;
  }

  void advance(const CurrentProgram& p, double t0_s, double t1_s) {
    double t = t0_s;
    for (const double ts : p.start_s) {
      if (ts > t && ts < t1_s) {
        hold(p.at(t), ts - t);
        t = ts;
      }
    }
    hold(p.at(t), t1_s - t);
  }
};

/// The damper's own force (Eq. 4.1–4.4, 5.10–5.12) with the form and fade variations.
struct DamperLaw {
  const EffectParams& e;
  double yield_n = 0.0, viscous_n_s_m = 0.0;

  void set_state(double current_a, double pr, double temp_rise_k) {
    double phi_y = 1.0, phi_v = 1.0;
    if (e.fade_exponential) {
      phi_y = std::exp(-e.fade_yield_per_k * temp_rise_k);
      phi_v = std::exp(-e.fade_viscous_per_k * temp_rise_k);
    } else {
      phi_y = std::max(0.0, 1.0 - e.fade_yield_per_k * temp_rise_k);
      phi_v = std::max(0.0, 1.0 - e.fade_viscous_per_k * temp_rise_k);
    }
    yield_n = phi_y * yield_force_n(current_a, pr);
    viscous_n_s_m = phi_v * viscous_coeff_n_s_m(current_a, pr);
  }

  [[nodiscard]] double force_n(double v) const {
    // Eq. 4.1–4.4, or the smooth variant tanh(v / v0)(f_c + c_0 |v|).
    const double f = e.tanh_velocity_m_s > 0.0
                         ? std::tanh(v / e.tanh_velocity_m_s) * (yield_n + viscous_n_s_m * std::abs(v))
                         : transition_factor(v) * (yield_n * sgn(v) + viscous_n_s_m * v);
    return f * (v > 0.0 ? 1.0 + e.asymmetry : (v < 0.0 ? 1.0 - e.asymmetry : 1.0));
  }
};

/// Smooth engagement of the play: the rod follows the actuator's velocity
/// times ½(1 + tanh(p / ℓ)), p the penetration past the contact point in the
/// direction of motion.
double smooth_rod_velocity(double xa, double va, double xd, double half_play_m, double contact_m) {
  const double p = (xa - xd) * sgn(va) - half_play_m;
  return va * 0.5 * (1.0 + std::tanh(p / contact_m));
}

/// The actuator's motion on the fine grid: each sine carried as a phasor
/// rotated by ωh per step (4 multiplications instead of a sine and a cosine).
class MotionStepper {
 public:
  MotionStepper(const Motion& m, double h) : m_(m), h_(h) {
    for (const auto& c : m.sines) {
      const double w = 2.0 * std::numbers::pi * c.frequency_hz;
      phasors_.push_back({std::cos(c.phase_rad), std::sin(c.phase_rad), std::cos(w * h), std::sin(w * h),
                          c.amplitude_m, c.amplitude_m * w, c.amplitude_m * w * w});
    }
  }
  /// Displacement and velocity at t_j, and the displacement at t_(j+1).
  [[nodiscard]] double x() const { return x_at(0.0, false); }
  [[nodiscard]] double v() const { return x_at(0.0, true); }
  [[nodiscard]] double x_next() const { return x_at(h_, false); }
  /// Acceleration at t_j.
  [[nodiscard]] double a() const {
    double sum = 0.0;
    for (const auto& p : phasors_) sum -= p.amp_m_s2 * p.s;
    if (m_.chirp.amplitude_m != 0.0) {
      // The sweep computed directly (its frequency changes every step).
      const Motion sweep{0.0, 0.0, {}, m_.chirp};
      sum += sweep.acceleration_m_s2(static_cast<double>(j_) * h_);
    }
    return sum;
  }
  void step() {
    ++j_;
    for (auto& p : phasors_) {
      const double c = p.c * p.cw - p.s * p.sw;
      p.s = p.s * p.cw + p.c * p.sw;
      p.c = c;
    }
  }

 private:
  struct Phasor {
    double c, s, cw, sw, amp_m, amp_m_s, amp_m_s2;
  };
  [[nodiscard]] double x_at(double ahead_s, bool velocity) const {
    const double t = static_cast<double>(j_) * h_ + ahead_s;
    double sum = velocity ? m_.ramp_m_s : m_.offset_m + m_.ramp_m_s * t;
    for (const auto& p : phasors_) {
      if (velocity) {
        sum += p.amp_m_s * p.c;
      } else if (ahead_s > 0.0) {
        sum += p.amp_m * (p.s * p.cw + p.c * p.sw);
      } else {
        sum += p.amp_m * p.s;
      }
    }
    if (m_.chirp.amplitude_m != 0.0) {
      const Motion sweep{0.0, 0.0, {}, m_.chirp};
      sum += velocity ? sweep.velocity_m_s(t) : sweep.displacement_m(t);
    }
    return sum;
  }
  const Motion& m_;
  double h_;
  std::size_t j_ = 0;
  std::vector<Phasor> phasors_;
};

}  // namespace

FineRun simulate(const Scenario& s, Channels channels) {
  if (!(s.duration_s > 0.0) || !(s.rate_hz > 0.0) || s.oversample < 1) {
    throw std::invalid_argument("indep::simulate: duration, rate and oversampling must be positive");
  }
  const EffectParams& e = s.effects;
  const bool play = e.free_play_m > 0.0;
  const bool compliant = e.series_stiffness_n_m > 0.0;
  if (play && compliant) throw std::invalid_argument("indep::simulate: free play with a series compliance");

  FineRun run;
  const double h = 1.0 / (s.rate_hz * s.oversample);
  run.step_s = h;
  const auto n = static_cast<std::size_t>(std::ceil((s.duration_s + 1.0 / s.rate_hz) / h)) + 2;
  const bool states = channels == Channels::all;
  run.force_channel_n.resize(n);
  if (states) {
    run.coil_current_a.resize(n);
    run.rod_disp_m.resize(n);
    run.rod_vel_m_s.resize(n);
    run.participant_ratio.resize(n);
    run.temperature_rise_k.resize(n);
  }

  const double u0 = s.current.at(0.0);
  // One lag: both halves with the same time constant.
  Coil coil = e.coil_single_lag
                  ? Coil{kCoilMeanTau_s * e.coil_tau_scale, kCoilMeanTau_s * e.coil_tau_scale, u0, u0}
                  : Coil{kCoilTauSlow_s * e.coil_tau_scale, kCoilTauFast_s * e.coil_tau_scale, u0, u0};
  const PrLaw law = pr_law(e.settling_quotient);
  DamperLaw damper{e};
  const double half_play = 0.5 * e.free_play_m;
  const double filter_gain = e.force_filter_s > 0.0 ? 1.0 - std::exp(-h / e.force_filter_s) : 1.0;
  const double aa_gain = e.delay_filter_s > 0.0 ? 1.0 - std::exp(-h / e.delay_filter_s) : 1.0;
  const bool impact = play && e.contact_stiffness_n_m > 0.0;
  const double cooling = e.cooling_time_s > 0.0 ? std::exp(-h / e.cooling_time_s) : 1.0;

  // The rod starts against the side of the play the actuator is moving towards.
  double xd = s.motion.displacement_m(0.0) - half_play * sgn(s.motion.velocity_m_s(0.0));
  double volume_l = 0.0;
  double temp_k = 0.0;
  double channel_n = e.force_offset_n + e.gas_preload_n;
  double aa_n = channel_n;

  MotionStepper motion(s.motion, h);
  double vd_before = s.motion.velocity_m_s(0.0);
  for (std::size_t j = 0; j < n; ++j, motion.step()) {
    const double t = static_cast<double>(j) * h;
    const double xa = motion.x();
    const double va = motion.v();
    const double current = coil.current_a();
    const double pr = e.settling_quotient <= 0.0        ? 1.0
                      : e.settling_recovery_l > 0.0 ? 1.0 - (1.0 - law.a_pr) * std::exp(-volume_l / e.settling_recovery_l)
                                                    : participant_ratio(law, volume_l);
    damper.set_state(current, pr, temp_k);

    // Rod motion.
    double vd = va;
    if (impact) {
      // Backward Euler through the contact spring: F_d(v) = k_c dz(x_a(t + h) − x_d − h v), dz the
      // dead zone of the half play; the left side rises and the right side falls with v.
      const double k = e.contact_stiffness_n_m;
      const double gap = motion.x_next() - xd;
      const auto dead_zone = [&](double u) { return u > half_play ? u - half_play : (u < -half_play ? u + half_play : 0.0); };
      double lo = -2.0, hi = 2.0;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (damper.force_n(mid) - k * dead_zone(gap - h * mid) > 0.0 ? hi : lo) = mid;
      }
      vd = 0.5 * (lo + hi);  // x_d advances with the other states
    } else if (play && e.contact_fraction > 0.0) {
      vd = smooth_rod_velocity(xa, va, xd, half_play, e.contact_fraction * e.free_play_m);
    } else if (play) {
      // Play operator: the rod moves only when the actuator pushes it, and then at its velocity.
      const double before = xd;
      xd = std::clamp(xd, xa - half_play, xa + half_play);
      vd = xd != before || j == 0 ? va : 0.0;
    } else if (compliant) {
      // Backward Euler on the spring: F_d(v) + c v = k (x_a − x_d − h v) + c v_a, monotone in v.
      const double k = e.series_stiffness_n_m, c = e.series_damping_n_s_m;
      const double rhs = k * (xa - xd) + c * va;
      double lo = -2.0, hi = 2.0;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (damper.force_n(mid) + (c + k * h) * mid - rhs > 0.0 ? hi : lo) = mid;
      }
      vd = 0.5 * (lo + hi);
      xd += h * vd;
    } else {
      xd = xa;
    }

    const double fd = damper.force_n(vd);
    // Rod acceleration: the actuator's (exact) when the rod follows it rigidly, else a backward difference.
    const double ad = !play && !compliant ? motion.a() : (j > 0 ? (vd - vd_before) / h : 0.0);
    vd_before = vd;
    const double f = fd + e.gas_preload_n + e.gas_stiffness_n_m * xd * (1.0 + e.gas_nonlinearity_per_m2 * xd * xd) +
                     e.fluid_mass_kg * ad + e.force_offset_n;
    // Each filter's output at t_j has seen its input up to t_(j−1), held over each step; the
    // acquisition's anti-alias filter follows the force low-pass.
    const double stage1 = e.force_filter_s > 0.0 ? channel_n : f;
    run.force_channel_n[j] = e.delay_filter_s > 0.0 ? aa_n : stage1;
    channel_n += filter_gain * (f - channel_n);
    aa_n += aa_gain * (stage1 - aa_n);
    if (states) {
      run.coil_current_a[j] = current;
      run.rod_disp_m[j] = xd;
      run.rod_vel_m_s[j] = vd;
      run.participant_ratio[j] = pr;
      run.temperature_rise_k[j] = temp_k;
    }

    // Advance the states to t + h.
    if (impact) xd += h * vd;
    volume_l += std::abs(vd) * kFlowArea_m2 * h * 1000.0;
    const double power_w = std::max(0.0, fd * vd);
    temp_k = e.cooling_time_s > 0.0
                 ? temp_k * cooling + power_w * e.cooling_time_s * (1.0 - cooling) / e.heat_capacity_j_per_k
                 : temp_k + power_w * h / e.heat_capacity_j_per_k;
    coil.advance(s.current, t, t + h);
    if (play && e.contact_fraction > 0.0) {
      // Backward Euler on the rod position with the actuator's exact
      // displacement over the step (stiff when the contact length is small):
      // x' = x + Δx_a e(x_a' − x'), monotone in x'. e ≤ 1, so the rod never
      // outruns the actuator, and an engaged rod follows it exactly.
      const double xa1 = motion.x_next();
      const double dxa = xa1 - xa;
      const double contact = e.contact_fraction * e.free_play_m;
      double lo = std::min(xd, xd + dxa), hi = std::max(xd, xd + dxa);
      for (int it = 0; it < 60 && hi > lo; ++it) {
        const double mid = 0.5 * (lo + hi);
        (mid - xd - smooth_rod_velocity(xa1, dxa, mid, half_play, contact) > 0.0 ? hi : lo) = mid;
      }
      xd = 0.5 * (lo + hi);
    }
  }
  return run;
}

std::vector<double> sample_force(const FineRun& run, const std::vector<double>& t_s, double delay_s) {
  std::vector<double> out(t_s.size());
  const auto& f = run.force_channel_n;
  const double last = static_cast<double>(f.size() - 1);
  for (std::size_t k = 0; k < t_s.size(); ++k) {
    const double pos = std::clamp((t_s[k] - delay_s) / run.step_s, 0.0, last);
    const auto j = static_cast<std::size_t>(std::floor(pos));
    const double w = pos - static_cast<double>(j);
    out[k] = j + 1 < f.size() ? (1.0 - w) * f[j] + w * f[j + 1] : f[j];
  }
  return out;
}

}  // namespace indep
