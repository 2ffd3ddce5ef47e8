#include "host_sim/run/sim_run.hpp"

#include "mrd/units.hpp"

namespace mrd::run {

SimRun run_sim(const SimSpec& spec, Controller& controller) {
  SimRun run;
  run.spec = spec;
  if (spec.record.empty()) {
    run.motion = synthetic_study_motion(spec.seed, spec.pga_g, spec.step_s,
                                        spec.duration_s > 0.0 ? spec.duration_s : kSyntheticSimDuration_s);
  } else {
    run.motion = load_study_motion(spec.record, spec.pga_g, spec.step_s, spec.duration_s);
  }
  plant::PlantSpec loop;
  loop.step_s = spec.step_s;
  loop.idle_time_s = units::years_to_s(spec.idle_years);
  run.summary = run_closed_loop(loop, run.motion.accel_m_s2, controller, spec.keep_record ? &run.record : nullptr);
  return run;
}

}  // namespace mrd::run
