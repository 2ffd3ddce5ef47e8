#pragma once
// Realistic inputs for timing the control core: the semi-active float core
// driving the thesis's damper model (fully mixed) under an imposed stroke of
// 40 mm at 0.25 Hz plus 8 mm at 1.7 Hz, recorded once. Replaying them makes
// every ODBDCO branch occur in a realistic mix.
#include <cmath>
#include <vector>

#include "firmware/core/damper_controller.hpp"
#include "mrd/physics/mr_damper.hpp"

namespace mrd::bench {

inline std::vector<control::ControllerInput> recorded_inputs(std::size_t n) {
  std::vector<control::ControllerInput> inputs(n);
  physics::MrDamper damper(physics::MrDamperParams{}, 1e-3, 0.0);
  fw::DamperController<num::Float32Policy> c;
  (void)c.init(fw::ControllerConfig{});
  const double w1 = 2.0 * 3.141592653589793 * 0.2508;
  const double w2 = 2.0 * 3.141592653589793 * 1.7;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * 1e-3;
    const double x = 0.04 * std::sin(w1 * t) + 0.008 * std::sin(w2 * t);
    const double v = 0.04 * w1 * std::cos(w1 * t) + 0.008 * w2 * std::cos(w2 * t);
    control::ControllerInput& in = inputs[k];
    in.tick = k;
    in.damper_disp_m = static_cast<float>(x);
    in.damper_force_n = static_cast<float>(damper.force_n(v));
    in.ground_accel_m_s2 = static_cast<float>(std::sin(7.0 * t));
    in.base_accel_m_s2 = static_cast<float>(0.5 * std::sin(5.0 * t));
    in.coil_current_a = static_cast<float>(damper.current_a());
    const control::ControllerOutput out = c.step(in);
    damper.step(out.current_command_a, v);
  }
  return inputs;
}

}  // namespace mrd::bench
