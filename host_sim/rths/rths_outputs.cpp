#include "host_sim/rths/rths_outputs.hpp"

#include <cmath>

#include "host_sim/report/plot.hpp"
#include "host_sim/report/summary_json.hpp"
#include "host_sim/report/time_series.hpp"

namespace mrd::rths {
namespace {

void note_rths_plot(std::vector<std::string>& problems, const report::PlotResult& r, const std::filesystem::path& png) {
  if (!r.ok) problems.push_back(png.filename().string() + ": " + r.reason);
}

std::vector<double> scaled(const std::vector<double>& v, double k) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = v[i] * k;
  return out;
}

}  // namespace

nlohmann::json rths_summary_json(const RthsSpec& spec, const RthsDescription& d, const RthsResult& r) {
  const auto& j = r.criteria.j;
  const LabPlantParams& p = spec.plant;
  return nlohmann::json{
      {"status", r.status},
      {"rate_hz", spec.rate_hz},
      {"compensator", compensator_name(spec.compensator.kind)},
      {"building", d.building},
      {"record", d.record},
      {"record_scale", d.record_scale},
      {"specimen_dof", spec.specimen_dof},
      {"criteria",
       {{"j1_lag_s", j[0]},
        {"j2_tracking_rms_pct", j[1]},
        {"j3_tracking_peak_pct", j[2]},
        {"j4_floor1_rms_pct", j[3]},
        {"j5_floor1_peak_pct", j[4]},
        {"j6_floor2_rms_pct", j[5]},
        {"j7_floor2_peak_pct", j[6]},
        {"j8_floor3_rms_pct", j[7]},
        {"j9_floor3_peak_pct", j[8]}}},
      {"peak_force_n", r.peak_force_n},
      {"force_limit_n", spec.lab.force_limit_n},
      {"force_limit_exceeded", r.peak_force_n > spec.lab.force_limit_n},
      {"plant",
       {{"drawn_from_uncertainty", d.plant_drawn},
        {"seed", d.plant_drawn ? nlohmann::json(d.plant_seed) : nlohmann::json(nullptr)},
        {"gain", p.gain},
        {"a1_beta0", p.a1_beta0},
        {"a2", p.a2},
        {"beta1_1_s", p.beta1},
        {"beta2_1_s2", p.beta2},
        {"a3_1_s", p.a3},
        {"specimen_mass_kg", p.specimen.mass_kg},
        {"specimen_stiffness_n_m", p.specimen.stiffness_n_m},
        {"specimen_damping_ratio", p.specimen.damping_ratio}}},
      {"laboratory",
       {{"converter_range_v", spec.lab.converter_range_v},
        {"converter_bits", spec.lab.converter_bits},
        {"displacement_full_scale_m", spec.lab.displacement_full_scale_m},
        {"force_full_scale_n", spec.lab.force_full_scale_n},
        {"displacement_noise_power_m2_hz", spec.lab.displacement_noise_power_m2_hz},
        {"force_noise_power_n2_hz", spec.lab.force_noise_power_n2_hz},
        {"displacement_noise_sigma_m", std::sqrt(spec.lab.displacement_noise_power_m2_hz * spec.rate_hz)},
        {"force_noise_sigma_n", std::sqrt(spec.lab.force_noise_power_n2_hz * spec.rate_hz)},
        {"tracking_limit_m", spec.lab.tracking_limit_m},
        {"noise_seed", spec.lab.noise_seed}}},
      {"integration", "Chen-Ricles explicit (alpha = (M + dt/2 C + dt^2/4 K)^-1 M), measured force as input"},
      {"coefficient_names", r.coefficient_names},
      {"final_coefficients", r.coefficients.empty() ? std::vector<double>{} : r.coefficients.back()},
  };
}

std::vector<std::string> write_rths_outputs(const std::filesystem::path& dir, const RthsSpec& spec,
                                            const RthsDescription& d, const RthsResult& r) {
  report::write_summary_json(dir, rths_summary_json(spec, d, r));

  std::vector<std::string> names{"time_s", "target_m", "measured_m", "command_m", "force_n"};
  for (std::size_t i = 0; i < r.floors_m.size(); ++i) names.push_back("floor_" + std::to_string(i + 1) + "_m");
  for (std::size_t i = 0; i < r.floors_m.size(); ++i)
    names.push_back("reference_floor_" + std::to_string(i + 1) + "_m");
  report::TimeSeries ts(names);
  ts.reserve(r.time_s.size());
  std::vector<double> row(names.size());
  for (std::size_t k = 0; k < r.time_s.size(); ++k) {
    row[0] = r.time_s[k];
    row[1] = r.target_m[k];
    row[2] = r.measured_m[k];
    row[3] = r.command_m[k];
    row[4] = r.force_n[k];
    for (std::size_t i = 0; i < r.floors_m.size(); ++i) {
      row[5 + i] = r.floors_m[i][k];
      row[5 + r.floors_m.size() + i] = r.reference_floors_m[i][k];
    }
    ts.add_row(row);
  }
  report::write_csv(ts, dir / "tracking.csv");

  if (!r.coefficient_names.empty()) {
    std::vector<std::string> cn{"time_s"};
    cn.insert(cn.end(), r.coefficient_names.begin(), r.coefficient_names.end());
    report::TimeSeries cs(cn);
    std::vector<double> crow(cn.size());
    for (std::size_t k = 0; k < r.coefficient_time_s.size(); ++k) {
      crow[0] = r.coefficient_time_s[k];
      for (std::size_t i = 0; i < r.coefficients[k].size(); ++i) crow[1 + i] = r.coefficients[k][i];
      cs.add_row(crow);
    }
    report::write_csv(cs, dir / "coefficients.csv");
  }

  std::vector<std::string> problems;
  std::vector<double> error_mm(r.time_s.size());
  for (std::size_t k = 0; k < r.time_s.size(); ++k) error_mm[k] = 1e3 * (r.measured_m[k] - r.target_m[k]);
  report::MultiPlot tracking;
  tracking.title = std::string("RTHS tracking, ") + compensator_name(spec.compensator.kind) + " compensation (" +
                   r.status + ")";
  tracking.panels.push_back({"", "time [s]", "displacement [mm]",
                             {report::Series{"target", r.time_s, scaled(r.target_m, 1e3), "lines"},
                              report::Series{"measured", r.time_s, scaled(r.measured_m, 1e3), "lines"}}});
  tracking.panels.push_back(
      {"", "time [s]", "measured - target [mm]", {report::Series{"error", r.time_s, error_mm, "lines"}}});
  tracking.panels.back().key = false;
  const auto tracking_png = dir / "tracking.png";
  note_rths_plot(problems, report::plot_png(tracking, tracking_png), tracking_png);

  report::MultiPlot floors;
  floors.title = "Floors: RTHS against the all-numerical reference";
  for (std::size_t i = 0; i < r.floors_m.size() && i < 6; ++i)
    floors.panels.push_back({"", "time [s]", "floor " + std::to_string(i + 1) + " [mm]",
                             {report::Series{"RTHS", r.time_s, scaled(r.floors_m[i], 1e3), "lines"},
                              report::Series{"reference", r.time_s, scaled(r.reference_floors_m[i], 1e3), "lines"}}});
  const auto floors_png = dir / "floors.png";
  note_rths_plot(problems, report::plot_png(floors, floors_png), floors_png);
  return problems;
}

}  // namespace mrd::rths
