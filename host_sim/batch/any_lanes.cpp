#include "host_sim/batch/any_lanes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <variant>

#include "host_sim/structure/building.hpp"
#include "host_sim/structure/discrete_building.hpp"
#include "mrd/physics/bingham.hpp"
#include "mrd/physics/participant_ratio.hpp"

namespace mrd::batch {
namespace {


/// `m` (R×C) row-major.
std::vector<double> row_major(const structure::Matrix& m) {
  std::vector<double> out(static_cast<std::size_t>(m.rows() * m.cols()));
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) out[static_cast<std::size_t>(r * m.cols() + c)] = m(r, c);
  }
  return out;
}

// The lost motion's plays, called from the kernels (LostMotionCalls): compiled
// here, for the baseline instruction set, as the scalar damper's are.
double play_engaged_mean(const void* plays, int index, double stroke_m, double half_width_m) {
  return static_cast<const physics::LostMotionPlay*>(plays)[index].engaged_mean(stroke_m, half_width_m);
}
void play_commit(void* plays, int index, double stroke_m, double half_width_m) {
  static_cast<physics::LostMotionPlay*>(plays)[index].commit(stroke_m, half_width_m);
}

// The scalar dampers of a law the lanes do not vectorize (ScalarDamperCalls).
double damper_force_n(const void* dampers, int index, double velocity_m_s, double stroke_m) {
  return static_cast<const physics::MrDamper*>(dampers)[index].force_n(velocity_m_s, stroke_m);
}
void damper_step(void* dampers, int index, double command_a, double velocity_m_s, double stroke_m) {
  (void)static_cast<physics::MrDamper*>(dampers)[index].step(command_a, velocity_m_s, stroke_m);
}

/// DiscreteBuilding's dot_halving over one lane's column of rows.
double dot_halving(const double* c, const double* q, int n, int l) {
  if (n == 1) return c[0] * q[l];
  const int half = n / 2;
  return dot_halving(c, q, half, l) + dot_halving(c + half, q + half * kMaxLanes, n - half, l);
}

}  // namespace

AnyLanes::AnyLanes(const plant::PlantSpec& spec, const LaneKernel& kernel) : spec_(spec), kernel_(kernel) {
  if (spec.kind != plant::PlantKind::kThesis) throw std::invalid_argument("the batch runs the thesis plant only");
  const structure::BuildingParams& p = spec.building;
  structure::validate(p);
  if (p.dampers.empty()) throw std::invalid_argument("building: the plant needs at least one damper");
  model_.damper = damper_constants(spec);  // throws for a law other than Bingham's

  // The building as plant::Plant::init steps it.
  const int substeps = plant::structural_substeps(p, spec.step_s);
  structure::DiscreteBuilding b;
  b.init(p, spec.step_s / substeps);
  model_.dofs = b.dofs();
  model_.states = 2 * b.dofs();
  model_.modal = b.modal_stepping();
  blocks_ = row_major(b.modal_blocks());
  phi_ = row_major(b.phi());
  gamma_ = row_major(b.stepping_gamma());
  t_rows_ = row_major(b.modal_basis());
  accel_rows_ = row_major(b.accel_rows());
  for (int i = 0; i < model_.dofs; ++i) inv_mass_.push_back(1.0 / p.mass_kg[static_cast<std::size_t>(i)]);
  model_.blocks = blocks_.data();
  model_.phi = phi_.data();
  model_.gamma = gamma_.data();
  model_.t_rows = t_rows_.data();
  model_.accel_rows = accel_rows_.data();
  model_.inv_mass = inv_mass_.data();

  element_of_ = b.force_elements();
  auto slot_of = [&](int e) {
    return static_cast<int>(std::lower_bound(element_of_.begin(), element_of_.end(), e) - element_of_.begin());
  };
  for (const structure::DamperPlacement& d : p.dampers) {
    const int slot = slot_of(static_cast<int>(d.element));
    first_on_slot_.push_back(std::find(damper_slot_.begin(), damper_slot_.end(), slot) == damper_slot_.end());
    damper_slot_.push_back(slot);
    damper_element_.push_back(static_cast<int>(d.element));
    damper_count_.push_back(d.count);
  }
  model_.elements = static_cast<int>(element_of_.size());
  model_.element_of = element_of_.data();
  model_.dampers = static_cast<int>(p.dampers.size());
  model_.damper_element = damper_element_.data();
  model_.damper_slot = damper_slot_.data();
  model_.damper_count = damper_count_.data();
  model_.first_on_slot = first_on_slot_.data();
  model_.isolator_slot = p.isolators.empty() ? -1 : slot_of(structure::kBaseDof);
  model_.substeps = substeps;
  model_.first_story = p.base == structure::BaseKind::kFixed ? 0 : 1;

  // The bearings as structure::IsolatorBank::init reads them.
  for (const structure::Isolator& iso : p.isolators) {
    AnyIsolatorGroup g;
    double linear_n_m = 0.0;
    if (const auto* lr = std::get_if<structure::LeadRubberBearing>(&iso)) {
      g.count = lr->count;
      g.strength_n = lr->characteristic_strength_n;
      linear_n_m = lr->post_yield_stiffness_n_m;
      g.dy_m = lr->yield_displacement_m;
      g.exponent = lr->exponent;
    } else {
      const auto& fp = std::get<structure::FrictionPendulumBearing>(iso);
      g.pendulum = true;
      g.count = fp.count;
      g.strength_n = structure::bearing_weight_n(p, fp);
      linear_n_m = g.strength_n / fp.radius_m;
      g.mu_fast = fp.friction_fast;
      g.mu_span = fp.friction_fast - fp.friction_slow;
      g.neg_rate_s_per_m = -fp.rate_s_per_m;
      g.dy_m = fp.yield_displacement_m;
      g.exponent = fp.exponent;
    }
    g.count_linear_n_m = g.count * linear_n_m;
    g.piece_m = g.dy_m / 8.0;
    groups_.push_back(g);
  }
  model_.groups = static_cast<int>(groups_.size());
  model_.group = groups_.data();
  if (model_.damper.lost_motion) {
    plays_.assign(static_cast<std::size_t>(model_.dampers) * kMaxLanes, physics::LostMotionPlay{});
    for (physics::LostMotionPlay& play : plays_) play.init(spec.step_s);
    model_.lost_motion = LostMotionCalls{plays_.data(), &play_engaged_mean, &play_commit};
  }
  if (model_.damper.scalar_law) {
    dampers_.assign(static_cast<std::size_t>(model_.dampers) * kMaxLanes, physics::MrDamper{});
    model_.scalar_damper = ScalarDamperCalls{dampers_.data(), &damper_force_n, &damper_step};
  }

  // The lanes' rows.
  const int states = model_.states, dofs = model_.dofs, dampers = model_.dampers;
  const int counts[] = {states, states, model_.elements, model_.groups, dampers, dampers, dampers, dampers,
                        dampers, dampers, dampers, dampers, dofs, dofs, dofs};
  std::size_t total = 0;
  for (int c : counts) total += static_cast<std::size_t>(c);
  rows_.assign(total, Row{});
  double* at = rows_.data()->v;
  double** targets[] = {&block_.q,       &block_.next,  &block_.held,     &block_.z,      &block_.displaced_m3,
                        &block_.pr,      &block_.fc_n,  &block_.c0_ns_m,  &block_.force_n, &block_.rate_m_s,
                        &block_.last_rate_m_s, &block_.stroke_rows_m, &block_.accel, &block_.disp, &block_.drift_m};
  for (std::size_t k = 0; k < std::size(counts); ++k) {
    *targets[k] = at;
    at += static_cast<std::ptrdiff_t>(counts[k]) * kMaxLanes;
  }
  for (int l = 0; l < kMaxLanes; ++l) rest(l, 1.0);
}

void AnyLanes::rest(int l, double sq) {
  AnyBlock& b = block_;
  for (Row& r : rows_) r.v[l] = 0.0;
  for (double* v : {b.y_slow, b.y_fast, b.base_accel_m_s2, b.rise_k, b.peak_disp_m, b.peak_force_n, b.peak_vel_m_s,
                    b.peak_current_a, b.peak_floor_accel_m_s2, b.peak_base_accel_m_s2, b.peak_stroke_m,
                    b.peak_story_drift_m, b.peak_isolator_force_n, b.coil_peak_a, b.coil_sum_sq_a2,
                    b.coil_peak_rise_k, b.last_command_a, b.ticks_above_rated, b.command_changes, b.command_a,
                    b.isolator_force_n}) {
    v[l] = 0.0;
  }
  // Plant::init: PR and each damper's coefficients at ∫Q = 0 and i = 0 A.
  const physics::PrCoefficients c = physics::pr_coefficients(spec_.damper.pr, sq);
  b.a_pr[l] = c.a_pr;
  b.b_pr[l] = c.b_pr;
  b.neg_c_pr[l] = -c.c_pr;
  const double pr = physics::participant_ratio(c, 0.0 / spec_.damper.pr.volume_unit_m3);
  const double i0_a = model_.damper.weight_slow * 0.0 + model_.damper.weight_fast * 0.0;
  for (int d = 0; d < model_.dampers; ++d) {
    b.pr[d * kMaxLanes + l] = pr;
    b.fc_n[d * kMaxLanes + l] =
        physics::coulomb_force_n(spec_.damper.bingham, i0_a, pr, spec_.damper.shape.yield_current_exponent);
    b.c0_ns_m[d * kMaxLanes + l] =
        physics::viscous_coeff_ns_m(spec_.damper.bingham, i0_a, pr, spec_.damper.shape.viscous_current_exponent);
    if (!plays_.empty()) plays_[static_cast<std::size_t>(d * kMaxLanes + l)].reset();
    // Plant::init: each damper at rest with the run's SQ.
    if (!dampers_.empty()) dampers_[static_cast<std::size_t>(d * kMaxLanes + l)].init(spec_.damper, spec_.step_s, sq);
  }
  // MrDamper::update_coefficients: |f_c(|i|, PR = 1)|.
  b.yield_pr1_n[l] =
      std::fabs(physics::coulomb_force_n(spec_.damper.bingham, i0_a, 1.0, spec_.damper.shape.yield_current_exponent));
  b.exp_current_a[l] = std::numeric_limits<double>::quiet_NaN();
  b.ground[l] = &kNoGround;
  b.ground_scale[l] = 1.0;
  b.ground_stride[l] = 0;
}

void AnyLanes::start(int l, const double* ground, double scale) noexcept {
  block_.ground[l] = ground;
  block_.ground_scale[l] = scale;
  block_.ground_stride[l] = 1;
}

LaneSensed AnyLanes::sensed(int l) const noexcept {
  const AnyBlock& b = block_;
  return LaneSensed{b.ground_accel_m_s2[l], b.stroke_m[l],          b.rate_sensed_m_s[l], b.damper_force_n[l],
                    b.sensed_base_accel_m_s2[l], b.current_a[l], b.pr[l]};
}

void AnyLanes::start_record(run::ClosedLoopRecord& rec, std::size_t n) const {
  for (auto* v : {&rec.time_s, &rec.ground_accel_m_s2, &rec.base_disp_m, &rec.base_vel_m_s, &rec.damper_force_n,
                  &rec.desired_force_n, &rec.command_a, &rec.current_a, &rec.pr, &rec.roof_accel_m_s2,
                  &rec.peak_floor_accel_m_s2, &rec.isolator_force_n}) {
    v->clear();
  }
  for (auto* v : {&rec.time_s, &rec.ground_accel_m_s2, &rec.base_disp_m, &rec.base_vel_m_s, &rec.damper_force_n,
                  &rec.desired_force_n, &rec.command_a, &rec.current_a, &rec.pr, &rec.roof_accel_m_s2,
                  &rec.peak_floor_accel_m_s2}) {
    v->reserve(n);
  }
  if (model_.groups > 0) rec.isolator_force_n.reserve(n);
  rec.story_elements.clear();
  for (int e = model_.first_story; e < model_.dofs; ++e) rec.story_elements.push_back(e);
  rec.story_drift_m.assign(rec.story_elements.size(), {});
  for (auto& v : rec.story_drift_m) v.reserve(n);
}

void AnyLanes::record_after(int l, run::ClosedLoopRecord& rec) const {
  const AnyBlock& b = block_;
  rec.roof_accel_m_s2.push_back(b.roof_accel_m_s2[l]);
  rec.peak_floor_accel_m_s2.push_back(b.floor_peak_m_s2[l]);
  if (model_.groups > 0) rec.isolator_force_n.push_back(b.isolator_force_n[l]);
  for (std::size_t s = 0; s < rec.story_elements.size(); ++s) {
    rec.story_drift_m[s].push_back(row_value(b.drift_m, rec.story_elements[s], l));
  }
}

double AnyLanes::disp_m(int l, int i) const noexcept {
  return dot_halving(model_.t_rows + static_cast<std::ptrdiff_t>(i) * model_.states, block_.q, model_.states, l);
}

plant::PlantSummary AnyLanes::summary(int l, std::size_t ticks, double sq) const {
  const AnyBlock& b = block_;
  plant::PlantSummary s;
  s.ticks = ticks;
  s.sq = sq;
  s.duration_s = static_cast<double>(ticks) * spec_.step_s;
  // Plant::summary: the last state reached counts too.
  s.peak_base_displacement_m = std::max(b.peak_disp_m[l], std::fabs(disp_m(l, 0)));
  const int sensed = model_.damper_element[0];
  const double stroke = sensed == 0 ? disp_m(l, 0) : disp_m(l, sensed) - disp_m(l, sensed - 1);
  s.peak_damper_stroke_m = std::max(b.peak_stroke_m[l], std::fabs(stroke));
  s.peak_damper_force_n = b.peak_force_n[l];
  s.peak_base_velocity_m_s = b.peak_vel_m_s[l];
  s.peak_superstructure_accel_m_s2 = b.peak_floor_accel_m_s2[l];
  s.peak_base_accel_m_s2 = b.peak_base_accel_m_s2[l];
  s.peak_current_a = b.peak_current_a[l];
  s.peak_isolator_force_n = b.peak_isolator_force_n[l];
  s.peak_story_drift_m = b.peak_story_drift_m[l];
  s.final_participant_ratio = b.pr[l];
  s.coil = coil_figures(b.coil_peak_a[l], b.coil_peak_rise_k[l], b.coil_sum_sq_a2[l], b.ticks_above_rated[l],
                        b.command_changes[l], ticks, spec_.step_s);
  return s;
}

}  // namespace mrd::batch
