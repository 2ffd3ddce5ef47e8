// One lane kernel: the plant's tick (plant::Plant::sense and ::advance on
// the thesis plant) for MRD_BATCH_LANES lanes at once, in GCC vector
// extensions. Included once per instruction set by lane_kernel_*.cpp, each
// of which defines MRD_BATCH_LANES, MRD_BATCH_NS (the namespace of its
// copy) and MRD_BATCH_FMA_EXP (1: exp() evaluated in the vector registers
// as glibc's FMA build evaluates it; 0: glibc's exp() per lane).
//
// Equality with the scalar plant rests on doing the same IEEE operations
// in the same order: every expression below mirrors the one in
// mr_damper.hpp, bingham.hpp, participant_ratio.hpp, current_dynamics.hpp,
// coil_thermal.hpp, coil_figures.hpp and discrete_building.cpp, and the
// files are compiled with -ffp-contract=off so that no multiply-add is
// fused that the scalar build (x86-64 baseline, no FMA) does not fuse.
// Only intrinsics, builtins and plain data are used here: an inline
// function shared with other translation units could otherwise be emitted
// with this file's instruction set and picked by the linker for all.

#include <math.h>

#include <cstddef>
#include <cstdint>

#include "host_sim/batch/exp_table.hpp"
#include "host_sim/batch/lane_block.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace mrd::batch::MRD_BATCH_NS {
namespace {

constexpr int kW = MRD_BATCH_LANES;  ///< lanes per register
#ifndef MRD_BATCH_INTERLEAVE
#define MRD_BATCH_INTERLEAVE 1
#endif
/// Register sets of kW lanes a kernel call steps: the thesis-shape lanes are
/// kW · kInterleave wide, so that the core's kMaxLanes float lanes, one step
/// for all of them, serve as many runs as they hold (core_run_ticks).
constexpr int kInterleave = MRD_BATCH_INTERLEAVE;
static_assert(kW * kInterleave <= kMaxLanes);

typedef double vd __attribute__((vector_size(kW * 8)));
typedef std::int64_t vi __attribute__((vector_size(kW * 8)));
typedef std::uint64_t vu __attribute__((vector_size(kW * 8)));

[[gnu::always_inline]] inline vd load(const double* p) {
  vd v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store(double* p, vd v) { __builtin_memcpy(p, &v, sizeof v); }
#if MRD_BATCH_LANES == 8
#define MRD_BATCH_ALL(x) {x, x, x, x, x, x, x, x}
#elif MRD_BATCH_LANES == 4
#define MRD_BATCH_ALL(x) {x, x, x, x}
#elif MRD_BATCH_LANES == 2
#define MRD_BATCH_ALL(x) {x, x}
#else
#error "2, 4 or 8 lanes"
#endif
[[gnu::always_inline]] inline vd splat(double x) { return vd MRD_BATCH_ALL(x); }
/// A constant of WideModel is already a register's worth.
[[gnu::always_inline]] inline vd splat(vd x) { return x; }
[[gnu::always_inline]] inline vi splat_i(std::int64_t x) { return vi MRD_BATCH_ALL(x); }
[[gnu::always_inline]] inline double from_bits(std::uint64_t b) {
  double d;
  __builtin_memcpy(&d, &b, sizeof d);
  return d;
}
/// std::fabs per lane.
[[gnu::always_inline]] inline vd vabs(vd x) { return (vd)((vi)x & splat_i(0x7fffffffffffffffll)); }
/// std::max(a, b) per lane: (a < b) ? b : a.
[[gnu::always_inline]] inline vd vmax(vd a, vd b) { return a < b ? b : a; }

/// Eigen's order for a fixed 12-term dot product of a matrix row (no
/// packets: the row is strided): halves, recursively,
/// ((p0 + (p1 + p2)) + (p3 + (p4 + p5))) + ((p6 + (p7 + p8)) + (p9 + (p10 + p11))).
template <class C>
[[gnu::always_inline]] inline vd dot_row12(const C* row, const vd* q) {
  vd p[kBlockStates];
  for (int k = 0; k < kBlockStates; ++k) p[k] = splat(row[k]) * q[k];
  const vd a = (p[0] + (p[1] + p[2])) + (p[3] + (p[4] + p[5]));
  const vd b = (p[6] + (p[7] + p[8])) + (p[9] + (p[10] + p[11]));
  return a + b;
}

// The few operations GCC's vector extensions lack, by instruction set:
// AVX-512 with 8 lanes; AVX2 with 4 lanes (8 lanes as two halves is supported, and measured 3–4×
// slower than two register sets of 4: MRD_BATCH_INTERLEAVE).
#if defined(__AVX512F__) && MRD_BATCH_LANES == 8
#define MRD_BATCH_X86 512
#elif defined(__AVX2__) && defined(__FMA__)
#define MRD_BATCH_X86 256
typedef double vd4 __attribute__((vector_size(32)));
typedef std::uint64_t vu4 __attribute__((vector_size(32)));
/// Applies `f` to each 4-lane half.
template <class V4, class V, class F>
[[gnu::always_inline]] inline V by_halves(F f) {
  V out;
  for (int h = 0; h < kW / 4; ++h) {
    const V4 part = f(h);
    __builtin_memcpy(reinterpret_cast<char*>(&out) + 32 * h, &part, 32);
  }
  return out;
}
template <class V4, class V>
[[gnu::always_inline]] inline V4 half(const V& v, int h) {
  V4 part;
  __builtin_memcpy(&part, reinterpret_cast<const char*>(&v) + 32 * h, 32);
  return part;
}
#else
#define MRD_BATCH_X86 0
#endif

/// True when any lane of the comparison result `m` is set.
[[gnu::always_inline]] inline bool any(vi m) {
#if MRD_BATCH_X86 == 512
  return _mm512_test_epi64_mask((__m512i)m, (__m512i)m) != 0;
#elif MRD_BATCH_X86 == 256
  bool a = false;
  for (int h = 0; h < kW / 4; ++h) {
    const __m256i part = (__m256i)half<vu4>(m, h);
    a |= _mm256_testz_si256(part, part) == 0;
  }
  return a;
#else
  bool a = false;
  for (int l = 0; l < kW; ++l) a |= m[l] != 0;
  return a;
#endif
}

/// True when every lane of the comparison result `m` is set.
[[gnu::always_inline]] inline bool all(vi m) { return !any(~m); }

/// The doubles at the addresses `addr`, one per lane.
[[gnu::always_inline]] inline vd gather_at(vu addr) {
#if MRD_BATCH_X86 == 512
  return (vd)_mm512_mask_i64gather_pd(_mm512_setzero_pd(), 0xff, (__m512i)addr, nullptr, 1);
#elif MRD_BATCH_X86 == 256
  return by_halves<vd4, vd>(
      [&](int h) { return (vd4)_mm256_i64gather_pd(nullptr, (__m256i)half<vu4>(addr, h), 1); });
#else
  vd v;
  for (int l = 0; l < kW; ++l) v[l] = *reinterpret_cast<const double*>(addr[l]);
  return v;
#endif
}

/// The correctly rounded square root per lane (std::sqrt).
[[gnu::always_inline]] inline vd vsqrt(vd x) {
#if MRD_BATCH_X86 == 512
  return (vd)_mm512_mask_sqrt_pd((__m512d)x, 0xff, (__m512d)x);  // _mm512_sqrt_pd: a false "uninitialized" in GCC 12
#elif MRD_BATCH_X86 == 256
  return by_halves<vd4, vd>([&](int h) { return (vd4)_mm256_sqrt_pd((__m256d)half<vd4>(x, h)); });
#else
  vd y;
  for (int l = 0; l < kW; ++l) y[l] = __builtin_sqrt(x[l]);
  return y;
#endif
}

#if MRD_BATCH_FMA_EXP
#if MRD_BATCH_X86 == 0
#error "the FMA exp needs AVX-512 or AVX2 + FMA"
#endif
/// Entries `idx` of the exp table, one per lane.
[[gnu::always_inline]] inline vu table_at(vu idx) {
#if MRD_BATCH_X86 == 512
  return (vu)_mm512_mask_i64gather_epi64(_mm512_setzero_si512(), 0xff, (__m512i)idx, kExpTable, 8);
#else
  return by_halves<vu4, vu>([&](int h) {
    return (vu4)_mm256_i64gather_epi64(reinterpret_cast<const long long*>(kExpTable), (__m256i)half<vu4>(idx, h), 8);
  });
#endif
}

/// a·b + c rounded once.
[[gnu::always_inline]] inline vd fma(vd a, vd b, vd c) {
#if MRD_BATCH_X86 == 512
  return (vd)_mm512_fmadd_pd((__m512d)a, (__m512d)b, (__m512d)c);
#else
  return by_halves<vd4, vd>([&](int h) {
    return (vd4)_mm256_fmadd_pd((__m256d)half<vd4>(a, h), (__m256d)half<vd4>(b, h), (__m256d)half<vd4>(c, h));
  });
#endif
}

/// exp(x) per lane, bit for bit as glibc's __exp_fma: its operations in its
/// order, the fused multiply-adds where that build fuses them. Lanes outside
/// its main range take glibc's own answer: |x| < 2^-54 gives 1 + x, and
/// |x| ≥ 512 (or NaN) calls exp().
[[gnu::always_inline]] inline vd vexp(vd x) {
  const vi abstop = ((vi)x >> 52) & splat_i(0x7ff);
  const vd kd0 = fma(x, splat(from_bits(kExpInvLn2N)), splat(from_bits(kExpShift)));
  const vu ki = (vu)kd0;
  const vd kd = kd0 - splat(from_bits(kExpShift));
  vd r = fma(kd, splat(from_bits(kExpNegLn2HiN)), x);
  r = fma(kd, splat(from_bits(kExpNegLn2LoN)), r);
  const vu idx = (ki & 127u) * 2u;
  const vu top = ki << 45;
  const vd tail = (vd)table_at(idx);
  const vu sbits = table_at(idx + 1u) + top;
  const vd p23 = fma(r, splat(from_bits(kExpC3)), splat(from_bits(kExpC2)));
  const vd rt = r + tail;
  const vd r2 = r * r;
  const vd p45 = fma(r, splat(from_bits(kExpC5)), splat(from_bits(kExpC4)));
  const vd t1 = fma(p23, r2, rt);
  const vd r4 = r2 * r2;
  const vd tmp = fma(r4, p45, t1);
  const vd scale = (vd)sbits;
  vd y = fma(scale, tmp, scale);
  // glibc: abstop − top12(2^-54) ≥ top12(512) − top12(2^-54) leaves the main path.
  const auto tiny = abstop < splat_i(0x3c9);
  y = tiny ? splat(1.0) + x : y;
  const vi big = abstop >= splat_i(0x408);
  if (__builtin_expect(any(big), 0)) {
    for (int l = 0; l < kW; ++l) {
      if (big[l]) y[l] = ::exp(x[l]);
    }
  }
  return y;
}
#else
/// exp(x) per lane by glibc's exp(): the scalar plant's own call.
[[gnu::always_inline]] inline vd vexp(vd x) {
  vd y;
  for (int l = 0; l < kW; ++l) y[l] = ::exp(x[l]);
  return y;
}
#endif

/// A peak bound's state (LaneBlock::PeakBound) in registers.
struct BoundRegs {
  vd amp, reach, rate;
};
[[gnu::always_inline]] inline void load_bound(const LaneBlock::PeakBound& b, int o, BoundRegs& r) {
  r.amp = load(b.amp + o);
  r.reach = load(b.reach + o);
  r.rate = load(b.rate + o);
}
[[gnu::always_inline]] inline void store_bound(LaneBlock::PeakBound& b, int o, const BoundRegs& r) {
  store(b.amp + o, r.amp);
  store(b.reach + o, r.reach);
  store(b.rate + o, r.rate);
}

/// The block's state in registers.
struct Regs {
  vd q[kBlockStates];
  vd y_slow, y_fast, displaced, a_pr, b_pr, neg_c_pr, pr, fc, c0, held, base_accel, rise;
  vd pk_disp, pk_force, pk_vel, pk_current, pk_floor, pk_base, pk_drift;
  vd coil_peak, coil_sum_sq, coil_peak_rise, last_cmd, above, changes;
  vd exp_fc, exp_c0, exp_current;  ///< the current laws' exp() terms and the |i| they are for
  BoundRegs floor_bound, drift_bound;  ///< bounds on the floors' accelerations and the story drifts (add_floor_peaks)
  vu ground_addr, ground_step;  ///< where each lane reads a_g, and its stride in bytes
  vd ground_scale;
};

[[gnu::always_inline]] inline void load_regs(const LaneBlock& b, int o, Regs& r) {
  for (int k = 0; k < kBlockStates; ++k) r.q[k] = load(b.q[k] + o);
  r.y_slow = load(b.y_slow + o);
  r.y_fast = load(b.y_fast + o);
  r.displaced = load(b.displaced_m3 + o);
  r.a_pr = load(b.a_pr + o);
  r.b_pr = load(b.b_pr + o);
  r.neg_c_pr = load(b.neg_c_pr + o);
  r.pr = load(b.pr + o);
  r.fc = load(b.fc_n + o);
  r.c0 = load(b.c0_ns_m + o);
  r.held = load(b.held_force_n + o);
  r.base_accel = load(b.base_accel_m_s2 + o);
  r.rise = load(b.rise_k + o);
  r.pk_disp = load(b.peak_disp_m + o);
  r.pk_force = load(b.peak_force_n + o);
  r.pk_vel = load(b.peak_vel_m_s + o);
  r.pk_current = load(b.peak_current_a + o);
  r.pk_floor = load(b.peak_floor_accel_m_s2 + o);
  r.pk_base = load(b.peak_base_accel_m_s2 + o);
  r.pk_drift = load(b.peak_story_drift_m + o);
  r.coil_peak = load(b.coil_peak_a + o);
  r.coil_sum_sq = load(b.coil_sum_sq_a2 + o);
  r.coil_peak_rise = load(b.coil_peak_rise_k + o);
  r.last_cmd = load(b.last_command_a + o);
  r.above = load(b.ticks_above_rated + o);
  r.changes = load(b.command_changes + o);
  r.exp_fc = load(b.exp_fc + o);
  r.exp_c0 = load(b.exp_c0 + o);
  r.exp_current = load(b.exp_current_a + o);
  load_bound(b.floor_bound, o, r.floor_bound);
  load_bound(b.drift_bound, o, r.drift_bound);
  __builtin_memcpy(&r.ground_addr, b.ground + o, sizeof r.ground_addr);
  vi stride;
  __builtin_memcpy(&stride, b.ground_stride + o, sizeof stride);
  r.ground_step = (vu)(stride * static_cast<std::int64_t>(sizeof(double)));
  r.ground_scale = load(b.ground_scale + o);
}

[[gnu::always_inline]] inline void store_regs(LaneBlock& b, int o, const Regs& r) {
  for (int k = 0; k < kBlockStates; ++k) store(b.q[k] + o, r.q[k]);
  store(b.y_slow + o, r.y_slow);
  store(b.y_fast + o, r.y_fast);
  store(b.displaced_m3 + o, r.displaced);
  store(b.pr + o, r.pr);
  store(b.fc_n + o, r.fc);
  store(b.c0_ns_m + o, r.c0);
  store(b.held_force_n + o, r.held);
  store(b.base_accel_m_s2 + o, r.base_accel);
  store(b.rise_k + o, r.rise);
  store(b.peak_disp_m + o, r.pk_disp);
  store(b.peak_force_n + o, r.pk_force);
  store(b.peak_vel_m_s + o, r.pk_vel);
  store(b.peak_current_a + o, r.pk_current);
  store(b.peak_floor_accel_m_s2 + o, r.pk_floor);
  store(b.peak_base_accel_m_s2 + o, r.pk_base);
  store(b.peak_story_drift_m + o, r.pk_drift);
  store(b.coil_peak_a + o, r.coil_peak);
  store(b.coil_sum_sq_a2 + o, r.coil_sum_sq);
  store(b.coil_peak_rise_k + o, r.coil_peak_rise);
  store(b.last_command_a + o, r.last_cmd);
  store(b.ticks_above_rated + o, r.above);
  store(b.command_changes + o, r.changes);
  store(b.exp_fc + o, r.exp_fc);
  store(b.exp_c0 + o, r.exp_c0);
  store(b.exp_current_a + o, r.exp_current);
  store_bound(b.floor_bound, o, r.floor_bound);
  store_bound(b.drift_bound, o, r.drift_bound);
  __builtin_memcpy(b.ground + o, &r.ground_addr, sizeof r.ground_addr);
}

/// SharedModel's numbers, each as a register of kW copies: the kernel's
/// loops multiply by them with the operand read from memory, where AVX2 and
/// SSE2 would otherwise load and broadcast each constant before its use (and
/// keep broadcast constants in the registers the lanes' state needs).
/// Made once a kernel call (widen()); the fields are SharedModel's own
/// (LoopConstants), so that sense_regs() and advance_regs() step from
/// either, and widen() fills every one of them (zip_loop_fields(), checked
/// against the struct's size in lane_block.hpp). AVX-512 broadcasts a
/// double in the operand itself: its kernel steps from SharedModel.
struct WideModel : LoopConstants<vd> {
  bool peak_bounds;
};

/// w = s copied into every lane, element by element for an array.
struct Splat {
  [[gnu::always_inline]] void operator()(const double& s, vd& w) const { w = splat(s); }
  template <class S, class W, std::size_t N>
  [[gnu::always_inline]] void operator()(const S (&s)[N], W (&w)[N]) const {
    for (std::size_t i = 0; i < N; ++i) (*this)(s[i], w[i]);
  }
};

inline void widen(const SharedModel& m, WideModel& w) {
  Splat splat_field;
  zip_loop_fields(m, w, splat_field);
  w.peak_bounds = m.peak_bounds;
}

/// The model a kernel loop steps from: see WideModel.
#if MRD_BATCH_X86 == 512
struct LoopModel {};
[[gnu::always_inline]] inline const SharedModel& loop_model(const SharedModel& m, LoopModel&) { return m; }
#else
using LoopModel = WideModel;
[[gnu::always_inline]] inline const WideModel& loop_model(const SharedModel& m, LoopModel& w) {
  widen(m, w);
  return w;
}
#endif

/// What sense() gives advance().
struct Sensed {
  vd ag, x, v, force, current;
};

/// The base displacement from the modal coordinates (DiscreteBuilding::disp_m(0)).
template <class M>
[[gnu::always_inline]] inline vd base_disp(const M& m, const Regs& r) { return dot_row12(m.disp_row, r.q); }

/// Plant::sense on the thesis plant; `x` is base_disp(m, r).
template <class M>
[[gnu::always_inline]] inline Sensed sense_regs(const M& m, Regs& r, vd x) {
  Sensed s;
  s.ag = gather_at(r.ground_addr) * r.ground_scale;
  r.ground_addr += r.ground_step;
  s.x = x;
  s.v = dot_row12(m.vel_row, r.q);
  // MrDamper::force_n: TF(v) · (f_c sgn v + c_0 v), Eq. 4.4, 5.12.
  const vd zero = splat(0.0);
  const vd sgn = s.v > zero ? splat(1.0) : (s.v < zero ? splat(-1.0) : zero);
  const vd speed = vabs(s.v);
  const vd vtf = splat(m.v_tf_m_s);
  const vd tf = speed <= vtf ? speed / vtf : splat(1.0);
  s.force = tf * (r.fc * sgn + r.c0 * s.v);
  // CurrentDynamics::current_a.
  s.current = splat(m.weight_slow) * r.y_slow + splat(m.weight_fast) * r.y_fast;
  return s;
}

/// A peak bound's step: W from the amplitudes grows by the step's inputs'
/// term; the reach, from the last computed value, by the rate bound and the
/// same term, and the rate bound by its own (see add_floor_peaks).
template <class G>
[[gnu::always_inline]] inline void grow_bound(const G& g, BoundRegs& b, vd ag_abs, vd force_abs) {
  const vd in = splat(g.per_ag) * ag_abs + splat(g.per_force) * force_abs;
  b.amp = b.amp + in;
  b.reach = b.reach + (b.rate + in);
  b.rate = b.rate + (splat(g.rate_per_ag) * ag_abs + splat(g.rate_per_force) * force_abs);
}

/// True when some lane's bound reaches its `peak`: its rows must be
/// computed. Lanes in `idle` are not counted: a lane at rest with no run
/// (ThesisLanes::rest: state, inputs and command zero) stays exactly at
/// rest, its rows ±0.
[[gnu::always_inline]] inline bool may_rise(const BoundRegs& b, vd peak, vi idle) {
  const vd w = b.amp < b.reach ? b.amp : b.reach;
  return !all((vi)(w + splat(kBoundFloor) < peak) | idle);
}

/// A peak bound set anew on a tick whose rows were computed: `now` is this
/// tick's largest |row|, `rho` the modes' amplitudes.
template <class G>
[[gnu::always_inline]] inline void reset_bound(const G& g, BoundRegs& b, const vd* rho, vd now) {
  vd amp = splat(g.weight[0]) * rho[0];
  vd rate = splat(g.rate_weight[0]) * rho[0];
  for (int j = 1; j < kBlockModes; ++j) {
    amp = amp + splat(g.weight[j]) * rho[j];
    rate = rate + splat(g.rate_weight[j]) * rho[j];
  }
  b.amp = amp;
  b.rate = rate;
  b.reach = now + splat(kBoundRounding) * amp;
}

/// The floors' and the story drifts' peaks of Plant::add_peaks_after_advance
/// on the state step() reached, whose base displacement is `x0`; `s` holds
/// the inputs of that step.
///
/// A tick can raise neither peak in a lane while the lane's bound on every
/// floor's |ẍ + a_g| (every story's |x_i − x_{i−1}|), as the scalar plant
/// computes it with its roundings, stays below the peak: the kernel then
/// leaves the peak as it is, the same double, and computes the floors
/// (drifts) only on ticks where some lane's bound reaches its peak. Two
/// bounds hold at once and the smaller is taken (their weights, with the
/// roundings they cover: peak_bounds.cpp):
///  - from the modes' amplitudes ρ_j = ‖(q_2j, q_2j+1)‖₂: a row's
///    Σ_k |c_k q_k| is at most Σ_j ‖c^(j)‖₂ ρ_j (Cauchy–Schwarz), and a
///    step moves ρ_j to at most ρ_j + ‖γ_j^a‖ |a_g| + ‖γ_j^F‖ |F| since
///    ‖B_j‖₂ < 1 (a damped mode), so the bound grows by the inputs' term;
///  - from the row's value when it was last computed (its reach): a step
///    changes a row by c·((B − I) q + γ^a a_g + γ^F F), at most the rate
///    bound Σ_j ‖c^(j)‖ ‖B_j − I‖₂ ρ_j plus the same inputs' term, and the
///    rate bound grows with the amplitudes.
/// Either is set anew on a tick that computes its rows.
template <bool kStoryDrift, class M>
[[gnu::always_inline]] inline void add_floor_peaks(const M& m, const Sensed& s, Regs& r, vd x0) {
  bool floors = true, drifts = kStoryDrift;
  if (m.peak_bounds) {
    const vd ag = vabs(s.ag);
    const vd force = vabs(s.force);
    const vi idle = (vi)(r.ground_step == 0u);  // no run: its ground input does not move
    grow_bound(m.floor_bound, r.floor_bound, ag, force);
    floors = may_rise(r.floor_bound, r.pk_floor, idle);
    if constexpr (kStoryDrift) {
      grow_bound(m.drift_bound, r.drift_bound, ag, force);
      drifts = may_rise(r.drift_bound, r.pk_drift, idle);
    }
  }
  if (!floors && !drifts) return;
  vd floors_now = splat(0.0), drifts_now = splat(0.0);
  if (floors) {
    // DiscreteBuilding::abs_accel_m_s2(): Eigen's lazy product sums over q in order.
    for (int i = 1; i < kBlockDofs; ++i) {
      vd acc = splat(m.accel_rows[i][0]) * r.q[0];
      for (int k = 1; k < kBlockStates; ++k) acc = splat(m.accel_rows[i][k]) * r.q[k] + acc;
      floors_now = vmax(floors_now, vabs(acc));
    }
    r.pk_floor = vmax(r.pk_floor, floors_now);
  }
  if (drifts) {
    // Story drifts |x_i − x_{i−1}|, i = 1..5, each x_i as DiscreteBuilding::disp_m sums it
    // (row 0 is the base's: disp_rows[0] = disp_row, batch_run.cpp, so x_0 is `x0`).
    vd below = x0;
    for (int i = 1; i < kBlockDofs; ++i) {
      const vd x = dot_row12(m.disp_rows[i], r.q);
      drifts_now = vmax(drifts_now, vabs(x - below));
      below = x;
    }
    r.pk_drift = vmax(r.pk_drift, drifts_now);
  }
  if (!m.peak_bounds) return;
  vd rho[kBlockModes];
  for (int j = 0; j < kBlockModes; ++j) rho[j] = vsqrt(r.q[2 * j] * r.q[2 * j] + r.q[2 * j + 1] * r.q[2 * j + 1]);
  if (floors) reset_bound(m.floor_bound, r.floor_bound, rho, floors_now);
  if (drifts) reset_bound(m.drift_bound, r.drift_bound, rho, drifts_now);
}

/// Plant::advance on the thesis plant with the command stage's output `u`;
/// `x_next` becomes base_disp(m, r) of the new state.
template <bool kStoryDrift, class M>
[[gnu::always_inline]] inline void advance_regs(const M& m, const Sensed& s, vd u, Regs& r, vd& x_next) {
  // MrDamper::step: coil (Eq. 4.5), then PR (Eq. 5.9), then f_c, c_0.
  r.y_slow = splat(m.a_slow) * r.y_slow + splat(m.one_minus_a_slow) * u;
  r.y_fast = splat(m.a_fast) * r.y_fast + splat(m.one_minus_a_fast) * u;
  const vd zero = splat(0.0);
  const vd moved = r.displaced + vabs(s.v) * splat(m.flow_area_m2) * splat(m.step_s);
  r.displaced = s.v != zero ? moved : r.displaced;
  // Unmoved lanes recompute the same PR from the same ∫Q.
  r.pr = r.b_pr + (r.a_pr - r.b_pr) * vexp(r.neg_c_pr * (r.displaced / splat(m.volume_unit_m3)));
  const vd i_next = vabs(splat(m.weight_slow) * r.y_slow + splat(m.weight_fast) * r.y_fast);
  // The current laws' exp() terms depend on |i| alone: while no lane's |i|
  // changed (a constant command, once the coil has settled to its last
  // bit), the previous values are the same doubles.
  if (any((vi)(i_next != r.exp_current))) {
    r.exp_fc = vexp(splat(m.neg_fc_c_per_a) * i_next);
    r.exp_c0 = vexp(splat(m.neg_c0_c_per_a) * i_next);
    r.exp_current = i_next;
  }
  const vd bf = r.pr * splat(m.fc_b_n);
  r.fc = bf + (splat(m.fc_a_n) - bf) * r.exp_fc;
  const vd bc = r.pr * splat(m.c0_b_ns_m);
  r.c0 = bc + (splat(m.c0_a_ns_m) - bc) * r.exp_c0;
  // CoilThermal::step with i[n]².
  const vd power_w = (s.current * s.current) * splat(m.resistance_ohm);
  r.rise = splat(m.thermal_a) * r.rise + splat(m.thermal_gain_k_w) * power_w;
  // CoilFigureCounter::add.
  const vd i_abs = vabs(s.current);
  r.coil_peak = vmax(r.coil_peak, i_abs);
  r.coil_sum_sq = r.coil_sum_sq + s.current * s.current;
  r.above = i_abs > splat(m.rated_current_a) ? r.above + splat(1.0) : r.above;
  r.changes = u != r.last_cmd ? r.changes + splat(1.0) : r.changes;
  r.last_cmd = u;
  r.coil_peak_rise = vmax(r.coil_peak_rise, r.rise);
  // DiscreteBuilding::step (modal form).
  vd next[kBlockStates];
  for (int j = 0; j < kBlockStates; j += 2) {
    next[j] = splat(m.blocks[j][0]) * r.q[j] + splat(m.blocks[j][1]) * r.q[j + 1];
    next[j + 1] = splat(m.blocks[j + 1][0]) * r.q[j] + splat(m.blocks[j + 1][1]) * r.q[j + 1];
  }
  for (int j = 0; j < kBlockStates; ++j) next[j] = next[j] + splat(m.gamma[j][0]) * s.ag;
  for (int j = 0; j < kBlockStates; ++j) next[j] = next[j] + splat(m.gamma[j][1]) * s.force;
  for (int j = 0; j < kBlockStates; ++j) r.q[j] = next[j];
  r.held = s.force;
  // Plant::advance's peaks.
  r.pk_disp = vmax(r.pk_disp, vabs(s.x));
  r.pk_force = vmax(r.pk_force, vabs(s.force));
  r.pk_vel = vmax(r.pk_vel, vabs(s.v));
  r.pk_current = vmax(r.pk_current, i_abs);
  // DiscreteBuilding::abs_accel_m_s2(0): Eigen's lazy product sums over q in order.
  vd a0 = splat(m.accel_rows[0][0]) * r.q[0];
  for (int k = 1; k < kBlockStates; ++k) a0 = splat(m.accel_rows[0][k]) * r.q[k] + a0;
  a0 = a0 - splat(m.inv_base_mass_per_kg) * r.held;
  r.pk_base = vmax(r.pk_base, vabs(a0));
  r.base_accel = a0;
  x_next = base_disp(m, r);
  add_floor_peaks<kStoryDrift>(m, s, r, x_next);
}

// The kernel steps kInterleave register sets of kW lanes in one loop, so
// that one set's dependency chains (q → v → F → q; v → ∫Q → exp → PR →
// f_c → F) can overlap another's; with one set it is plain SIMD.

void sense(const SharedModel& m, LaneBlock& b) {
  for (int h = 0; h < kInterleave; ++h) {
    const int o = h * kW;
    Regs r;
    load_regs(b, o, r);
    const Sensed s = sense_regs(m, r, base_disp(m, r));
    __builtin_memcpy(b.ground + o, &r.ground_addr, sizeof r.ground_addr);
    store(b.ground_accel_m_s2 + o, s.ag);
    store(b.base_disp_m + o, s.x);
    store(b.base_vel_m_s + o, s.v);
    store(b.damper_force_n + o, s.force);
    store(b.current_a + o, s.current);
  }
}

void advance(const SharedModel& m, LaneBlock& b) {
  for (int h = 0; h < kInterleave; ++h) {
    const int o = h * kW;
    Regs r;
    load_regs(b, o, r);
    Sensed s;
    s.ag = load(b.ground_accel_m_s2 + o);
    s.x = load(b.base_disp_m + o);
    s.v = load(b.base_vel_m_s + o);
    s.force = load(b.damper_force_n + o);
    s.current = load(b.current_a + o);
    vd x_next;
    advance_regs<true>(m, s, load(b.command_a + o), r, x_next);
    store_regs(b, o, r);
  }
}

template <bool kStoryDrift>
void run_ticks(const SharedModel& shared, LaneBlock& b, std::size_t ticks) {
  if (ticks == 0) return;
  LoopModel wide;
  const auto& m = loop_model(shared, wide);
  Regs r[kInterleave];
  vd u[kInterleave], x[kInterleave];
  for (int h = 0; h < kInterleave; ++h) {
    load_regs(b, h * kW, r[h]);
    u[h] = load(b.command_a + h * kW);
    x[h] = base_disp(m, r[h]);
  }
  for (std::size_t t = 0; t < ticks; ++t) {
    Sensed s[kInterleave];
    for (int h = 0; h < kInterleave; ++h) s[h] = sense_regs(m, r[h], x[h]);
    for (int h = 0; h < kInterleave; ++h) advance_regs<kStoryDrift>(m, s[h], u[h], r[h], x[h]);
  }
  for (int h = 0; h < kInterleave; ++h) store_regs(b, h * kW, r[h]);
}

void run(const SharedModel& m, LaneBlock& b, std::size_t ticks) { run_ticks<true>(m, b, ticks); }
/// run() without the story drifts' peak.
void run_without_drift(const SharedModel& m, LaneBlock& b, std::size_t ticks) { run_ticks<false>(m, b, ticks); }

void exp_n(const double* x, double* y, std::size_t n) {
  std::size_t i = 0;
  for (; i + kW <= n; i += kW) store(y + i, vexp(load(x + i)));
  if (i < n) {
    double in[kW], out[kW];
    for (int l = 0; l < kW; ++l) in[l] = i + static_cast<std::size_t>(l) < n ? x[i + static_cast<std::size_t>(l)] : 0.0;
    store(out, vexp(load(in)));
    for (int l = 0; i + static_cast<std::size_t>(l) < n; ++l) y[i + static_cast<std::size_t>(l)] = out[l];
  }
}

}  // namespace
}  // namespace mrd::batch::MRD_BATCH_NS
