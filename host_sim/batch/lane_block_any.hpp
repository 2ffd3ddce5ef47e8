#pragma once
/// Closed-loop runs of any building (structure::BuildingParams: N DOFs,
/// isolated or fixed-base, lead-rubber and friction-pendulum bearings,
/// dampers on any elements) held side by side in SIMD lanes. The lane
/// kernels (lane_kernel_any.hpp) step a block with the arithmetic of
/// plant::Plant on that building, operation for operation; sizes are known
/// at run time, so the state lives in memory (one cache line per quantity
/// of kMaxLanes lanes) rather than in registers.
///
/// Plain data only: this header is compiled for several instruction sets.
/// The arrays are owned by the caller (batch_run.cpp).

#include <cstddef>
#include <cstdint>

#include "host_sim/batch/lane_block.hpp"

namespace mrd::batch {

/// One group of identical bearings (structure::IsolatorBank's Group).
struct AnyIsolatorGroup {
  bool pendulum = false;
  double count = 1.0;
  double strength_n = 0.0;        ///< Q (lead-rubber) or W (pendulum, per bearing)
  double count_linear_n_m = 0.0;  ///< count · (k_p or W/R), as total_force_n forms it
  double mu_fast = 0.0;           ///< μ_fast
  double mu_span = 0.0;           ///< μ_fast − μ_slow
  double neg_rate_s_per_m = 0.0;  ///< −a of μ(v)
  double dy_m = 1.0;              ///< D_y
  double piece_m = 0.125;         ///< D_y / 8, the largest sub-increment of z's integration
  double exponent = 2.0;          ///< n
};

/// The lost motion's plays (physics::LostMotionPlay), one per damper and
/// lane at [damper · kMaxLanes + lane], stepped through functions compiled
/// for the baseline instruction set (any_lanes.cpp), not the kernel's.
struct LostMotionCalls {
  void* plays = nullptr;
  /// e[n] of play `index` at `stroke_m` with the half width `half_width_m`.
  double (*engaged_mean)(const void* plays, int index, double stroke_m, double half_width_m) = nullptr;
  /// Commits play `index`'s step to `stroke_m`.
  void (*commit)(void* plays, int index, double stroke_m, double half_width_m) = nullptr;
};

/// A damper law the lanes do not vectorize (batch::lanes_vectorize), stepped
/// whole by the scalar damper (physics::MrDamper), one per damper and lane at
/// [damper · kMaxLanes + lane], through functions compiled for the baseline
/// instruction set (any_lanes.cpp).
struct ScalarDamperCalls {
  void* dampers = nullptr;
  /// MrDamper::force_n of damper `index` at the element's rate and deformation.
  double (*force_n)(const void* dampers, int index, double velocity_m_s, double stroke_m) = nullptr;
  /// MrDamper::step of damper `index` with the command stage's current.
  void (*step)(void* dampers, int index, double command_a, double velocity_m_s, double stroke_m) = nullptr;
};

/// What every lane of a batch on one building shares. Matrices are row-major
/// (row r of an R×C matrix at [r·C, r·C + C)).
struct AnyModel {
  SharedModel damper;  ///< the damper, coil and thermal constants (its building fields are unused)

  int dofs = 0;    ///< N
  int states = 0;  ///< 2N
  bool modal = false;
  const double* blocks = nullptr;      ///< states × 2: rows (2j, 2j+1) of B_j (modal)
  const double* phi = nullptr;         ///< states × states (dense stepping)
  const double* gamma = nullptr;       ///< states × (1 + elements): T⁻¹Γ, column 0 for a_g
  const double* t_rows = nullptr;      ///< states × states: T (rows 0..N−1 displacements, N..2N−1 velocities)
  const double* accel_rows = nullptr;  ///< N × states: rows N..2N−1 of A·T
  const double* inv_mass = nullptr;    ///< N: 1/m_i, 1/kg

  int elements = 0;                 ///< loaded elements (structure::force_elements)
  const int* element_of = nullptr;  ///< elements: element index of force slot k
  int dampers = 0;
  const int* damper_element = nullptr;          ///< dampers: the element each damper acts on
  const int* damper_slot = nullptr;             ///< dampers: its force slot
  const unsigned* damper_count = nullptr;       ///< dampers: identical dampers in parallel
  const std::uint8_t* first_on_slot = nullptr;  ///< dampers: 1 for the first damper on its slot
  int isolator_slot = -1;                       ///< the isolators' force slot (element 0), −1: none
  int substeps = 1;                             ///< structural sub-steps a tick (plant::structural_substeps)
  int first_story = 1;                          ///< first superstructure DOF (0 for a fixed base)
  int groups = 0;
  const AnyIsolatorGroup* group = nullptr;
  LostMotionCalls lost_motion{};      ///< damper.lost_motion: the plays
  ScalarDamperCalls scalar_damper{};  ///< damper.scalar_law: the dampers
};

/// The state of kMaxLanes runs of one building, and what the last tick
/// measured. Every pointer is to kMaxLanes doubles per row (row k of a
/// per-state quantity at [k·kMaxLanes, k·kMaxLanes + kMaxLanes)).
struct AnyBlock {
  using Lanes = double[kMaxLanes];

  double* q = nullptr;     ///< states rows: the building in its stepping coordinates
  double* next = nullptr;  ///< states rows: scratch for the step
  double* held = nullptr;  ///< elements rows: the element forces held over the last (sub-)step, N
  double* z = nullptr;     ///< groups rows: the bearings' Bouc–Wen variables
  // Per damper (dampers rows).
  double* displaced_m3 = nullptr;  ///< ∫|v| A dt
  double* pr = nullptr;            ///< participant ratio at t_n
  double* fc_n = nullptr;          ///< f_c at t_n
  double* c0_ns_m = nullptr;       ///< c_0 at t_n
  double* force_n = nullptr;       ///< one damper's force at t_n (sense)
  double* rate_m_s = nullptr;      ///< its element's deformation rate at t_n (sense)
  double* last_rate_m_s = nullptr; ///< the rate its last step took (a transition time's |a|; 0 at rest)
  double* stroke_rows_m = nullptr; ///< its element's deformation at t_n (sense; with a spring or a lost motion)
  double* accel = nullptr;         ///< dofs rows: absolute accelerations at t_{n+1}⁻ (scratch)
  double* disp = nullptr;          ///< dofs rows: displacements at t_{n+1} (scratch)
  double* drift_m = nullptr;       ///< dofs rows: element deformations at t_{n+1} (stories from first_story)

  // Per lane.
  alignas(64) Lanes y_slow = {}, y_fast = {};
  Lanes a_pr = {}, b_pr = {}, neg_c_pr = {};
  Lanes exp_fc = {}, exp_c0 = {}, exp_current_a = {};
  Lanes yield_pr1_n = {};  ///< |f_c(|i|, PR = 1)| at t_n: the lost motion's play is λ times it
  Lanes base_accel_m_s2 = {}, rise_k = {};
  Lanes peak_disp_m = {}, peak_force_n = {}, peak_vel_m_s = {}, peak_current_a = {};
  Lanes peak_floor_accel_m_s2 = {}, peak_base_accel_m_s2 = {};
  Lanes peak_stroke_m = {}, peak_story_drift_m = {}, peak_isolator_force_n = {};
  Lanes coil_peak_a = {}, coil_sum_sq_a2 = {}, coil_peak_rise_k = {}, last_command_a = {};
  Lanes ticks_above_rated = {}, command_changes = {};

  const double* ground[kMaxLanes] = {};
  Lanes ground_scale = {};
  std::ptrdiff_t ground_stride[kMaxLanes] = {};

  Lanes command_a = {};

  // What sense() measured at t_n (the first damper's element is the sensed one).
  Lanes ground_accel_m_s2 = {}, stroke_m = {}, rate_sensed_m_s = {}, damper_force_n = {}, current_a = {};
  Lanes sensed_base_accel_m_s2 = {};
  // What advance() reached at t_{n+1}.
  Lanes roof_accel_m_s2 = {}, floor_peak_m_s2 = {}, isolator_force_n = {};
};

}  // namespace mrd::batch
