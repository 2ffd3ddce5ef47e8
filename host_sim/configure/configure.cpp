#include "host_sim/configure/configure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <variant>

#include "firmware/core/controller_config.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/structure/building.hpp"
#include "host_sim/structure/modal.hpp"
#include "mrd/units.hpp"

namespace mrd::configure {
namespace {

std::string num(double v, const char* fmt = "%.6g") {
  char b[64];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

/// The isolation layer's effective (secant) stiffness at D: element 0's
/// springs, each bearing group's linear part, and its hysteretic force at
/// full yield over D (lead-rubber Q/D; friction pendulum μ_fast·W/D, the
/// sliding friction at speed), counts included. N/m.
double isolation_secant_stiffness_n_m(const structure::BuildingParams& b, double d_m, std::string& how) {
  double k = b.story_stiffness_n_m[0];
  how = "element 0's springs " + num(k) + " N/m";
  for (const structure::Isolator& iso : b.isolators) {
    if (const auto* lr = std::get_if<structure::LeadRubberBearing>(&iso)) {
      const double ki = lr->count * (lr->post_yield_stiffness_n_m + lr->characteristic_strength_n / d_m);
      k += ki;
      how += " + " + std::to_string(lr->count) + " lead-rubber × (k_p + Q/D) = " + num(ki) + " N/m";
    } else {
      const auto& fp = std::get<structure::FrictionPendulumBearing>(iso);
      const double w = structure::bearing_weight_n(b, fp);
      const double ki = fp.count * (w / fp.radius_m + fp.friction_fast * w / d_m);
      k += ki;
      how += " + " + std::to_string(fp.count) + " friction-pendulum × (W/R + μ_fast W/D) = " + num(ki) + " N/m";
    }
  }
  return k;
}

}  // namespace

Result configure(const Inputs& in) {
  const structure::BuildingParams& b = in.building;
  structure::validate(b);
  if (b.dampers.empty()) throw io::UsageError("configure: the building has no damper ([[damper]] in its file)");
  const physics::MrDamperParams& d = in.damper;
  Result r;
  r.board = in.board;
  app::BoardConfig& board = r.board;
  const double period_s = board.period_s();
  fw::ControllerConfig c = fw::default_controller_config(board.mode, period_s);
  auto put = [&](const std::string& field, double value, const char* unit, const std::string& rule) {
    r.derived.push_back({field, value, unit, rule});
  };

  // RILD, Eq. 6.1: k of the damper's element, ω_f of the building's fundamental mode.
  const int e = static_cast<int>(b.dampers.front().element);
  double k = b.story_stiffness_n_m[static_cast<std::size_t>(e)];
  std::string k_how = "element " + std::to_string(e) + "'s springs";
  structure::BuildingParams linear = b;
  if (e == 0 && !b.isolators.empty()) {
    const double d_m = in.design_displacement_m > 0.0 ? in.design_displacement_m : 0.5 * d.rating.stroke_m;
    k = isolation_secant_stiffness_n_m(b, d_m, k_how);
    k_how = "the isolation layer's secant stiffness at the design displacement D = " + num(d_m) + " m" +
            (in.design_displacement_m > 0.0 ? "" : " (half the damper's rated stroke)") + ": " + k_how;
    linear.story_stiffness_n_m[0] = k;
    linear.isolators.clear();
  }
  c.stiffness_n_m = k;
  put("controller.stiffness_n_m", k, "N/m", "k of Eq. 6.1: " + k_how);
  const structure::ModalResult modes = structure::modal_analysis(linear);
  c.filter_freq_rad_s = 2.0 * units::kPi * modes.frequencies_hz.front();
  put("controller.filter_freq_rad_s", c.filter_freq_rad_s, "rad/s",
      "ω_f of Eq. 6.1: the building's fundamental mode, " + num(modes.frequencies_hz.front(), "%.5g") + " Hz" +
          (linear.isolators.size() != b.isolators.size() ? " (bearings at their secant stiffness)" : ""));
  put("controller.loss_factor", c.loss_factor, "", "η of Eq. 6.1: the thesis's 0.8 (§6.3)");

  // Forces.
  const double f_r = d.rating.force_n;
  c.desired_force_limit_n = 2.0 * f_r;
  put("controller.desired_force_limit_n", c.desired_force_limit_n, "N",
      "2 × the rated force " + num(f_r) + " N (the thesis: 400 kN for 200 kN)");
  c.force_limit_n = 2.5 * f_r;
  put("controller.force_limit_n", c.force_limit_n, "N", "the load cell's guard: 2.5 × the rated force (500 kN)");
  c.force_deadband_n = 0.01 * f_r;
  put("controller.force_deadband_n", c.force_deadband_n, "N", "1 % of the rated force (2 kN)");

  // Currents.
  const double i_r = d.rating.current_a;
  c.command_limit_a = in.drive.command_limit_a;
  c.drive_continuous_limit_a = in.drive.continuous_limit_a;
  c.drive_peak_limit_a = in.drive.peak_limit_a;
  c.coil_current_limit_a = in.drive.peak_limit_a;
  const DriveLimits thesis_drive{};
  const auto drive_rule = [&in](double value, double thesis, const char* what) {
    return std::string("the drive's ") + what +
           (value == thesis ? " (the thesis rig's, §3.2)"
                            : " (" + in.drive_source + "; the thesis rig's: " + num(thesis) + " A)");
  };
  put("controller.command_limit_a", c.command_limit_a, "A",
      drive_rule(c.command_limit_a, thesis_drive.command_limit_a, "command range, ±"));
  put("controller.drive_continuous_limit_a", c.drive_continuous_limit_a, "A",
      drive_rule(c.drive_continuous_limit_a, thesis_drive.continuous_limit_a, "continuous current"));
  put("controller.drive_peak_limit_a", c.drive_peak_limit_a, "A",
      drive_rule(c.drive_peak_limit_a, thesis_drive.peak_limit_a, "peak current (also the coil's current limit)"));
  c.rated_current_a = i_r;
  c.nominal_current_a = i_r;
  c.fallback_current_a = i_r;
  put("controller.rated_current_a", i_r, "A", "the damper's rated current (also passive-on and the fallback)");
  c.overdrive_current_a = std::min(4.0 * i_r, c.command_limit_a);
  c.backdrive_current_a = -c.overdrive_current_a;
  put("controller.overdrive_current_a", c.overdrive_current_a, "A",
      "min(4 × I_r, the command range): the thesis's 10 A for 2.5 A; back-drive its negative");
  c.current_band_a = 0.04 * i_r;
  put("controller.current_band_a", c.current_band_a, "A", "4 % of I_r (the thesis's 0.1 A of 2.5 A)");
  c.coil_thermal_time_constant_s = d.coil_heat.time_constant_s;
  put("controller.coil_thermal_time_constant_s", c.coil_thermal_time_constant_s, "s",
      "the I²t's τ: the damper's coil (its file's [coil] thermal_time_constant_s; absent, the thesis coil's "
      "assumed 20 min)");

  // Direction thresholds from the stroke sensor's noise.
  const double lsb_m = 2.0 * d.rating.stroke_m / std::ldexp(1.0, in.sensor.bits);
  const double sigma_x = std::sqrt(in.sensor.noise_rms_m * in.sensor.noise_rms_m + lsb_m * lsb_m / 12.0);
  const double beta = 1.0 - std::exp(-2.0 * units::kPi * c.velocity_cutoff_hz * period_s);
  const double sigma_v = sigma_x * beta / period_s * std::sqrt(2.0 / (2.0 - beta));
  c.velocity_on_m_s = 10.0 * sigma_v;
  c.velocity_off_m_s = 5.0 * sigma_v;
  put("controller.velocity_on_m_s", c.velocity_on_m_s, "m/s",
      "10 σ_v: the stroke sensor's σ_x = " + num(sigma_x) + " m (" + num(in.sensor.noise_rms_m) + " m RMS and a " +
          num(lsb_m) + " m step) through the velocity estimate at f_v = " + num(c.velocity_cutoff_hz) +
          " Hz gives σ_v = " + num(sigma_v) + " m/s");
  put("controller.velocity_off_m_s", c.velocity_off_m_s, "m/s", "5 σ_v");
  c.disp_limit_m = 1.03 * d.rating.stroke_m;
  put("controller.disp_limit_m", c.disp_limit_m, "m", "1.03 × the rated stroke (the thesis: 0.30 m for 0.2921 m)");

  // Estimator and mixing.
  board.controller = c;
  board.damper = d;
  board.damper_name = in.damper_name;
  board.settling = in.settling;
  board.fluid_name = in.fluid_name;
  board.dead_band_m = 30.0 * sigma_x;
  put("mixing.dead_band_m", board.dead_band_m, "m", "30 σ_x: stroke noise earns no mixing credit");
  board.mixing.max_amplitude_m = 0.26 * d.rating.stroke_m;
  put("mixing.max_amplitude_m", board.mixing.max_amplitude_m, "m", "0.26 × the rated stroke (the thesis's 76 mm)");
  board.mixing.max_velocity_m_s = 0.4 * d.rating.velocity_m_s;
  put("mixing.max_velocity_m_s", board.mixing.max_velocity_m_s, "m/s",
      "0.4 × the rated velocity (the thesis's 0.1 m/s)");
  const double t_max_s = physics::max_settling_time_s(in.settling);
  put("fluid (T_max)", t_max_s / units::kSecondsPerYear, "years",
      in.settling.measured_max_settling_time_s > 0.0 ? "the fluid's measured maximum settling time"
                                                      : "Eq. 5.4 from the fluid (Table 5.3) and the damper's bore");

  // What the core will check at boot, now.
  const fw::ConfigError err = board.fixed_point ? fw::validate_config<num::Fixed32Policy>(c)
                                                : fw::validate_config<num::Float32Policy>(c);
  if (err != fw::ConfigError::kNone) {
    const char* misfit = err == fw::ConfigError::kFixedPointRange ? fw::fixed_point_misfit<num::Fixed32Policy>(c)
                                                                   : nullptr;
    const bool drive_named = misfit != nullptr && (std::string(misfit).rfind("command_limit_a", 0) == 0 ||
                                                   std::string(misfit).rfind("drive_peak_limit_a", 0) == 0 ||
                                                   std::string(misfit).rfind("coil_current_limit_a", 0) == 0);
    throw io::UsageError(std::string("configure: the control core (") + (board.fixed_point ? "fixed" : "float") +
                         " build) refuses the derived configuration: " + fw::config_error_name(err) +
                         (misfit ? std::string(": ") + misfit : std::string()) +
                         (drive_named ? " (a drive of a smaller range: --drive-command-limit-a, "
                                        "--drive-peak-limit-a)"
                                      : ""));
  }
  if (d.law != physics::ForceLaw::kBingham) {
    r.notes.push_back("the damper's force law is not Eq. 4.4's: the estimator's capacity uses its current laws "
                      "with the Bingham form");
  }
  r.notes.push_back("the coil's derating starts at " + num(c.coil_derate_fraction) +
                    " of I_r² held (the thesis coil's fraction, whatever this coil's thermal resistance)");
  return r;
}

/// The unit scales the fixed-point core runs `c` at (firmware/core/numeric_formats.hpp), each with its rule.
std::string fixed_point_scales_markdown(const fw::ControllerConfig& c) {
  const fw::CoreScales s = fw::core_scales<num::Fixed32Policy>(c);
  const auto p2 = [](int e) { return "2^" + std::to_string(e); };
  std::string md = "\n## Fixed-point scales\n\nThe fixed-point core counts each quantity in a unit that is a power "
                   "of two chosen for this configuration (firmware/core/numeric_formats.hpp):\n\n"
                   "| scale | value | rule | one count |\n|---|---|---|---|\n";
  md += "| s_D, strokes | " + p2(s.disp_exp) + " m | disp_limit_m = " + num(c.disp_limit_m) +
        " m within (0.21, 0.42] s_D | " + num(s.disp_m() * std::ldexp(1.0, -28), "%.3g") + " m (Q3.28) |\n";
  md += "| s_F, forces | " + p2(s.force_exp) + " N | the smallest with the largest force limit within 524 288 s_F "
        "and kη s_D/s_F within 8.39e6 N/m | " + num(s.force_n() * std::ldexp(1.0, -12), "%.3g") + " N (Q19.12) |\n";
  md += "| s_I, currents | " + p2(s.current_exp) + " A | rated_current_a = " + num(c.rated_current_a) +
        " A within (1.77, 3.54] s_I | " + num(s.current_a() * std::ldexp(1.0, -24), "%.3g") + " A (Q7.24) |\n";
  md += "| s_V, velocities | " + p2(s.velocity_exp) + " m per tick | 8 s_D m/s × period_s within 4 s_V | " +
        num(s.velocity_m() * std::ldexp(1.0, -28) / c.period_s, "%.3g") + " m/s (Q3.28) |\n";
  return md;
}

std::string configure_markdown(const Inputs& in, const Result& r) {
  std::string md = "# Board configuration\n\n";
  md += "Board `" + r.board.name + "`, building `" + in.building_name + "` (" +
        std::to_string(in.building.dofs()) + " DOFs), damper `" + in.damper_name + "`, fluid `" + in.fluid_name +
        "`, control period " + num(r.board.period_s()) + " s, " + (r.board.fixed_point ? "fixed" : "float") +
        " build.\n\n| field | value | unit | rule |\n|---|---|---|---|\n";
  for (const Derived& d : r.derived) {
    md += "| `" + d.field + "` | " + num(d.value, "%.6g") + " | " + d.unit + " | " + d.rule + " |\n";
  }
  if (r.board.fixed_point) md += fixed_point_scales_markdown(r.board.controller_config());
  if (!r.notes.empty()) {
    md += "\n## Notes\n\n";
    for (const std::string& n : r.notes) md += "- " + n + "\n";
  }
  md += "\nEvery other key of board.toml is the input board file's; `mrd-firmware` validates the whole file at "
        "boot and `mrd sim --board board.toml` runs the same tables.\n";
  return md;
}

}  // namespace mrd::configure
