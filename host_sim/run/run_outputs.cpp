#include "host_sim/run/run_outputs.hpp"

#include "host_sim/run/validity.hpp"

#include <algorithm>

#include "mrd/units.hpp"
#include "host_sim/report/plot.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/report/summary_json.hpp"
#include "host_sim/report/time_series.hpp"

namespace mrd::run {
namespace {

// Plots thin 1 kHz series to 100 Hz: enough for the eye, small files.
constexpr std::size_t kPlotStride = 10;

std::vector<double> thin(const std::vector<double>& v, double scale = 1.0) {
  std::vector<double> out;
  out.reserve(v.size() / kPlotStride + 1);
  for (std::size_t k = 0; k < v.size(); k += kPlotStride) out.push_back(v[k] * scale);
  return out;
}

report::Series series(std::string label, const ClosedLoopRecord& r, const std::vector<double>& y, double scale) {
  return report::Series{std::move(label), thin(r.time_s), thin(y, scale), "lines"};
}

void note(std::vector<std::string>& problems, const report::PlotResult& r, const std::filesystem::path& png) {
  if (!r.ok) problems.push_back(png.filename().string() + ": " + r.reason);
}

}  // namespace

std::vector<ClosedLoopColumn> closed_loop_columns(const ClosedLoopRecord& rec) {
  std::vector<ClosedLoopColumn> columns{{"time_s", &rec.time_s},
                                        {"ground_accel_m_s2", &rec.ground_accel_m_s2},
                                        {"base_disp_m", &rec.base_disp_m},
                                        {"base_vel_m_s", &rec.base_vel_m_s},
                                        {"damper_force_n", &rec.damper_force_n},
                                        {"desired_force_n", &rec.desired_force_n},
                                        {"command_a", &rec.command_a},
                                        {"current_a", &rec.current_a},
                                        {"participant_ratio", &rec.pr},
                                        {"roof_accel_m_s2", &rec.roof_accel_m_s2},
                                        {"peak_floor_accel_m_s2", &rec.peak_floor_accel_m_s2}};
  const std::size_t ticks = rec.time_s.size();
  if (rec.isolator_force_n.size() == ticks && ticks > 0) columns.push_back({"isolator_force_n", &rec.isolator_force_n});
  for (std::size_t st = 0; st < rec.story_elements.size(); ++st) {
    if (rec.story_drift_m[st].size() != ticks) continue;
    columns.push_back({"story_" + std::to_string(rec.story_elements[st]) + "_drift_m", &rec.story_drift_m[st]});
  }
  return columns;
}

std::vector<std::string> write_closed_loop_outputs(const std::filesystem::path& dir, const std::string& stem,
                                                   const std::string& title, const ClosedLoopRecord& rec) {
  const std::vector<ClosedLoopColumn> columns = closed_loop_columns(rec);
  std::vector<std::string> names;
  for (const ClosedLoopColumn& c : columns) names.push_back(c.name);
  const std::size_t ticks = rec.time_s.size();
  report::TimeSeries ts(names);
  ts.reserve(ticks);
  std::vector<double> row(columns.size());
  for (std::size_t k = 0; k < ticks; ++k) {
    for (std::size_t c = 0; c < columns.size(); ++c) row[c] = (*columns[c].values)[k];
    ts.add_row(row);
  }
  report::write_csv(ts, dir / (stem + ".csv"));

  std::vector<std::string> problems;
  report::MultiPlot mp;
  mp.title = title;
  mp.panels.push_back({"", "time [s]", "base displacement [mm]", {series("base", rec, rec.base_disp_m, 1e3)}});
  mp.panels.push_back({"", "time [s]", "damper force [kN]", {series("damper", rec, rec.damper_force_n, 1e-3)}});
  mp.panels.push_back({"",
                       "time [s]",
                       "max |floor accel| 1-5 [m/s²]",
                       {series("superstructure", rec, rec.peak_floor_accel_m_s2, 1.0)}});
  mp.panels.push_back({"", "time [s]", "coil current [A]", {series("current", rec, rec.current_a, 1.0)}});
  for (auto& p : mp.panels) p.key = false;
  mp.height_px = 1100;
  const auto response_png = dir / (stem + "_response.png");
  note(problems, report::plot_png(mp, response_png), response_png);

  report::PlotSpec loop{title + ": force-displacement loop",
                        "damper stroke [mm]",
                        "damper force [kN]",
                        {report::Series{"damper", thin(rec.base_disp_m, 1e3), thin(rec.damper_force_n, 1e-3), "lines"}}};
  loop.key = false;
  const auto loop_png = dir / (stem + "_loop.png");
  note(problems, report::plot_png(loop, loop_png), loop_png);
  return problems;
}

std::vector<std::string> write_comparison_plot(const std::filesystem::path& png, const std::string& title,
                                               const std::string& label_a, const ClosedLoopRecord& a,
                                               const std::string& label_b, const ClosedLoopRecord& b) {
  report::MultiPlot mp;
  mp.title = title;
  mp.panels.push_back({"",
                       "time [s]",
                       "base displacement [mm]",
                       {series(label_a, a, a.base_disp_m, 1e3), series(label_b, b, b.base_disp_m, 1e3)}});
  mp.panels.push_back({"",
                       "time [s]",
                       "damper force [kN]",
                       {series(label_a, a, a.damper_force_n, 1e-3), series(label_b, b, b.damper_force_n, 1e-3)}});
  mp.panels.push_back({"",
                       "time [s]",
                       "max |floor accel| [m/s²]",
                       {series(label_a, a, a.peak_floor_accel_m_s2, 1.0),
                        series(label_b, b, b.peak_floor_accel_m_s2, 1.0)}});
  mp.height_px = 900;
  std::vector<std::string> problems;
  note(problems, report::plot_png(mp, png), png);
  return problems;
}

nlohmann::json closed_loop_summary_json(const plant::PlantSummary& s) {
  return nlohmann::json{
      {"peak_base_displacement_m", s.peak_base_displacement_m},
      {"peak_damper_force_kn", units::n_to_kn(s.peak_damper_force_n)},
      {"peak_superstructure_accel_m_s2", s.peak_superstructure_accel_m_s2},
      {"peak_base_accel_m_s2", s.peak_base_accel_m_s2},
      {"peak_current_a", s.peak_current_a},
      {"sq", s.sq},
      {"final_participant_ratio", s.final_participant_ratio},
      {"duration_s", s.duration_s},
  };
}

std::vector<std::string> sim_warnings(const SimRun& run) {
  std::vector<std::string> w = validity_warnings(validity_peaks(run.summary), run.spec.damper.rating);
  for (std::string& s : bearing_capacity_warnings({run.summary.peak_base_displacement_m}, run.spec.building))
    w.push_back(std::move(s));
  return w;
}

nlohmann::json sim_summary_json(const SimRun& run) {
  nlohmann::json j = closed_loop_summary_json(run.summary);
  j["record"] = run.motion.source;
  j["synthetic_motion"] = run.motion.synthetic;
  j["pga_m_s2"] = run.motion.pga_m_s2;
  j["scale_factor"] = run.motion.scale_factor;
  j["control"] = control::mode_name(run.spec.mode);
  j["numeric"] = numeric_name(run.spec.numeric);
  j["idle_years"] = run.spec.idle_years;
  j["step_s"] = run.spec.step_s;
  const plant::CoilFigures& c = run.summary.coil;
  j["plant"] = plant::plant_kind_name(run.spec.plant);
  // What only the hardware plant uses: its sensor noise and where its damper
  // is parked (the thesis plant's sensors are ideal and its damper centred).
  const bool hardware = run.spec.plant == plant::PlantKind::kHardware;
  j["sensor_seed"] = hardware ? nlohmann::json(run.spec.sensor_seed) : nlohmann::json(nullptr);
  j["parking_offset_m"] = hardware ? nlohmann::json(run.spec.stroke_offset_m) : nlohmann::json(nullptr);
  j["drive"] = hardware ? nlohmann::json(run.spec.hardware_drive_name) : nlohmann::json(nullptr);
  j["peak_coil_current_a"] = c.peak_coil_current_a;
  j["rms_coil_current_a"] = c.rms_coil_current_a;
  j["time_above_rated_s"] = c.time_above_rated_s;
  j["command_changes_per_s"] = c.command_changes_per_s;
  j["peak_coil_temperature_rise_k"] = c.peak_coil_temperature_rise_k;
  j["peak_damper_velocity_m_s"] = run.summary.peak_base_velocity_m_s;
  j["peak_isolator_force_kn"] = units::n_to_kn(run.summary.peak_isolator_force_n);
  j["peak_story_drift_m"] = run.summary.peak_story_drift_m;
  j["peak_damper_stroke_m"] = run.summary.peak_damper_stroke_m;
  j["building"] = run.spec.building.name;
  j["dofs"] = run.spec.building.dofs();
  j["structural_substeps"] = plant::structural_substeps(run.spec.building, run.spec.step_s);
  j["warnings"] = sim_warnings(run);
  return j;
}

std::vector<std::string> write_sim_outputs(const std::filesystem::path& dir, const SimRun& run) {
  const std::string title = run.motion.name + ", " + control::mode_name(run.spec.mode) + ", idle " +
                            std::to_string(run.spec.idle_years) + " years";
  auto problems = write_closed_loop_outputs(dir, "timeseries", title, run.record);
  report::write_summary_json(dir, sim_summary_json(run));
  return problems;
}

}  // namespace mrd::run
