#pragma once
/// Up to kMaxLanes closed-loop runs of the thesis plant held side by side,
/// structure-of-arrays: entry [l] of every array belongs to lane l, so one
/// SIMD register holds one quantity of all lanes. The lane kernels
/// (lane_kernel.hpp) step a block with the arithmetic of plant::Plant,
/// operation for operation; what every lane shares (the building's stepping
/// form, the damper, coil and thermal constants) is in SharedModel.
///
/// Plain data only: this header is compiled for several instruction sets.
/// Its structs' special members are trivial or made outside the kernels, and
/// its field walks are instantiated by a kernel only with its own functors
/// (internal linkage), so no copy built for one instruction set is shared.

#include <cstddef>
#include <cstdint>

namespace mrd::batch {

/// Lanes in a block: the widest kernel's (8 doubles, AVX-512).
inline constexpr int kMaxLanes = 8;
inline constexpr int kBlockStates = 12;  ///< building states (6 DOFs × displacement, velocity)
inline constexpr int kBlockDofs = 6;
inline constexpr int kBlockModes = kBlockStates / 2;  ///< 2 × 2 modal blocks
/// What a peak bound adds to cover underflow (add_floor_peaks in lane_kernel.hpp).
inline constexpr double kBoundFloor = 1e-290;
/// The share of the amplitude bound a reach adds for the roundings of the
/// rows' sums (each within 12 u of Σ|c_k q_k|; u = 2⁻⁵³).
inline constexpr double kBoundRounding = 1e-12;

/// The weights of one group of rows' peak bounds (the floors' absolute
/// accelerations, m/s², or the story drifts, m; add_floor_peaks in
/// lane_kernel.hpp): the amplitude bound Σ_j weight[j] ρ_j grows by
/// per_ag |a_g| + per_force |F| a step; the rate bound Σ_j rate_weight[j] ρ_j
/// by rate_per_ag |a_g| + rate_per_force |F|. Each number a T: a double
/// here (PeakBoundModel), a register of copies in the kernels' WideModel.
template <class T>
struct PeakBoundFields {
  T weight[kBlockModes], rate_weight[kBlockModes];
  T per_ag, per_force;            ///< per m/s², per N
  T rate_per_ag, rate_per_force;  ///< per m/s², per N
};
using PeakBoundModel = PeakBoundFields<double>;

/// f(a.x, b.x) for every field x of two PeakBoundFields (of any T each).
template <class A, class B, class F>
[[gnu::always_inline]] constexpr void zip_bound_fields(A& a, B& b, F& f) {
  f(a.weight, b.weight);
  f(a.rate_weight, b.rate_weight);
  f(a.per_ag, b.per_ag);
  f(a.per_force, b.per_force);
  f(a.rate_per_ag, b.rate_per_ag);
  f(a.rate_per_force, b.rate_per_force);
}

/// The numbers of a batch's building, damper, coil and fluid that the
/// kernels' loops read, each a T: a double in SharedModel, a register of
/// copies in the AVX2 and generic kernels' WideModel (lane_kernel.hpp),
/// which zip_loop_fields() fills field by field. No member initializers:
/// the register form's default constructor stays trivial, so that no
/// out-of-line copy of it is emitted with one kernel's instruction set and
/// picked by the linker for another's (SharedModel zeroes its own).
template <class T>
struct LoopConstants {
  // Building (structure::DiscreteBuilding's modal stepping form).
  T blocks[kBlockStates][2];                 ///< rows (2j, 2j+1) of the 2×2 modal blocks B_j
  T gamma[kBlockStates][2];                  ///< T⁻¹Γ: columns a_g (m/s²) and F (N)
  T disp_row[kBlockStates];                  ///< row 0 of T: base displacement from q, m
  T vel_row[kBlockStates];                   ///< row 6 of T: base velocity from q, m/s
  T accel_rows[kBlockDofs][kBlockStates];    ///< rows 6..11 of A·T: ẍ from q
  T disp_rows[kBlockDofs][kBlockStates];     ///< rows 0..5 of T: displacements from q
  T inv_base_mass_per_kg;
  // Bounds on the floors' absolute accelerations and the story drifts.
  PeakBoundFields<T> floor_bound, drift_bound;
  // Damper, Eq. 4.4, 5.10–5.11.
  T fc_a_n, fc_b_n, neg_fc_c_per_a;
  T c0_a_ns_m, c0_b_ns_m, neg_c0_c_per_a;
  T v_tf_m_s;
  // Coil, Eq. 4.5: y ← a y + (1 − a) u per branch, i = w_slow y_slow + w_fast y_fast.
  T a_slow, one_minus_a_slow, a_fast, one_minus_a_fast;
  T weight_slow, weight_fast;
  // Participant ratio, Eq. 5.9: ∫Q += |v| A T.
  T flow_area_m2, volume_unit_m3, step_s;
  // Coil heating: ΔT ← a ΔT + ((1 − a) R_th) i² R.
  T thermal_a, thermal_gain_k_w, resistance_ohm;
  T rated_current_a;  ///< for the time above the rating
};

/// f(a.x, b.x) for every field x of two LoopConstants (of any T each; a
/// field that is an array is passed whole).
template <class A, class B, class F>
[[gnu::always_inline]] constexpr void zip_loop_fields(A& a, B& b, F& f) {
  f(a.blocks, b.blocks);
  f(a.gamma, b.gamma);
  f(a.disp_row, b.disp_row);
  f(a.vel_row, b.vel_row);
  f(a.accel_rows, b.accel_rows);
  f(a.disp_rows, b.disp_rows);
  f(a.inv_base_mass_per_kg, b.inv_base_mass_per_kg);
  zip_bound_fields(a.floor_bound, b.floor_bound, f);
  zip_bound_fields(a.drift_bound, b.drift_bound, f);
  f(a.fc_a_n, b.fc_a_n);
  f(a.fc_b_n, b.fc_b_n);
  f(a.neg_fc_c_per_a, b.neg_fc_c_per_a);
  f(a.c0_a_ns_m, b.c0_a_ns_m);
  f(a.c0_b_ns_m, b.c0_b_ns_m);
  f(a.neg_c0_c_per_a, b.neg_c0_c_per_a);
  f(a.v_tf_m_s, b.v_tf_m_s);
  f(a.a_slow, b.a_slow);
  f(a.one_minus_a_slow, b.one_minus_a_slow);
  f(a.a_fast, b.a_fast);
  f(a.one_minus_a_fast, b.one_minus_a_fast);
  f(a.weight_slow, b.weight_slow);
  f(a.weight_fast, b.weight_fast);
  f(a.flow_area_m2, b.flow_area_m2);
  f(a.volume_unit_m3, b.volume_unit_m3);
  f(a.step_s, b.step_s);
  f(a.thermal_a, b.thermal_a);
  f(a.thermal_gain_k_w, b.thermal_gain_k_w);
  f(a.resistance_ohm, b.resistance_ohm);
  f(a.rated_current_a, b.rated_current_a);
}

namespace detail {
/// The bytes zip_loop_fields() passes: every field once, so they add up to
/// the struct's (doubles only: no padding).
consteval std::size_t zipped_bytes() {
  LoopConstants<double> c{};
  std::size_t bytes = 0;
  auto count = [&bytes](const auto& x, const auto&) { bytes += sizeof x; };
  zip_loop_fields(c, c, count);
  return bytes;
}
}  // namespace detail
static_assert(detail::zipped_bytes() == sizeof(LoopConstants<double>),
              "a field of LoopConstants is missing from zip_loop_fields(), or listed twice");

/// What every lane of a batch shares: the loops' constants (zeroed until
/// set) and how the lanes step the law.
struct SharedModel : LoopConstants<double> {
  SharedModel() : LoopConstants<double>() {}
  bool peak_bounds = false;  ///< every block contracts: the bounds hold (else the floors every tick)
  // The law's form and a calibration's bends of it (physics::LawShape) the
  // lanes step: Eq. 4.4's transition or a tanh one, the current exponents of
  // Eq. 4.2–4.3, the viscous exponent, the spring and the transition time.
  bool scalar_law = false;  ///< a law the lanes do not vectorize: the scalar damper steps it (AnyModel::scalar_damper)
  bool tanh_law = false;  ///< physics::ForceLaw::kBinghamTanh: f_c tanh(v / v_TF) + c_0 v
  double yield_current_exponent = 1.0, viscous_current_exponent = 1.0;
  bool shaped = false;  ///< the force bent by the viscous exponent, the spring or the transition time (MrDamper's bent_)
  double transition_time_s = 0.0;  ///< τ: the band v_TF + τ |v − v[n−1]| / T
  bool has_viscous_exponent = false;
  double viscous_exponent_minus_one = 0.0, viscous_ref_m_s = 0.0;
  double stiffness_n_m = 0.0;  ///< N/m, on the damper's stroke
  bool lost_motion = false;    ///< a lost motion at reversals (LawShape::has_lost_motion)
  double lost_motion_m_per_n = 0.0, lost_motion_share = 0.0;  ///< λ; the share r clamped to [0, 1]
  double lost_motion_band_m_s = 0.0;                         ///< v_p (0: none)
};

/// The state of kMaxLanes runs and what the last tick measured.
struct alignas(64) LaneBlock {
  using Lanes = double[kMaxLanes];

  // State at t_n.
  Lanes q[kBlockStates] = {};  ///< building, modal coordinates
  Lanes y_slow = {}, y_fast = {};  ///< coil branches, A
  Lanes displaced_m3 = {};         ///< ∫|v| A dt
  Lanes a_pr = {}, b_pr = {}, neg_c_pr = {};  ///< Eq. 5.6–5.8 coefficients (−c_PR)
  Lanes pr = {}, fc_n = {}, c0_ns_m = {};     ///< PR and the damper's coefficients at t_n
  Lanes held_force_n = {};         ///< damper force held over the last step
  Lanes base_accel_m_s2 = {};      ///< absolute base acceleration at t_n
  Lanes rise_k = {};               ///< coil temperature rise
  /// exp(−f_c,c |i|), exp(−c_0,c |i|) of Eq. 4.2–4.3 and the |i| they were
  /// computed for (NaN: none yet).
  Lanes exp_fc = {}, exp_c0 = {}, exp_current_a = {};
  /// Bounds on every floor's |ẍ + a_g| (m/s²) and every story's drift (m)
  /// at t_n (SharedModel's peak bounds; 0 at rest): from the amplitudes, the
  /// reach from the last computed value, and the rate bound per step.
  struct PeakBound {
    Lanes amp = {}, reach = {}, rate = {};
  } floor_bound, drift_bound;

  // Peaks and coil figures so far.
  Lanes peak_disp_m = {}, peak_force_n = {}, peak_vel_m_s = {}, peak_current_a = {};
  Lanes peak_floor_accel_m_s2 = {}, peak_base_accel_m_s2 = {}, peak_story_drift_m = {};
  Lanes coil_peak_a = {}, coil_sum_sq_a2 = {}, coil_peak_rise_k = {}, last_command_a = {};
  Lanes ticks_above_rated = {}, command_changes = {};  ///< counts, exact in double below 2^53

  // Ground input: each tick a lane reads *ground[l] · ground_scale[l],
  // then moves ground[l] by ground_stride[l] (0 for an idle lane).
  const double* ground[kMaxLanes] = {};
  Lanes ground_scale = {};
  std::ptrdiff_t ground_stride[kMaxLanes] = {};

  Lanes command_a = {};  ///< u[n] over the step (the command stage's output)

  // What sense() measured at t_n.
  Lanes ground_accel_m_s2 = {}, base_disp_m = {}, base_vel_m_s = {}, damper_force_n = {}, current_a = {};
};

struct AnyModel;  // lane_block_any.hpp
struct AnyBlock;
struct CoreLanesIn;  // core_lanes.hpp
struct CoreLanesOut;

/// One instruction set's kernel.
struct LaneKernel {
  const char* name = "";
  int lanes = 0;  ///< thesis-shape lanes it steps (≤ kMaxLanes); lanes beyond are left untouched
  int any_lanes = 0;  ///< any building's lanes it steps (≤ lanes)
  /// Starts tick n: reads the ground input, fills the sensed values.
  void (*sense)(const SharedModel&, LaneBlock&) = nullptr;
  /// Completes tick n with command_a held over the step.
  void (*advance)(const SharedModel&, LaneBlock&) = nullptr;
  /// `ticks` × (sense, advance) with command_a constant.
  void (*run)(const SharedModel&, LaneBlock&, std::size_t ticks) = nullptr;
  /// run() leaving peak_story_drift_m untouched.
  void (*run_without_drift)(const SharedModel&, LaneBlock&, std::size_t ticks) = nullptr;
  /// y[i] = exp(x[i]) for n values, as the kernel evaluates it.
  void (*exp)(const double* x, double* y, std::size_t n) = nullptr;
  /// The same three steps on any building (lane_block_any.hpp, lane_kernel_any.hpp).
  void (*any_sense)(const AnyModel&, AnyBlock&) = nullptr;
  void (*any_advance)(const AnyModel&, AnyBlock&) = nullptr;
  void (*any_run)(const AnyModel&, AnyBlock&, std::size_t ticks) = nullptr;
  /// The float control core in kMaxLanes lanes, built for this instruction set (core_lanes.hpp).
  void* (*core_make)(const void* prototype, std::size_t bytes) = nullptr;
  void (*core_destroy)(void* core) = nullptr;
  void (*core_reset)(void* core, int lane) = nullptr;
  /// One tick of the cores holding lanes 0 … lanes − 1 (`out` beyond them untouched).
  void (*core_step)(void* core, int lanes, const CoreLanesIn& in, CoreLanesOut& out) = nullptr;
  /// `ticks` × (sense, the core's step, advance) on the thesis-shape lanes, the
  /// controllers' ticks from tick0[l]; lanes with active[l] = 0 keep their command.
  void (*core_run)(const SharedModel&, LaneBlock&, void* core, std::size_t ticks, const std::uint32_t* tick0,
                   const std::int32_t* active) = nullptr;
  /// core_run() leaving peak_story_drift_m untouched.
  void (*core_run_without_drift)(const SharedModel&, LaneBlock&, void* core, std::size_t ticks,
                                 const std::uint32_t* tick0, const std::int32_t* active) = nullptr;
};

/// The kernels this build has. The x86-64-v3 and -v4 kernels run only on
/// CPUs with those instruction sets (batch_run.cpp checks before use).
LaneKernel generic_lane_kernel() noexcept;
#if defined(__x86_64__)
LaneKernel x86_64_v3_lane_kernel() noexcept;
LaneKernel x86_64_v4_lane_kernel() noexcept;
#endif

}  // namespace mrd::batch
