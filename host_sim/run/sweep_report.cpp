#include "host_sim/run/sweep_report.hpp"

#include "host_sim/run/thesis_building.hpp"
#include "host_sim/run/validity.hpp"

#include <cstdio>
#include <sstream>

#include "host_sim/report/output_dir.hpp"
#include "host_sim/report/plot.hpp"
#include "host_sim/report/summary_json.hpp"

namespace mrd::run {
namespace {

struct Metric {
  const char* file;
  const char* title;
  const char* axis;
  double (*value)(const plant::PlantSummary&);
};

constexpr Metric kMetrics[] = {
    {"peak_base_displacement", "Max. displacement of base isolation", "max |base displacement| [mm]",
     [](const plant::PlantSummary& s) { return s.peak_base_displacement_m * 1e3; }},
    {"peak_damper_force", "Max. damping force", "max |damper force| [kN]",
     [](const plant::PlantSummary& s) { return s.peak_damper_force_n / 1e3; }},
    {"peak_superstructure_accel", "Max. acceleration of superstructure", "max |floor acceleration| [m/s²]",
     [](const plant::PlantSummary& s) { return s.peak_superstructure_accel_m_s2; }},
};

/// Thesis figure numbers for (mode, metric): semi-active 6.12–6.14,
/// passive-off 6.15–6.17, passive-on 6.18–6.20.
int thesis_figure(control::ControlMode mode, int metric) {
  switch (mode) {
    case control::ControlMode::kSemiActive: return 12 + metric;
    case control::ControlMode::kPassiveOff: return 15 + metric;
    case control::ControlMode::kPassiveOn: return 18 + metric;
  }
  return 0;
}

}  // namespace

std::string sweep_csv(const SweepSpec& spec, const std::vector<SweepRow>& rows) {
  // The thesis building keeps the thesis's ten columns; another building
  // appends its isolators' and stories' peaks.
  const bool building_columns = !is_thesis_building(spec.base.building);
  std::ostringstream os;
  os << "record,control,idle_years,sq,peak_base_displacement_m,peak_damper_force_kn,"
        "peak_superstructure_accel_m_s2,peak_base_accel_m_s2,peak_current_a,final_participant_ratio";
  os << (building_columns ? ",peak_isolator_force_kn,peak_story_drift_m\n" : "\n");
  char buf[512];
  for (const auto& r : rows) {
    const auto& s = r.summary;
    std::snprintf(buf, sizeof buf, "%s,%s,%.6g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g",
                  spec.motions[r.motion_index].name.c_str(), control::mode_name(r.mode), r.idle_years, s.sq,
                  s.peak_base_displacement_m, s.peak_damper_force_n / 1e3, s.peak_superstructure_accel_m_s2,
                  s.peak_base_accel_m_s2, s.peak_current_a, s.final_participant_ratio);
    os << buf;
    if (building_columns) {
      std::snprintf(buf, sizeof buf, ",%.9g,%.9g", s.peak_isolator_force_n / 1e3, s.peak_story_drift_m);
      os << buf;
    }
    os << '\n';
  }
  return os.str();
}

std::vector<std::string> write_sweep_outputs(const std::filesystem::path& dir, const SweepSpec& spec,
                                             const std::vector<SweepRow>& rows, std::vector<std::string>* pngs) {
  report::write_file_atomically(dir / "sweep.csv", sweep_csv(spec, rows));
  std::vector<std::string> problems;
  const bool thesis = is_thesis_building(spec.base.building);
  for (auto mode : spec.modes) {
    for (int mi = 0; mi < 3; ++mi) {
      const Metric& metric = kMetrics[mi];
      report::PlotSpec p;
      p.title = std::string(metric.title) + ", " + control::mode_name(mode) +
                (thesis ? " (cf. thesis Fig. 6." + std::to_string(thesis_figure(mode, mi)) + ")"
                        : " (" + spec.base.building.name + ")");
      p.x_label = "idle time [years]";
      p.y_label = metric.axis;
      for (std::size_t m = 0; m < spec.motions.size(); ++m) {
        report::Series s{spec.motions[m].label, {}, {}, "linespoints"};
        for (const auto& r : rows) {
          if (r.motion_index != m || r.mode != mode) continue;
          s.x.push_back(r.idle_years);
          s.y.push_back(metric.value(r.summary));
        }
        p.series.push_back(std::move(s));
      }
      const std::string name = std::string(control::mode_name(mode)) + "_" + metric.file + ".png";
      const auto res = report::plot_png(p, dir / name);
      if (res.ok) {
        if (pngs) pngs->push_back(name);
      } else {
        problems.push_back(name + ": " + res.reason);
      }
    }
  }
  return problems;
}

double simulated_seconds(const std::vector<SweepRow>& rows) {
  double simulated_s = 0.0;
  for (const auto& r : rows) simulated_s += r.summary.duration_s;
  return simulated_s;
}

std::vector<std::string> sweep_warnings(const std::vector<SweepRow>& rows, const plant::PlantSpec& base) {
  std::vector<ValidityPeaks> peaks;
  std::vector<double> base_m;
  for (const auto& r : rows) {
    peaks.push_back(validity_peaks(r.summary));
    base_m.push_back(r.summary.peak_base_displacement_m);
  }
  std::vector<std::string> w = validity_warnings(peaks, base.damper.rating);
  for (std::string& s : bearing_capacity_warnings(base_m, base.building)) w.push_back(std::move(s));
  return w;
}

nlohmann::json sweep_summary_json(const SweepSpec& spec, const std::vector<SweepRow>& rows, double wall_s,
                                  const std::vector<std::string>& pngs) {
  nlohmann::json motions = nlohmann::json::array();
  for (const auto& m : spec.motions) {
    motions.push_back({{"name", m.name}, {"source", m.source}, {"synthetic", m.synthetic},
                       {"scale_factor", m.scale_factor}, {"pga_m_s2", m.pga_m_s2}});
  }
  nlohmann::json modes = nlohmann::json::array();
  for (auto m : spec.modes) modes.push_back(control::mode_name(m));
  const double simulated_s = simulated_seconds(rows);
  nlohmann::json j{{"runs", rows.size()},          {"wall_time_s", wall_s},
                        {"simulated_s", simulated_s},     {"real_time_factor", simulated_s / wall_s},
                        {"motions", motions},            {"controls", modes},
                        {"idle_years", spec.idle_years}, {"csv", "sweep.csv"},
                        {"plots", pngs},                {"warnings", sweep_warnings(rows, spec.base)}};
  // The thesis building keeps the thesis's summary; any other is named.
  if (!is_thesis_building(spec.base.building)) {
    j["building"] = spec.base.building.name;
    j["dofs"] = spec.base.building.dofs();
  }
  return j;
}

std::vector<std::string> write_sweep_report(const std::filesystem::path& dir, const SweepSpec& spec,
                                            const std::vector<SweepRow>& rows, double wall_s,
                                            std::vector<std::string>* pngs) {
  std::vector<std::string> written;
  auto problems = write_sweep_outputs(dir, spec, rows, &written);
  report::write_summary_json(dir, sweep_summary_json(spec, rows, wall_s, written));
  if (pngs) *pngs = std::move(written);
  return problems;
}

}  // namespace mrd::run
