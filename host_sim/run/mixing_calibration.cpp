#include "host_sim/run/mixing_calibration.hpp"

#include <cmath>
#include <algorithm>
#include <limits>

#include "host_sim/run/sine_rig.hpp"

namespace mrd::run {

MixingCalibration evaluate_rise_times(const physics::MrDamperParams& damper) {
  MixingCalibration cal;
  cal.flow_area_m2 = damper.pr.flow_area_m2;
  cal.volume_unit_m3 = damper.pr.volume_unit_m3;
  double sum_sq = 0.0;
  int n = 0;
  for (const auto& c : thesis_sine_cases()) {
    const SineMetrics m = run_sine_rig(c.spec, damper);
    cal.cases.push_back({c.name, m.rise_time_90_s, c.rise_time_90_s, m.rise_time_95_s, c.rise_time_95_s});
    for (const auto& [model, thesis] : {std::pair{m.rise_time_90_s, c.rise_time_90_s},
                                        std::pair{m.rise_time_95_s, c.rise_time_95_s}}) {
      // A rise time that never happens within the test counts as a large miss.
      const double r = std::isfinite(model) && model > 0.0 ? std::log(model / thesis) : 5.0;
      sum_sq += r * r;
      ++n;
    }
  }
  cal.rms_log_error = std::sqrt(sum_sq / n);
  return cal;
}

MixingCalibration calibrate_mixing_area(const physics::MrDamperParams& base, double min_area_m2,
                                        double max_area_m2) {
  physics::MrDamperParams p = base;
  p.pr.volume_unit_m3 = 1.0e-3;
  MixingCalibration best;
  best.rms_log_error = std::numeric_limits<double>::infinity();
  const auto search = [&](double lo, double hi, double step) {
    for (double a = lo; a <= hi + 1e-12; a += step) {
      p.pr.flow_area_m2 = a;
      MixingCalibration c = evaluate_rise_times(p);
      if (c.rms_log_error < best.rms_log_error) best = std::move(c);
    }
  };
  search(min_area_m2, max_area_m2, 0.5e-3);
  const double centre = best.flow_area_m2;
  search(std::max(min_area_m2, centre - 0.5e-3), std::min(max_area_m2, centre + 0.5e-3), 0.01e-3);
  return best;
}

}  // namespace mrd::run
