#include "host_sim/rths/damper_rths_outputs.hpp"

#include <algorithm>
#include <cmath>

#include "host_sim/io/text.hpp"
#include "host_sim/report/plot.hpp"
#include "host_sim/report/summary_json.hpp"
#include "host_sim/report/time_series.hpp"

namespace mrd::rths {
namespace {

void note_damper_rths_plot(std::vector<std::string>& problems, const report::PlotResult& r,
                           const std::filesystem::path& png) {
  if (!r.ok) problems.push_back(png.filename().string() + ": " + r.reason);
}

std::vector<double> times_k(const std::vector<double>& v, double k) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = v[i] * k;
  return out;
}

}  // namespace

double DamperRthsOutcome::gap_pct() const {
  const double ref = closed_loop.peak_base_displacement_m;
  return ref > 0.0 ? 100.0 * (rths.peak_base_displacement_m - ref) / ref : 0.0;
}

std::string DamperRthsOutcome::status() const {
  const bool finite = std::isfinite(rths.peak_base_displacement_m) && std::isfinite(rths.peak_damper_force_n) &&
                      std::isfinite(rths.peak_tracking_error_m) && std::isfinite(rths.rms_tracking_error_pct);
  const bool grew = rths.peak_base_displacement_m > 2.0 * closed_loop.peak_base_displacement_m;
  return finite && !grew ? "ok" : "unstable";
}

std::vector<std::string> damper_rths_warnings(const DamperRthsSpec& spec, const DamperRthsOutcome& o) {
  const std::string setup = "the actuator's " + io::format_number("%g", 1e3 * spec.delay_s) + " ms delay and " +
                            io::format_number("%g", 1e3 * spec.lag_s) + " ms lag";
  if (o.status() != "ok")
    return {"the RTHS is unstable (its peak base displacement " +
            io::format_number("%.4g", 1e3 * o.rths.peak_base_displacement_m) + " mm, the closed loop's " +
            io::format_number("%.4g", 1e3 * o.closed_loop.peak_base_displacement_m) + " mm) with " + setup + (spec.compensate ? " compensated" : " uncompensated") +
            ": the damper's force, delayed, destabilizes the numerical building (a specimen large against the "
            "building's mass and stiffness); " +
            (spec.compensate ? std::string("a shorter delay or a smaller damper may run")
                             : std::string("--compensate model or a shorter delay may run"))};
  if (std::fabs(o.gap_pct()) > kDamperRthsGapWarning_pct)
    return {"the RTHS's peak base displacement is " + io::format_number("%+.4g", o.gap_pct()) +
            " % off the all-numerical closed loop's (more than " +
            io::format_number("%g", kDamperRthsGapWarning_pct) + " %) with " + setup};
  return {};
}

nlohmann::json damper_rths_summary_json(const DamperRthsSpec& spec, const DamperRthsDescription& d,
                                        const DamperRthsOutcome& o) {
  return nlohmann::json{
      {"status", o.status()},
      {"warnings", damper_rths_warnings(spec, o)},
      {"specimen", "damper"},
      {"building", d.building},
      {"dofs", d.dofs},
      {"damper", d.damper},
      {"fluid", d.fluid},
      {"record", d.record},
      {"pga_g", d.pga_g},
      {"scale_factor", d.scale_factor},
      {"control", d.control},
      {"idle_years", d.idle_years},
      {"duration_s", d.duration_s},
      {"step_s", spec.plant.step_s},
      {"rate_hz", 1.0 / spec.plant.step_s},
      {"delay_s", spec.delay_s},
      {"lag_s", spec.lag_s},
      {"compensation", spec.compensate ? "model" : "none"},
      {"damper_element", static_cast<int>(spec.plant.building.dampers.front().element)},
      {"damper_count", spec.plant.building.dampers.front().count},
      {"peak_base_displacement_m",
       {{"rths", o.rths.peak_base_displacement_m},
        {"closed_loop", o.closed_loop.peak_base_displacement_m},
        {"gap_pct", o.gap_pct()}}},
      {"peak_damper_force_n",
       {{"rths", o.rths.peak_damper_force_n}, {"closed_loop", o.closed_loop.peak_damper_force_n}}},
      {"tracking",
       {{"rms_error_pct", o.rths.rms_tracking_error_pct},
        {"peak_error_m", o.rths.peak_tracking_error_m},
        {"rms_velocity_error_pct", o.rths.rms_velocity_error_pct}}},
      {"sq", o.closed_loop.sq},
      {"closed_loop", "the same building, damper, fluid, record, control mode and idle time without the actuator "
                      "(what mrd sim runs)"},
  };
}

std::vector<std::string> write_damper_rths_outputs(const std::filesystem::path& dir, const DamperRthsSpec& spec,
                                                   const DamperRthsDescription& d, const DamperRthsOutcome& o) {
  report::write_summary_json(dir, damper_rths_summary_json(spec, d, o));

  const DamperRthsRecord& r = o.record;
  const run::ClosedLoopRecord& c = o.closed_loop_record;
  report::TimeSeries ts({"time_s", "target_m", "actuator_m", "actuator_velocity_m_s", "command_m", "force_n",
                         "current_a", "base_displacement_m", "closed_loop_base_displacement_m",
                         "closed_loop_force_n"});
  // Both loops ran over the same record at the same step: one row per tick.
  const std::size_t rows = std::min(r.time_s.size(), c.base_disp_m.size());
  ts.reserve(rows);
  for (std::size_t k = 0; k < rows; ++k)
    ts.add_row({r.time_s[k], r.target_m[k], r.actuator_m[k], r.actuator_velocity_m_s[k], r.command_m[k], r.force_n[k],
                r.current_a[k], r.base_displacement_m[k], c.base_disp_m[k], c.damper_force_n[k]});
  report::write_csv(ts, dir / "tracking.csv");

  std::vector<std::string> problems;
  std::vector<double> error_mm(r.time_s.size());
  for (std::size_t k = 0; k < r.time_s.size(); ++k) error_mm[k] = 1e3 * (r.actuator_m[k] - r.target_m[k]);
  report::MultiPlot tracking;
  tracking.title = "RTHS tracking, " + std::string(spec.compensate ? "model" : "no") + " compensation, delay " +
                   std::to_string(std::lround(1e3 * spec.delay_s)) + " ms";
  tracking.panels.push_back({"", "time [s]", "damper stroke [mm]",
                             {report::Series{"target", r.time_s, times_k(r.target_m, 1e3), "lines"},
                              report::Series{"actuator", r.time_s, times_k(r.actuator_m, 1e3), "lines"}}});
  tracking.panels.push_back(
      {"", "time [s]", "actuator - target [mm]", {report::Series{"error", r.time_s, error_mm, "lines"}}});
  tracking.panels.back().key = false;
  const auto tracking_png = dir / "tracking.png";
  note_damper_rths_plot(problems, report::plot_png(tracking, tracking_png), tracking_png);

  report::MultiPlot base;
  base.title = "RTHS against the all-numerical closed loop (" + d.control + ")";
  base.panels.push_back({"", "time [s]", "base displacement [mm]",
                         {report::Series{"RTHS", r.time_s, times_k(r.base_displacement_m, 1e3), "lines"},
                          report::Series{"closed loop", c.time_s, times_k(c.base_disp_m, 1e3), "lines"}}});
  base.panels.push_back({"", "time [s]", "damper force [kN]",
                         {report::Series{"RTHS", r.time_s, times_k(r.force_n, 1e-3), "lines"},
                          report::Series{"closed loop", c.time_s, times_k(c.damper_force_n, 1e-3), "lines"}}});
  const auto base_png = dir / "base.png";
  note_damper_rths_plot(problems, report::plot_png(base, base_png), base_png);
  return problems;
}

}  // namespace mrd::rths
