// The plant's tick on any building (plant::Plant::sense and ::advance with
// structure::DiscreteBuilding, structure::IsolatorBank and several dampers)
// for MRD_BATCH_LANES lanes at once. Included by lane_kernel_*.cpp after
// lane_kernel.hpp, whose vector type and helpers (load, store, splat, vabs,
// vmax, vexp, any, gather_at) it uses, in the same namespace.
//
// Every expression mirrors the scalar one in plant.cpp, discrete_building.cpp
// (dot_halving, sum_in_order, step, abs_accel_m_s2), isolators.cpp and the
// damper's headers, in the same order, so that each lane equals the scalar
// run bit for bit. Branches of the scalar code that depend on the run's
// state become masks; those that depend on the building alone (modal or
// dense stepping, a group's kind and exponent) stay branches.

#include <array>
#include <utility>

#include "host_sim/batch/lane_block_any.hpp"

namespace mrd::batch::MRD_BATCH_NS {
namespace {

[[gnu::always_inline]] inline vd row_at(const double* rows, int k) { return load(rows + k * kMaxLanes); }
[[gnu::always_inline]] inline void row_put(double* rows, int k, vd v) { store(rows + k * kMaxLanes, v); }

/// Σ c[k]·q_k over k < N by halves, recursively (DiscreteBuilding's dot_halving).
template <int N>
[[gnu::always_inline]] inline vd dot_n(const double* c, const double* q) {
  if constexpr (N == 1) {
    return splat(c[0]) * row_at(q, 0);
  } else {
    constexpr int kHalf = N / 2;
    return dot_n<kHalf>(c, q) + dot_n<N - kHalf>(c + kHalf, q + kHalf * kMaxLanes);
  }
}

template <int N>
vd dot_fn(const double* c, const double* q) {
  return dot_n<N>(c, q);
}

using DotFn = vd (*)(const double*, const double*);

template <std::size_t... I>
constexpr std::array<DotFn, sizeof...(I)> dot_table(std::index_sequence<I...>) {
  return {&dot_fn<static_cast<int>(I) + 1>...};
}

/// Unrolled sums for 1..64 terms (buildings of up to 32 DOFs in one call).
constexpr auto kDots = dot_table(std::make_index_sequence<64>{});

vd dot_halving(const double* c, const double* q, int n) {
  if (n <= static_cast<int>(kDots.size())) return kDots[static_cast<std::size_t>(n - 1)](c, q);
  const int half = n / 2;
  return dot_halving(c, q, half) + dot_halving(c + half, q + half * kMaxLanes, n - half);
}

/// Σ c[k]·q_k, k ascending (DiscreteBuilding's sum_in_order).
inline vd sum_in_order(const double* c, const double* q, int n) {
  vd acc = splat(c[0]) * row_at(q, 0);
  for (int k = 1; k < n; ++k) acc = splat(c[k]) * row_at(q, k) + acc;
  return acc;
}

inline vd disp_of(const AnyModel& m, const AnyBlock& b, int i) {
  return dot_halving(m.t_rows + static_cast<std::ptrdiff_t>(i) * m.states, b.q, m.states);
}
inline vd vel_of(const AnyModel& m, const AnyBlock& b, int i) {
  return dot_halving(m.t_rows + static_cast<std::ptrdiff_t>(m.dofs + i) * m.states, b.q, m.states);
}
/// DiscreteBuilding::element_deformation_m.
inline vd deformation_of(const AnyModel& m, const AnyBlock& b, int e) {
  return e == 0 ? disp_of(m, b, 0) : disp_of(m, b, e) - disp_of(m, b, e - 1);
}
/// DiscreteBuilding::element_rate_m_s.
inline vd rate_of(const AnyModel& m, const AnyBlock& b, int e) {
  return e == 0 ? vel_of(m, b, 0) : vel_of(m, b, e) - vel_of(m, b, e - 1);
}

/// MrDamper::force_n: TF(v) · (f_c sgn v + c_0 v), Eq. 4.4, 5.12.
[[gnu::always_inline]] inline vd damper_force(const SharedModel& d, vd v, vd fc, vd c0) {
  const vd zero = splat(0.0);
  const vd sgn = v > zero ? splat(1.0) : (v < zero ? splat(-1.0) : zero);
  const vd speed = vabs(v);
  const vd vtf = splat(d.v_tf_m_s);
  const vd tf = speed <= vtf ? speed / vtf : splat(1.0);
  return tf * (fc * sgn + c0 * v);
}

/// pow(x, y) per lane by glibc's pow(): the scalar damper's own call (std::pow).
inline vd vpow(vd x, double y) {
  vd r;
  for (int l = 0; l < kW; ++l) r[l] = ::pow(x[l], y);
  return r;
}

/// tanh(x) per lane by glibc's tanh(): the scalar damper's own call (std::tanh).
inline vd vtanh(vd x) {
  vd t;
  for (int l = 0; l < kW; ++l) t[l] = ::tanh(x[l]);
  return t;
}

/// physics::bingham_tanh_force_n: f_c tanh(v / band) + c v.
inline vd tanh_force(vd v, vd band, vd fc, vd c) { return fc * vtanh(v / band) + c * v; }

/// The lost motion's play half width λ |f_c(|i|, PR = 1)| / 2 (MrDamper::play_half_width_m).
inline vd play_half_width(const SharedModel& d, const AnyBlock& b) {
  return splat(0.5 * d.lost_motion_m_per_n) * load(b.yield_pr1_n);
}

/// MrDamper::shaped_force_n of damper `damper`'s Bingham law bent by a
/// viscous exponent, a spring, a transition time or a lost motion: TF(v) ·
/// (f_c sgn v + c_eff v) (or the tanh law's f_c tanh(v / band) + c_eff v),
/// times (1 − r) + r e with the play's engagement e (plus (1 − e) f_c
/// tanh(v / v_p)), + k x; c_eff = c_0 (|v|/v_r)^(m−1) (0 at rest), the band
/// v_TF + τ |v − v[n−1]| / T, x the stroke.
inline vd shaped_damper_force(const AnyModel& m, const AnyBlock& b, int damper, vd v, vd v_last, vd stroke, vd fc,
                              vd c0) {
  const SharedModel& d = m.damper;
  const vd zero = splat(0.0);
  const vd av = vabs(v);
  const vd band = d.transition_time_s != 0.0
                      ? splat(d.v_tf_m_s) + splat(d.transition_time_s) * (vabs(v - v_last) / splat(d.step_s))
                      : splat(d.v_tf_m_s);
  vd c_eff = c0;
  if (d.has_viscous_exponent) {
    vd ratio = zero;
    for (int l = 0; l < kW; ++l) ratio[l] = av[l] > 0.0 ? ::pow(av[l] / d.viscous_ref_m_s, d.viscous_exponent_minus_one) : 0.0;
    c_eff = av > zero ? c0 * ratio : zero;
  }
  vd fb;
  if (d.tanh_law) {
    fb = tanh_force(v, band, fc, c_eff);
  } else {
    const vd sgn = v > zero ? splat(1.0) : (v < zero ? splat(-1.0) : zero);
    const vd tf = av < band ? av / band : splat(1.0);
    fb = tf * (fc * sgn + c_eff * v);
  }
  if (d.lost_motion) {
    const vd h = play_half_width(d, b);
    const LostMotionCalls& calls = m.lost_motion;
    vd e = splat(0.0);
    for (int l = 0; l < kW; ++l) e[l] = calls.engaged_mean(calls.plays, damper * kMaxLanes + l, stroke[l], h[l]);
    const vd share = splat(d.lost_motion_share);
    fb = fb * ((splat(1.0) - share) + share * e);
    if (d.lost_motion_band_m_s > 0.0) fb = fb + (splat(1.0) - e) * fc * vtanh(v / splat(d.lost_motion_band_m_s));
  }
  const vd elastic = splat(d.stiffness_n_m) * stroke;
  return fb + elastic;
}

/// IsolatorBank::hysteretic_force_n at the isolation layer's rate `v`.
inline vd hysteretic_force(const AnyModel& m, const AnyBlock& b, vd v) {
  vd f = splat(0.0);
  for (int g = 0; g < m.groups; ++g) {
    const AnyIsolatorGroup& grp = m.group[g];
    const vd z = row_at(b.z, g);
    vd per_bearing;
    if (grp.pendulum) {
      const vd mu = splat(grp.mu_fast) - splat(grp.mu_span) * vexp(splat(grp.neg_rate_s_per_m) * vabs(v));
      per_bearing = (mu * splat(grp.strength_n)) * z;
    } else {
      per_bearing = splat(grp.strength_n) * z;
    }
    f = f + splat(grp.count) * per_bearing;
  }
  return f;
}

/// |z|ⁿ as isolators.cpp forms it.
inline vd abs_power(vd a, double n) {
  if (n == 2.0) return a * a;
  if (n == 1.0) return a;
  vd out;
  for (int l = 0; l < kW; ++l) out[l] = ::pow(a[l], n);
  return out;
}

/// dz/du for a deformation moving in direction s (±1), isolators.cpp's slope().
inline vd bw_slope(vd z, vd s, double dy, double n) {
  const vd zero = splat(0.0);
  const vd sz = s * z;
  const vd sgn = sz > zero ? splat(1.0) : (sz < zero ? splat(-1.0) : zero);
  return (splat(1.0) - abs_power(vabs(z), n) * (splat(0.5) * sgn + splat(0.5))) / splat(dy);
}

/// IsolatorBank::advance over the deformation increments du.
inline void advance_isolators(const AnyModel& m, AnyBlock& b, vd du) {
  const vd zero = splat(0.0);
  const vi active = (du != zero) & (vabs(du) <= splat(__DBL_MAX__));
  if (!any(active)) return;
  const vd s = du > zero ? splat(1.0) : splat(-1.0);
  for (int g = 0; g < m.groups; ++g) {
    const AnyIsolatorGroup& grp = m.group[g];
    vd pieces;
    double most = 1.0;
    for (int l = 0; l < kW; ++l) {
      const double p = active[l] ? __builtin_ceil(__builtin_fabs(du[l]) / grp.piece_m) : 1.0;
      pieces[l] = p < 1.0 ? 1.0 : p;
      most = pieces[l] > most ? pieces[l] : most;
    }
    const vd h = du / pieces;
    const vd half_h = splat(0.5) * h;
    const vd sixth_h = h / splat(6.0);
    vd z = row_at(b.z, g);
    const vd z_before = z;
    for (double k = 0.0; k < most; k += 1.0) {
      const vd k1 = bw_slope(z, s, grp.dy_m, grp.exponent);
      const vd k2 = bw_slope(z + half_h * k1, s, grp.dy_m, grp.exponent);
      const vd k3 = bw_slope(z + half_h * k2, s, grp.dy_m, grp.exponent);
      const vd k4 = bw_slope(z + h * k3, s, grp.dy_m, grp.exponent);
      const vd stepped = z + sixth_h * (((k1 + splat(2.0) * k2) + splat(2.0) * k3) + k4);
      z = splat(k) < pieces ? stepped : z;
    }
    // std::clamp(z, −1, 1).
    const vd one = splat(1.0), minus_one = splat(-1.0);
    z = z < minus_one ? minus_one : (one < z ? one : z);
    row_put(b.z, g, active ? z : z_before);
  }
}

/// DiscreteBuilding::step with a_g and the element forces in b.held.
inline void step_building(const AnyModel& m, AnyBlock& b, vd ag) {
  const int n = m.states;
  const int inputs = 1 + m.elements;
  if (m.modal) {
    for (int j = 0; j < n; j += 2) {
      const vd q0 = row_at(b.q, j), q1 = row_at(b.q, j + 1);
      const double* bj = m.blocks + 2 * j;
      row_put(b.next, j, splat(bj[0]) * q0 + splat(bj[1]) * q1);
      row_put(b.next, j + 1, splat(bj[2]) * q0 + splat(bj[3]) * q1);
    }
  } else {
    for (int r = 0; r < n; ++r) row_put(b.next, r, sum_in_order(m.phi + static_cast<std::ptrdiff_t>(r) * n, b.q, n));
  }
  for (int j = 0; j < n; ++j) row_put(b.next, j, row_at(b.next, j) + splat(m.gamma[j * inputs]) * ag);
  for (int k = 0; k < m.elements; ++k) {
    const vd f = row_at(b.held, k);
    for (int j = 0; j < n; ++j) row_put(b.next, j, row_at(b.next, j) + splat(m.gamma[j * inputs + 1 + k]) * f);
  }
  double* t = b.q;
  b.q = b.next;
  b.next = t;
}

void any_sense(const AnyModel& m, AnyBlock& b) {
  vu addr;
  __builtin_memcpy(&addr, b.ground, sizeof addr);
  vi stride;
  __builtin_memcpy(&stride, b.ground_stride, sizeof stride);
  const vd ag = gather_at(addr) * load(b.ground_scale);
  addr += (vu)(stride * static_cast<std::int64_t>(sizeof(double)));
  __builtin_memcpy(b.ground, &addr, sizeof addr);

  const int sensed = m.damper_element[0];
  const vd x0 = disp_of(m, b, 0);
  const vd stroke = sensed == 0 ? x0 : deformation_of(m, b, sensed);
  for (int d = 0; d < m.dampers; ++d) {
    const int e = m.damper_element[d];
    const vd v = rate_of(m, b, e);
    row_put(b.rate_m_s, d, v);
    if (m.damper.scalar_law || m.damper.shaped) {
      // The damper's stroke: its element's deformation (the first damper's is the sensed one).
      const vd x = d == 0 ? stroke : deformation_of(m, b, e);
      row_put(b.stroke_rows_m, d, x);
      vd f = splat(0.0);
      if (m.damper.scalar_law) {
        const ScalarDamperCalls& calls = m.scalar_damper;
        for (int l = 0; l < kW; ++l) f[l] = calls.force_n(calls.dampers, d * kMaxLanes + l, v[l], x[l]);
      } else {
        f = shaped_damper_force(m, b, d, v, row_at(b.last_rate_m_s, d), x, row_at(b.fc_n, d), row_at(b.c0_ns_m, d));
      }
      row_put(b.force_n, d, f);
    } else if (m.damper.tanh_law) {
      row_put(b.force_n, d, tanh_force(v, splat(m.damper.v_tf_m_s), row_at(b.fc_n, d), row_at(b.c0_ns_m, d)));
    } else {
      row_put(b.force_n, d, damper_force(m.damper, v, row_at(b.fc_n, d), row_at(b.c0_ns_m, d)));
    }
  }
  store(b.ground_accel_m_s2, ag);
  store(b.stroke_m, stroke);
  store(b.rate_sensed_m_s, row_at(b.rate_m_s, 0));
  store(b.damper_force_n, row_at(b.force_n, 0));
  store(b.sensed_base_accel_m_s2, load(b.base_accel_m_s2));
  store(b.peak_disp_m, vmax(load(b.peak_disp_m), vabs(x0)));
  store(b.current_a, splat(m.damper.weight_slow) * load(b.y_slow) + splat(m.damper.weight_fast) * load(b.y_fast));
}

void any_advance(const AnyModel& m, AnyBlock& b) {
  const SharedModel& s = m.damper;
  const vd zero = splat(0.0);
  const vd u = load(b.command_a);
  const vd current = load(b.current_a);

  // MrDamper::step of each damper: coil (Eq. 4.5; one command, so one coil
  // state for all), participant ratio (Eq. 5.9), then f_c, c_0.
  const vd y_slow = splat(s.a_slow) * load(b.y_slow) + splat(s.one_minus_a_slow) * u;
  const vd y_fast = splat(s.a_fast) * load(b.y_fast) + splat(s.one_minus_a_fast) * u;
  store(b.y_slow, y_slow);
  store(b.y_fast, y_fast);
  if (s.scalar_law) {
    // Plant::advance: MrDamper::step of each damper at the rate and stroke sense() used.
    const ScalarDamperCalls& calls = m.scalar_damper;
    for (int d = 0; d < m.dampers; ++d) {
      const vd v = row_at(b.rate_m_s, d), x = row_at(b.stroke_rows_m, d);
      for (int l = 0; l < kW; ++l) calls.step(calls.dampers, d * kMaxLanes + l, u[l], v[l], x[l]);
    }
  }
  if (s.lost_motion) {
    // MrDamper::step: the play commits this step's stroke before the coil and f_c move on.
    const vd h = play_half_width(s, b);
    const LostMotionCalls& calls = m.lost_motion;
    for (int d = 0; d < m.dampers; ++d) {
      const vd x = row_at(b.stroke_rows_m, d);
      for (int l = 0; l < kW; ++l) calls.commit(calls.plays, d * kMaxLanes + l, x[l], h[l]);
    }
  }
  const vd a_pr = load(b.a_pr), b_pr = load(b.b_pr), neg_c_pr = load(b.neg_c_pr);
  for (int d = 0; d < m.dampers; ++d) {
    const vd v = row_at(b.rate_m_s, d);
    const vd before = row_at(b.displaced_m3, d);
    const vd moved = before + vabs(v) * splat(s.flow_area_m2) * splat(s.step_s);
    const vd displaced = v != zero ? moved : before;
    row_put(b.displaced_m3, d, displaced);
    // MrDamper::advance: v[n−1] of the next step's transition time (read only with one).
    if (s.transition_time_s != 0.0) row_put(b.last_rate_m_s, d, v);
    row_put(b.pr, d, b_pr + (a_pr - b_pr) * vexp(neg_c_pr * (displaced / splat(s.volume_unit_m3))));
  }
  const vd i_next = vabs(splat(s.weight_slow) * y_slow + splat(s.weight_fast) * y_fast);
  if (any((vi)(i_next != load(b.exp_current_a)))) {
    // physics::current_law_decay: |I| raised only when its exponent is not 1.
    const vd i_fc = s.yield_current_exponent == 1.0 ? i_next : vpow(i_next, s.yield_current_exponent);
    const vd i_c0 = s.viscous_current_exponent == 1.0 ? i_next : vpow(i_next, s.viscous_current_exponent);
    store(b.exp_fc, vexp(splat(s.neg_fc_c_per_a) * i_fc));
    store(b.exp_c0, vexp(splat(s.neg_c0_c_per_a) * i_c0));
    store(b.exp_current_a, i_next);
  }
  const vd exp_fc = load(b.exp_fc), exp_c0 = load(b.exp_c0);
  // MrDamper::update_coefficients: |f_c(|i|, PR = 1)| for the play.
  if (s.lost_motion) store(b.yield_pr1_n, vabs(splat(s.fc_b_n) + (splat(s.fc_a_n) - splat(s.fc_b_n)) * exp_fc));
  for (int d = 0; d < m.dampers; ++d) {
    const vd pr = row_at(b.pr, d);
    const vd bf = pr * splat(s.fc_b_n);
    row_put(b.fc_n, d, bf + (splat(s.fc_a_n) - bf) * exp_fc);
    const vd bc = pr * splat(s.c0_b_ns_m);
    row_put(b.c0_ns_m, d, bc + (splat(s.c0_a_ns_m) - bc) * exp_c0);
  }
  // CoilThermal::step with i[n]², CoilFigureCounter::add.
  const vd power_w = (current * current) * splat(s.resistance_ohm);
  const vd rise = splat(s.thermal_a) * load(b.rise_k) + splat(s.thermal_gain_k_w) * power_w;
  store(b.rise_k, rise);
  const vd i_abs = vabs(current);
  store(b.coil_peak_a, vmax(load(b.coil_peak_a), i_abs));
  store(b.coil_sum_sq_a2, load(b.coil_sum_sq_a2) + current * current);
  const vd above = load(b.ticks_above_rated);
  store(b.ticks_above_rated, i_abs > splat(s.rated_current_a) ? above + splat(1.0) : above);
  const vd changes = load(b.command_changes);
  store(b.command_changes, u != load(b.last_command_a) ? changes + splat(1.0) : changes);
  store(b.last_command_a, u);
  store(b.coil_peak_rise_k, vmax(load(b.coil_peak_rise_k), rise));

  // The element forces held over the tick: count × one damper's force per placement.
  vd on_base = zero;
  for (int d = 0; d < m.dampers; ++d) {
    const vd one = row_at(b.force_n, d);
    const vd f = m.damper_count[d] == 1 ? one : splat(static_cast<double>(m.damper_count[d])) * one;
    const int slot = m.damper_slot[d];
    const vd on_slot = m.first_on_slot[d] ? f : row_at(b.held, slot) + f;
    row_put(b.held, slot, on_slot);
    if (slot == m.isolator_slot) on_base = on_slot;
  }
  const vd ag = load(b.ground_accel_m_s2);
  if (m.isolator_slot < 0) {
    step_building(m, b, ag);
  } else {
    for (int k = 0; k < m.substeps; ++k) {
      const vd u0 = disp_of(m, b, 0);
      row_put(b.held, m.isolator_slot, on_base + hysteretic_force(m, b, vel_of(m, b, 0)));
      step_building(m, b, ag);
      advance_isolators(m, b, disp_of(m, b, 0) - u0);
    }
  }

  store(b.peak_stroke_m, vmax(load(b.peak_stroke_m), vabs(load(b.stroke_m))));
  store(b.peak_force_n, vmax(load(b.peak_force_n), vabs(load(b.damper_force_n))));
  store(b.peak_vel_m_s, vmax(load(b.peak_vel_m_s), vabs(load(b.rate_sensed_m_s))));
  store(b.peak_current_a, vmax(load(b.peak_current_a), i_abs));

  // Plant::add_peaks_after_advance: DiscreteBuilding::abs_accel_m_s2(double*).
  const int n = m.dofs;
  for (int i = 0; i < n; ++i) {
    row_put(b.accel, i, sum_in_order(m.accel_rows + static_cast<std::ptrdiff_t>(i) * m.states, b.q, m.states));
  }
  for (int k = 0; k < m.elements; ++k) {
    const int e = m.element_of[k];
    const vd f = row_at(b.held, k);
    row_put(b.accel, e, row_at(b.accel, e) - splat(m.inv_mass[e]) * f);
    if (e > 0) row_put(b.accel, e - 1, row_at(b.accel, e - 1) + splat(m.inv_mass[e - 1]) * f);
  }
  vd floor_peak = zero;
  for (int i = m.first_story; i < n; ++i) floor_peak = vmax(floor_peak, vabs(row_at(b.accel, i)));
  store(b.floor_peak_m_s2, floor_peak);
  store(b.roof_accel_m_s2, row_at(b.accel, n - 1));
  const vd a0 = row_at(b.accel, 0);
  store(b.peak_floor_accel_m_s2, vmax(load(b.peak_floor_accel_m_s2), floor_peak));
  store(b.peak_base_accel_m_s2, vmax(load(b.peak_base_accel_m_s2), vabs(a0)));
  store(b.base_accel_m_s2, a0);
  for (int i = 0; i < n; ++i) row_put(b.disp, i, disp_of(m, b, i));
  vd below = m.first_story == 0 ? zero : row_at(b.disp, 0);
  vd drift_peak = load(b.peak_story_drift_m);
  for (int i = m.first_story; i < n; ++i) {
    const vd x = row_at(b.disp, i);
    const vd drift = x - below;
    row_put(b.drift_m, i, drift);
    drift_peak = vmax(drift_peak, vabs(drift));
    below = x;
  }
  store(b.peak_story_drift_m, drift_peak);
  if (m.groups > 0) {
    // IsolatorBank::total_force_n.
    const vd u_m = row_at(b.disp, 0);
    vd linear = zero;
    for (int g = 0; g < m.groups; ++g) linear = linear + splat(m.group[g].count_linear_n_m) * u_m;
    const vd total = linear + hysteretic_force(m, b, vel_of(m, b, 0));
    store(b.isolator_force_n, total);
    store(b.peak_isolator_force_n, vmax(load(b.peak_isolator_force_n), vabs(total)));
  }
}

void any_run(const AnyModel& m, AnyBlock& b, std::size_t ticks) {
  for (std::size_t t = 0; t < ticks; ++t) {
    any_sense(m, b);
    any_advance(m, b);
  }
}

}  // namespace
}  // namespace mrd::batch::MRD_BATCH_NS
