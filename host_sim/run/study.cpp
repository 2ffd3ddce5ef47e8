#include "host_sim/run/study.hpp"

#include <chrono>

#include "mrd/physics/settling.hpp"
#include "mrd/units.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/motions.hpp"

namespace mrd::run {
namespace {

/// One record in one mode: a fresh controller for each of the two runs.
StudyRow run_pair(const StudyMotion& m, control::ControlMode mode, const StudyOptions& o) {
  StudyRow row{m.name, m.label, mode, {}, {}, {}, {}};
  plant::PlantSpec spec;
  spec.step_s = o.step_s;
  spec.building = o.building;
  spec.damper = o.damper;
  spec.settling = o.settling;
  auto mixed_controller = make_controller(mode, o.step_s);
  row.fully_mixed = run_closed_loop(spec, m.accel_m_s2, *mixed_controller, &row.fully_mixed_record);
  spec.idle_time_s = units::years_to_s(o.idle_years);
  auto idle_controller = make_controller(mode, o.step_s);
  row.idle = run_closed_loop(spec, m.accel_m_s2, *idle_controller, &row.idle_record);
  return row;
}

StudySweep run_study_sweep(const std::vector<StudyMotion>& motions, const std::vector<control::ControlMode>& modes,
                           const StudyOptions& o) {
  StudySweep sweep;
  sweep.spec.motions = motions;
  sweep.spec.modes = modes;
  sweep.spec.idle_years = idle_grid(0.0, 1.0, 0.05);
  sweep.spec.base.step_s = o.step_s;
  sweep.spec.base.building = o.building;
  sweep.spec.base.damper = o.damper;
  sweep.spec.base.settling = o.settling;
  sweep.spec.threads = o.threads;
  const auto t0 = std::chrono::steady_clock::now();
  sweep.rows = run_sweep(sweep.spec);
  sweep.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sweep;
}

}  // namespace

StudyResult run_study(const StudyOptions& o) {
  StudyResult result;
  result.options = o;
  const auto motions = thesis_study_motions(o.pga_g, o.step_s);
  result.synthetic_motions = !motions.empty() && motions.front().synthetic;
  const auto modes = available_modes();
  result.modal = structure::modal_analysis(o.building);
  result.max_settling_time_years = units::s_to_years(physics::max_settling_time_s(o.settling));
  result.sine_cases = run_thesis_sine_cases();
  for (const auto& m : motions) {
    for (auto mode : modes) result.rows.push_back(run_pair(m, mode, o));
  }
  if (o.with_sweep) result.sweep = run_study_sweep(motions, modes, o);
  return result;
}

}  // namespace mrd::run
