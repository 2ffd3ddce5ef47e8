#include "host_sim/batch/batch_run.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#if defined(__x86_64__)
#include <cpuid.h>
#endif

#include "host_sim/batch/any_lanes.hpp"
#include "host_sim/batch/core_lanes.hpp"
#include "host_sim/batch/lane_block.hpp"
#include "host_sim/batch/lane_stepper.hpp"
#include "host_sim/batch/peak_bounds.hpp"
#include "host_sim/structure/discrete_building.hpp"
#include "mrd/physics/bingham.hpp"
#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/participant_ratio.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::batch {
namespace {

#if defined(__x86_64__)
/// CPUID leaf `leaf`'s ECX has every bit of `bits`.
bool cpuid_ecx_has(unsigned leaf, unsigned bits) {
  unsigned a = 0, b = 0, c = 0, d = 0;
  return __get_cpuid(leaf, &a, &b, &c, &d) != 0 && (c & bits) == bits;
}
#endif

}  // namespace

bool lane_isa_cpu_runs(LaneIsa isa) {
#if defined(__x86_64__)
  // The x86-64 psABI's levels: v3 is AVX, AVX2, BMI1, BMI2, F16C, FMA, LZCNT,
  // MOVBE and XSAVE; v4 adds AVX-512 F, BW, CD, DQ and VL. The builtin checks
  // that the OS saves the AVX (and AVX-512) state, which needs XSAVE; F16C,
  // LZCNT and MOVBE come from CPUID, as Clang's builtin does not name them.
  const auto v3 = [] {
    return __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") &&
           __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("fma") &&
           cpuid_ecx_has(1, bit_F16C | bit_MOVBE) && cpuid_ecx_has(0x80000001u, bit_LZCNT);
  };
  switch (isa) {
    case LaneIsa::kX86_64V3: return v3();
    case LaneIsa::kX86_64V4:
      return v3() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
             __builtin_cpu_supports("avx512vl");
    default: return true;
  }
#else
  return isa == LaneIsa::kGeneric || isa == LaneIsa::kAuto;
#endif
}

bool lanes_vectorize(const physics::MrDamperParams& d) noexcept {
  // A series compliance's per-step solve is the scalar damper's.
  return (d.law == physics::ForceLaw::kBingham || d.law == physics::ForceLaw::kBinghamTanh) &&
         d.shape.series_compliance_m_per_n == 0.0;
}

SharedModel damper_constants(const plant::PlantSpec& spec) {
  SharedModel m;
  m.scalar_law = !lanes_vectorize(spec.damper);
  // As physics::MrDamper::init reads the shape: bent by m, k, τ or the lost motion (the current exponents act in
  // f_c, c_0); a law the lanes do not vectorize is stepped whole by the scalar damper, its shape with it.
  const physics::LawShape& sh = m.scalar_law ? physics::LawShape{} : spec.damper.shape;
  m.yield_current_exponent = sh.yield_current_exponent;
  m.viscous_current_exponent = sh.viscous_current_exponent;
  m.tanh_law = spec.damper.law == physics::ForceLaw::kBinghamTanh;
  m.has_viscous_exponent = sh.has_viscous_exponent();
  m.shaped = m.has_viscous_exponent || sh.stiffness_n_m != 0.0 || sh.transition_time_s != 0.0;
  m.transition_time_s = sh.transition_time_s;
  m.viscous_exponent_minus_one = sh.viscous_exponent - 1.0;
  m.viscous_ref_m_s = sh.viscous_ref_m_s;
  m.stiffness_n_m = sh.stiffness_n_m;
  m.lost_motion = sh.has_lost_motion();
  m.shaped = m.shaped || m.lost_motion;
  m.lost_motion_m_per_n = sh.lost_motion_m_per_n;
  m.lost_motion_share = std::clamp(sh.lost_motion_share, 0.0, 1.0);
  m.lost_motion_band_m_s = sh.lost_motion_band_m_s;
  const physics::BinghamParams& bp = spec.damper.bingham;
  m.fc_a_n = bp.fc_a_n;
  m.fc_b_n = bp.fc_b_n;
  m.neg_fc_c_per_a = -bp.fc_c_per_a;
  m.c0_a_ns_m = bp.c0_a_ns_m;
  m.c0_b_ns_m = bp.c0_b_ns_m;
  m.neg_c0_c_per_a = -bp.c0_c_per_a;
  m.v_tf_m_s = bp.v_tf_m_s;
  // As physics::CurrentDynamics::init and plant::CoilThermal::init compute them.
  m.a_slow = std::exp(-spec.step_s / spec.damper.coil.tau_slow_s);
  m.a_fast = std::exp(-spec.step_s / spec.damper.coil.tau_fast_s);
  m.one_minus_a_slow = 1.0 - m.a_slow;
  m.one_minus_a_fast = 1.0 - m.a_fast;
  m.weight_slow = spec.damper.coil.weight_slow;
  m.weight_fast = spec.damper.coil.weight_fast;
  m.flow_area_m2 = spec.damper.pr.flow_area_m2;
  m.volume_unit_m3 = spec.damper.pr.volume_unit_m3;
  m.step_s = spec.step_s;
  const physics::CoilHeatParams& heat = spec.damper.coil_heat;
  m.thermal_a = std::exp(-spec.step_s / heat.time_constant_s);
  m.thermal_gain_k_w = (1.0 - m.thermal_a) * heat.thermal_resistance_k_w;
  m.resistance_ohm = heat.resistance_ohm;
  m.rated_current_a = spec.damper.rating.current_a;
  return m;
}

plant::CoilFigures coil_figures(double peak_a, double peak_rise_k, double sum_sq_a2, double ticks_above_rated,
                                double command_changes, std::size_t ticks, double step_s) noexcept {
  // plant::CoilFigureCounter::figures.
  plant::CoilFigures f;
  f.peak_coil_current_a = peak_a;
  f.peak_coil_temperature_rise_k = peak_rise_k;
  if (ticks == 0) return f;
  const double duration_s = static_cast<double>(ticks) * step_s;
  f.rms_coil_current_a = std::sqrt(sum_sq_a2 / static_cast<double>(ticks));
  f.time_above_rated_s = ticks_above_rated * step_s;
  f.command_changes_per_s = command_changes / duration_s;
  return f;
}

namespace {

LaneKernel kernel_of(LaneIsa isa) {
  switch (isa) {
#if defined(__x86_64__)
    case LaneIsa::kX86_64V3: return x86_64_v3_lane_kernel();
    case LaneIsa::kX86_64V4: return x86_64_v4_lane_kernel();
#endif
    default: return generic_lane_kernel();
  }
}

/// The kernel's exp() against the C library's, bit for bit, over the main
/// range, both of its edges and the special cases.
bool exp_agrees(const LaneKernel& k) {
  std::vector<double> x = {0.0, -0.0, 1e-300, -1e-17, 0x1p-55, -0x1p-54, 511.9, -511.9, 512.0, -512.0, -745.2, 710.0};
  for (int i = 0; i < 4000; ++i) x.push_back(-700.0 + 0.3501234567 * i);
  for (int i = 0; i < 4000; ++i) x.push_back(-3.0 + 0.00100007 * i);
  std::vector<double> y(x.size());
  k.exp(x.data(), y.data(), x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double e = std::exp(x[i]);
    if (std::memcmp(&e, &y[i], sizeof e) != 0) return false;
  }
  return true;
}

/// Eigen's order for DiscreteBuilding::disp_m(0) (see lane_kernel.hpp).
double dot_row12(const double* row, const double* q) {
  double p[kBlockStates];
  for (int k = 0; k < kBlockStates; ++k) p[k] = row[k] * q[k];
  const double a = (p[0] + (p[1] + p[2])) + (p[3] + (p[4] + p[5]));
  const double b = (p[6] + (p[7] + p[8])) + (p[9] + (p[10] + p[11]));
  return a + b;
}

/// The thesis's shape: 6 DOFs on linear isolation (no bearings, so no
/// sub-steps), one damper on element 0 with an unbent law, stepped in modal form. Its lanes
/// keep the whole state in registers (lane_kernel.hpp).
bool thesis_shape(const plant::PlantSpec& spec) {
  const structure::BuildingParams& b = spec.building;
  if (spec.kind != plant::PlantKind::kThesis || spec.damper.law != physics::ForceLaw::kBingham ||
      spec.damper.shape.bends() || b.dofs() != kBlockDofs ||
      !b.isolators.empty() ||
      b.dampers.size() != 1 || b.dampers[0].element != 0 || b.dampers[0].count != 1 ||
      b.base != structure::BaseKind::kIsolated) {
    return false;
  }
  structure::DiscreteBuilding d;
  d.init(b, spec.step_s);
  return d.modal_stepping();
}

}  // namespace

SharedModel thesis_shared_model(const plant::PlantSpec& spec) {
  structure::DiscreteBuilding b;
  b.init(spec.building, spec.step_s);
  SharedModel m = damper_constants(spec);
  for (int r = 0; r < kBlockStates; ++r) {
    m.blocks[r][0] = b.modal_blocks()(r, 0);
    m.blocks[r][1] = b.modal_blocks()(r, 1);
    m.gamma[r][0] = b.stepping_gamma()(r, 0);
    m.gamma[r][1] = b.stepping_gamma()(r, 1);
    m.disp_row[r] = b.modal_basis()(structure::kBaseDof, r);
    m.vel_row[r] = b.modal_basis()(b.dofs() + structure::kBaseDof, r);
    for (int i = 0; i < kBlockDofs; ++i) m.accel_rows[i][r] = b.accel_rows()(i, r);
    for (int i = 0; i < kBlockDofs; ++i) m.disp_rows[i][r] = b.modal_basis()(i, r);
  }
  // The story drifts' first row is the base's displacement.
  static_assert(structure::kBaseDof == 0, "disp_rows[0] is disp_row");
  m.inv_base_mass_per_kg = b.inv_base_mass_per_kg();
  set_peak_bounds(m);
  return m;
}

namespace {

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
constexpr int kModes = 3;

bool passive(control::ControlMode m) { return m != control::ControlMode::kSemiActive; }

/// Lanes of the thesis's shape (see thesis_shape), in registers.
class ThesisLanes {
 public:
  ThesisLanes(const plant::PlantSpec& spec, const LaneKernel& kernel, bool story_drift)
      : spec_(spec),
        kernel_(kernel),
        model_(thesis_shared_model(spec)),
        block_(std::make_unique<LaneBlock>()),
        run_(story_drift ? kernel.run : kernel.run_without_drift),
        core_run_(story_drift ? kernel.core_run : kernel.core_run_without_drift) {
    for (int l = 0; l < kMaxLanes; ++l) rest(l, 1.0);
  }

  int lanes() const noexcept { return kernel_.lanes; }
  const LaneKernel& kernel() const noexcept { return kernel_; }

  void rest(int l, double sq) {
    LaneBlock& b = *block_;
    for (auto& row : b.q) row[l] = 0.0;
    for (double* v : {b.y_slow, b.y_fast, b.displaced_m3, b.held_force_n, b.base_accel_m_s2, b.rise_k,
                      b.floor_bound.amp, b.floor_bound.reach, b.floor_bound.rate, b.drift_bound.amp,
                      b.drift_bound.reach, b.drift_bound.rate, b.peak_disp_m,
                      b.peak_force_n, b.peak_vel_m_s, b.peak_current_a, b.peak_floor_accel_m_s2,
                      b.peak_base_accel_m_s2, b.peak_story_drift_m, b.coil_peak_a, b.coil_sum_sq_a2,
                      b.coil_peak_rise_k, b.last_command_a, b.ticks_above_rated, b.command_changes, b.command_a}) {
      v[l] = 0.0;
    }
    // Plant::init: PR and the damper's coefficients at ∫Q = 0 and i = 0 A
    // (physics::ParticipantRatio::reset, MrDamper::update_coefficients).
    const physics::PrCoefficients c = physics::pr_coefficients(spec_.damper.pr, sq);
    b.a_pr[l] = c.a_pr;
    b.b_pr[l] = c.b_pr;
    b.neg_c_pr[l] = -c.c_pr;
    b.pr[l] = physics::participant_ratio(c, 0.0 / spec_.damper.pr.volume_unit_m3);
    const double i0_a = model_.weight_slow * 0.0 + model_.weight_fast * 0.0;
    b.fc_n[l] = physics::coulomb_force_n(spec_.damper.bingham, i0_a, b.pr[l]);
    b.c0_ns_m[l] = physics::viscous_coeff_ns_m(spec_.damper.bingham, i0_a, b.pr[l]);
    b.exp_current_a[l] = std::numeric_limits<double>::quiet_NaN();
    b.ground[l] = &kNoGround;
    b.ground_scale[l] = 1.0;
    b.ground_stride[l] = 0;
  }

  void start(int l, const double* ground, double scale) noexcept {
    block_->ground[l] = ground;
    block_->ground_scale[l] = scale;
    block_->ground_stride[l] = 1;
  }
  void set_command(int l, double current_a) noexcept { block_->command_a[l] = current_a; }

  void run(std::size_t ticks) { run_(model_, *block_, ticks); }
  /// `ticks` ticks with the control core's lanes in the loop (LaneKernel::core_run).
  void run_core(void* core, std::size_t ticks, const std::uint32_t* tick0, const std::int32_t* active) {
    core_run_(model_, *block_, core, ticks, tick0, active);
  }
  void sense() { kernel_.sense(model_, *block_); }
  void advance() { kernel_.advance(model_, *block_); }

  LaneSensed sensed(int l) const noexcept {
    const LaneBlock& b = *block_;
    return LaneSensed{b.ground_accel_m_s2[l], b.base_disp_m[l], b.base_vel_m_s[l], b.damper_force_n[l],
                      b.base_accel_m_s2[l],   b.current_a[l],   b.pr[l]};
  }

  plant::PlantSummary summary(int l, std::size_t ticks, double sq) const {
    const LaneBlock& b = *block_;
    plant::PlantSummary s;
    double q[kBlockStates];
    for (int k = 0; k < kBlockStates; ++k) q[k] = b.q[k][l];
    s.ticks = ticks;
    s.sq = sq;
    s.duration_s = static_cast<double>(s.ticks) * spec_.step_s;
    s.peak_base_displacement_m = std::max(b.peak_disp_m[l], std::fabs(dot_row12(model_.disp_row, q)));
    s.peak_damper_stroke_m = s.peak_base_displacement_m;  // the one damper is on element 0
    s.peak_damper_force_n = b.peak_force_n[l];
    s.peak_base_velocity_m_s = b.peak_vel_m_s[l];
    s.peak_superstructure_accel_m_s2 = b.peak_floor_accel_m_s2[l];
    s.peak_base_accel_m_s2 = b.peak_base_accel_m_s2[l];
    s.peak_current_a = b.peak_current_a[l];
    s.peak_story_drift_m = b.peak_story_drift_m[l];
    s.final_participant_ratio = b.pr[l];
    s.coil = coil_figures(b.coil_peak_a[l], b.coil_peak_rise_k[l], b.coil_sum_sq_a2[l], b.ticks_above_rated[l],
                          b.command_changes[l], ticks, spec_.step_s);
    return s;
  }

 private:
  const plant::PlantSpec& spec_;
  const LaneKernel& kernel_;
  SharedModel model_;
  std::unique_ptr<LaneBlock> block_;
  void (*run_)(const SharedModel&, LaneBlock&, std::size_t);
  void (*core_run_)(const SharedModel&, LaneBlock&, void*, std::size_t, const std::uint32_t*, const std::int32_t*);
};

/// Steps the runs of one queue through one set of lanes, a lane taking the
/// next run when its run ends. `Lanes` is ThesisLanes or AnyLanes.
template <class Lanes>
class Batch {
 public:
  Batch(const plant::PlantSpec& spec, Lanes& lanes, std::span<const BatchRun> runs, const BatchOptions& options,
        std::vector<plant::PlantSummary>& out)
      : spec_(spec), lanes_(lanes), runs_(runs), options_(options), out_(out) {}

  void run(const std::vector<std::size_t>& queue) {
    queue_ = &queue;
    next_ = 0;
    const int width = lanes_.lanes();
    for (int l = 0; l < width; ++l) take_next(l);
    for (;;) {
      std::size_t left = std::numeric_limits<std::size_t>::max();
      bool tick_by_tick = false;
      for (int l = 0; l < width; ++l) {
        if (lane_[l].run == kNone) continue;
        left = std::min(left, lane_[l].ticks - lane_[l].tick);
        const BatchRun& r = runs_[lane_[l].run];
        tick_by_tick = tick_by_tick || r.record != nullptr || !passive(r.mode);
      }
      if (left == std::numeric_limits<std::size_t>::max()) return;  // every lane idle
      if (tick_by_tick && core_lanes_only()) {
        run_core_lanes(left);
      } else if (tick_by_tick) {
        tick();
        left = 1;
      } else {
        lanes_.run(left);
      }
      for (int l = 0; l < width; ++l) {
        if (lane_[l].run == kNone) continue;
        lane_[l].tick += left;
        if (lane_[l].tick == lane_[l].ticks) {
          finish(l);
          take_next(l);
        }
      }
    }
  }

 private:
  struct Lane {
    std::size_t run = kNone;
    std::size_t tick = 0;
    std::size_t ticks = 0;
    double sq = 0.0;
    double desired_force_n = 0.0;  ///< the passive core's F_d (0)
    double command_a = 0.0;        ///< u[n]: the passive core's for the run, the semi-active core's this tick
    run::Controller* controller = nullptr;  ///< semi-active, fixed or double build: the lane's own core
    bool in_core_lanes = false;             ///< semi-active, float build: lane l of the core's lanes
  };

  /// The float build's control core in lanes (core_lanes.hpp), built for the
  /// kernel's instruction set: lane l is lane l's controller.
  struct CoreLanes {
    const LaneKernel* kernel = nullptr;
    void* core = nullptr;
    CoreLanes() = default;
    CoreLanes(const CoreLanes&) = delete;
    CoreLanes& operator=(const CoreLanes&) = delete;
    ~CoreLanes() {
      if (core) kernel->core_destroy(core);
    }
  };

  const plant::PlantSpec& spec_;
  Lanes& lanes_;
  std::span<const BatchRun> runs_;
  const BatchOptions& options_;
  std::vector<plant::PlantSummary>& out_;
  std::array<Lane, kMaxLanes> lane_{};
  std::array<std::array<std::unique_ptr<run::Controller>, kModes>, kMaxLanes> controllers_{};
  const std::vector<std::size_t>* queue_ = nullptr;
  std::size_t next_ = 0;
  CoreLanes core_lanes_;

  /// Every running lane is a semi-active lane of the core's lanes, none
  /// records, and the lanes can run the core in their loop.
  bool core_lanes_only() const {
    if constexpr (requires(Lanes& s) { s.run_core(nullptr, 0, nullptr, nullptr); }) {
      for (int l = 0; l < lanes_.lanes(); ++l) {
        const Lane& lane = lane_[l];
        if (lane.run != kNone && (!lane.in_core_lanes || runs_[lane.run].record)) return false;
      }
      return true;
    } else {
      return false;
    }
  }

  /// `ticks` ticks of the lanes with the core's lanes in the loop.
  void run_core_lanes(std::size_t ticks) {
    if constexpr (requires(Lanes& s) { s.run_core(nullptr, 0, nullptr, nullptr); }) {
      std::uint32_t tick0[kMaxLanes] = {};
      std::int32_t active[kMaxLanes] = {};
      for (int l = 0; l < lanes_.lanes(); ++l) {
        if (lane_[l].run == kNone) continue;
        tick0[l] = static_cast<std::uint32_t>(lane_[l].tick);
        active[l] = -1;
      }
      lanes_.run_core(core_lanes(), ticks, tick0, active);
    }
  }

  /// The core's lanes, configured as run::make_controller configures the
  /// float build (which names what a rejected period breaks).
  void* core_lanes() {
    if (!core_lanes_.core) {
      (void)run::make_controller(control::ControlMode::kSemiActive, spec_.step_s, run::NumericKind::kFloat);
      const auto prototype = std::make_unique<CoreLanesPrototype>();
      if (prototype->init(fw::default_controller_config(control::ControlMode::kSemiActive, spec_.step_s)) !=
          fw::ConfigError::kNone) {
        throw std::invalid_argument("the control core's lanes reject the plant's step");
      }
      const LaneKernel& k = lanes_.kernel();
      core_lanes_.core = k.core_make(prototype.get(), sizeof(CoreLanesPrototype));
      if (!core_lanes_.core) throw std::logic_error("the kernel's control core lanes differ from the prototype");
      core_lanes_.kernel = &k;
    }
    return core_lanes_.core;
  }

  run::Controller& controller(int l, control::ControlMode mode) {
    auto& c = controllers_[l][static_cast<int>(mode)];
    if (!c) c = run::make_controller(mode, spec_.step_s, options_.numeric);
    return *c;
  }

  void take_next(int l) {
    Lane& lane = lane_[l];
    lane = Lane{};
    while (next_ < queue_->size()) {
      const std::size_t i = (*queue_)[next_++];
      const BatchRun& r = runs_[i];
      lane.run = i;
      lane.ticks = r.ground_accel_m_s2.size();
      lane.sq = physics::settling_quotient_after_idle(r.idle_time_s, spec_.settling);
      lanes_.rest(l, lane.sq);
      if (r.record) start_record(*r.record, lane.ticks);
      if (lane.ticks == 0) {
        finish(l);
        lane = Lane{};
        continue;
      }
      lanes_.start(l, r.ground_accel_m_s2.data(), r.ground_scale);
      if (!passive(r.mode) && options_.numeric == run::NumericKind::kFloat) {
        void* core = core_lanes();
        core_lanes_.kernel->core_reset(core, l);
        lane.in_core_lanes = true;
        return;
      }
      run::Controller& c = controller(l, r.mode);
      c.reset();
      if (passive(r.mode)) {
        // SAFE-3: a passive core's output ignores its input, so its first
        // tick's command holds for the run.
        const control::ControllerOutput o = c.step(control::ControllerInput{});
        lane.command_a = plant::command_stage_a(run::coil_drive(o));
        lanes_.set_command(l, lane.command_a);
        lane.desired_force_n = o.desired_force_n;
      } else {
        lane.controller = &c;
      }
      return;
    }
    lane = Lane{};
    lanes_.rest(l, 1.0);
  }

  void start_record(run::ClosedLoopRecord& rec, std::size_t n) {
    if constexpr (requires(Lanes& s) { s.start_record(rec, n); }) {
      lanes_.start_record(rec, n);
    } else {
      throw std::logic_error("time series are recorded on any building's lanes");
    }
  }

  /// One tick of every lane, the semi-active lanes' cores in between, as
  /// run::run_closed_loop does it.
  void tick() {
    lanes_.sense();
    std::array<LaneSensed, kMaxLanes> sensed{};
    std::array<double, kMaxLanes> desired{};
    CoreLanesIn core_in;
    bool core_lanes_run = false;
    for (int l = 0; l < lanes_.lanes(); ++l) {
      Lane& lane = lane_[l];
      if (lane.run == kNone) continue;
      sensed[l] = lanes_.sensed(l);
      desired[l] = lane.desired_force_n;
      const LaneSensed& s = sensed[l];
      control::ControllerInput in;
      in.tick = lane.tick;
      in.damper_disp_m = static_cast<float>(s.stroke_m);
      in.damper_force_n = static_cast<float>(s.damper_force_n);
      in.ground_accel_m_s2 = static_cast<float>(s.ground_accel_m_s2);
      in.base_accel_m_s2 = static_cast<float>(s.base_accel_m_s2);
      in.coil_current_a = static_cast<float>(s.current_a);
      if (lane.in_core_lanes) {
        core_lanes_run = true;
        core_in.tick[l] = static_cast<std::uint32_t>(in.tick);
        core_in.disp_m[l] = in.damper_disp_m;
        core_in.force_n[l] = in.damper_force_n;
        core_in.ground_accel_m_s2[l] = in.ground_accel_m_s2;
        core_in.base_accel_m_s2[l] = in.base_accel_m_s2;
        core_in.coil_current_a[l] = in.coil_current_a;
        continue;
      }
      if (!lane.controller) continue;
      const control::ControllerOutput o = lane.controller->step(in);
      lane.command_a = plant::command_stage_a(run::coil_drive(o));
      lanes_.set_command(l, lane.command_a);
      desired[l] = o.desired_force_n;
    }
    if (core_lanes_run) {
      CoreLanesOut o;
      core_lanes_.kernel->core_step(core_lanes(), lanes_.lanes(), core_in, o);
      for (int l = 0; l < lanes_.lanes(); ++l) {
        Lane& lane = lane_[l];
        if (lane.run == kNone || !lane.in_core_lanes) continue;
        // run::coil_drive and plant::command_stage_a, per lane.
        lane.command_a = o.drive_enable[l] != 0 ? static_cast<double>(o.command_a[l]) : 0.0;
        lanes_.set_command(l, lane.command_a);
        desired[l] = o.desired_force_n[l];
      }
    }
    lanes_.advance();
    if constexpr (requires(Lanes& s, run::ClosedLoopRecord& r) { s.record_after(0, r); }) {
      for (int l = 0; l < lanes_.lanes(); ++l) {
        const Lane& lane = lane_[l];
        if (lane.run == kNone || !runs_[lane.run].record) continue;
        run::ClosedLoopRecord& rec = *runs_[lane.run].record;
        const LaneSensed& s = sensed[l];
        rec.time_s.push_back(static_cast<double>(lane.tick) * spec_.step_s);
        rec.ground_accel_m_s2.push_back(s.ground_accel_m_s2);
        rec.base_disp_m.push_back(s.stroke_m);
        rec.base_vel_m_s.push_back(s.rate_m_s);
        rec.damper_force_n.push_back(s.damper_force_n);
        rec.desired_force_n.push_back(desired[l]);
        rec.command_a.push_back(lane.command_a);
        rec.current_a.push_back(s.current_a);
        rec.pr.push_back(s.pr);
        lanes_.record_after(l, rec);
      }
    }
  }

  void finish(int l) {
    const Lane& lane = lane_[l];
    out_[lane.run] = lanes_.summary(l, lane.tick, lane.sq);
    if (!options_.story_drift) out_[lane.run].peak_story_drift_m = std::numeric_limits<double>::quiet_NaN();
  }
};

}  // namespace

const char* lane_isa_name(LaneIsa isa) noexcept {
  switch (isa) {
    case LaneIsa::kAuto: return "auto";
    case LaneIsa::kGeneric: return "generic";
    case LaneIsa::kX86_64V3: return "x86-64-v3";
    case LaneIsa::kX86_64V4: return "x86-64-v4";
  }
  return "unknown";
}

bool lane_isa_available(LaneIsa isa) {
  if (isa == LaneIsa::kAuto || isa == LaneIsa::kGeneric) return true;
  static const bool v3 = lane_isa_cpu_runs(LaneIsa::kX86_64V3) && exp_agrees(kernel_of(LaneIsa::kX86_64V3));
  static const bool v4 = lane_isa_cpu_runs(LaneIsa::kX86_64V4) && exp_agrees(kernel_of(LaneIsa::kX86_64V4));
  return isa == LaneIsa::kX86_64V3 ? v3 : v4;
}

LaneIsa auto_lane_isa() {
  static const LaneIsa chosen = [] {
    for (LaneIsa isa : {LaneIsa::kX86_64V4, LaneIsa::kX86_64V3}) {
      if (lane_isa_available(isa)) return isa;
    }
    return LaneIsa::kGeneric;
  }();
  return chosen;
}

int lane_count(LaneIsa isa, bool any_building) {
  const LaneKernel& k = kernel_of(isa == LaneIsa::kAuto ? auto_lane_isa() : isa);
  return any_building ? k.any_lanes : k.lanes;
}

std::vector<plant::PlantSummary> run_closed_loop_batch(const plant::PlantSpec& plant, std::span<const BatchRun> runs,
                                                       const BatchOptions& options) {
  const LaneIsa isa = options.isa == LaneIsa::kAuto ? auto_lane_isa() : options.isa;
  if (!lane_isa_available(isa)) {
    throw std::invalid_argument(std::string("the ") + lane_isa_name(isa) +
                                " lane kernel does not run here (instruction set, or the C library's exp())");
  }
  if (plant.kind != plant::PlantKind::kThesis) throw std::invalid_argument("the batch runs the thesis plant only");

  const LaneKernel kernel = kernel_of(isa);
  std::vector<plant::PlantSummary> out(runs.size());
  // Passive runs step many ticks per kernel call; semi-active ones tick by
  // tick around their cores. Each kind fills its own lanes.
  std::vector<std::size_t> passive_runs, active_runs;
  bool recorded = false;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    (passive(runs[i].mode) ? passive_runs : active_runs).push_back(i);
    recorded = recorded || runs[i].record != nullptr;
  }
  // Time series (story drifts, isolator force) come from any building's lanes.
  auto run_all = [&](auto& lanes) {
    Batch batch(plant, lanes, runs, options, out);
    batch.run(passive_runs);
    batch.run(active_runs);
  };
  if (thesis_shape(plant) && !recorded) {
    ThesisLanes lanes(plant, kernel, options.story_drift);
    run_all(lanes);
  } else {
    AnyLanes lanes(plant, kernel);
    run_all(lanes);
  }
  return out;
}

}  // namespace mrd::batch
