#include "host_sim/run/sim_run.hpp"

#include <cmath>

#include "host_sim/io/usage_error.hpp"
#include "mrd/units.hpp"

namespace mrd::run {

SimRun run_sim(const SimSpec& spec, Controller& controller) {
  SimRun run;
  run.spec = spec;
  if (spec.record == kNoRecord) {
    if (!(spec.duration_s > 0.0)) throw io::UsageError("--record none needs a --duration-s above 0");
    run.motion.name = "none";
    run.motion.label = "no ground motion";
    run.motion.source = "none (zero ground acceleration)";
    run.motion.accel_m_s2.assign(static_cast<std::size_t>(std::llround(spec.duration_s / spec.step_s)), 0.0);
  } else if (spec.record.empty()) {
    run.motion = synthetic_study_motion(spec.seed, spec.pga_g, spec.step_s,
                                        spec.duration_s > 0.0 ? spec.duration_s : kSyntheticSimDuration_s);
  } else {
    run.motion = load_study_motion(spec.record, spec.pga_g, spec.step_s, spec.duration_s);
  }
  plant::PlantSpec loop;
  loop.step_s = spec.step_s;
  loop.idle_time_s = units::years_to_s(spec.idle_years);
  loop.kind = spec.plant;
  loop.building = spec.building;
  loop.damper = spec.damper;
  loop.settling = spec.settling;
  loop.hardware.drive = spec.hardware_drive;
  loop.hardware.sensors.seed = spec.sensor_seed;
  loop.hardware.stroke_offset_m = spec.stroke_offset_m;
  run.summary = run_closed_loop(loop, run.motion.accel_m_s2, controller, spec.keep_record ? &run.record : nullptr);
  return run;
}

}  // namespace mrd::run
