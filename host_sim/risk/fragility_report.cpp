#include "host_sim/risk/fragility_report.hpp"

#include "host_sim/run/thesis_building.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "host_sim/report/output_dir.hpp"
#include "host_sim/report/plot.hpp"
#include "host_sim/report/summary_json.hpp"
#include "host_sim/run/thesis_building.hpp"
#include "host_sim/run/validity.hpp"
#include "mrd/control/io.hpp"

namespace mrd::risk {
namespace {

std::string num(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return "nan";
  char b[40];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

const char* mode_label(const FragilityPlan& plan, std::size_t m) { return control::mode_name(plan.modes[m]); }

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

std::vector<std::string> fragility_warnings(const std::vector<RunMetrics>& runs, const physics::DamperRating& rating) {
  std::vector<run::ValidityPeaks> peaks;
  peaks.reserve(runs.size());
  for (const RunMetrics& m : runs) {
    run::ValidityPeaks p;
    p.stroke_m = m.peak_base_displacement_m;
    p.force_n = m.peak_damper_force_n;  // velocity and current: not recorded, left at 0
    peaks.push_back(p);
  }
  return run::validity_warnings(peaks, rating);
}

std::string runs_csv(const FragilityPlan& plan, const std::vector<RunMetrics>& runs) {
  std::string s =
      "run,record,control,idle_years,pga_g,peak_base_displacement_m,peak_damper_force_kn,peak_floor_accel_m_s2,"
      "peak_base_accel_m_s2,peak_story_drift_m\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunKey k = plan.key(i);
    const RunMetrics& m = runs[i];
    s += std::to_string(i) + ',' + plan.records[k.record].name + ',' + mode_label(plan, k.mode) + ',' +
         num(plan.idle_years[k.idle]) + ',' + num(plan.pga_g[k.pga]) + ',' + num(m.peak_base_displacement_m) + ',' +
         num(m.peak_damper_force_n / 1e3) + ',' + num(m.peak_floor_accel_m_s2) + ',' + num(m.peak_base_accel_m_s2) +
         ',' + num(m.peak_story_drift_m) + '\n';
  }
  return s;
}

std::string fragility_csv(const FragilityPlan& plan, const std::vector<LimitState>& limit_states,
                          const std::vector<FragilityCurve>& curves) {
  std::string s = std::string(kFragilityCsvHeader) + "," + kFragilityCsvRangeColumns + "\n";
  const std::string range = plan.pga_g.empty() ? std::string(",nan,nan")
                                               : ',' + num(plan.pga_g.front()) + ',' + num(plan.pga_g.back());
  for (const auto& c : curves) {
    unsigned runs = 0, exceed = 0;
    for (const auto& l : c.levels) {
      runs += l.runs;
      exceed += l.exceed;
    }
    const bool fitted = c.fit.status == FitStatus::kFitted;
    s += std::string(mode_label(plan, c.mode)) + ',' + limit_states[c.limit_state].name + ',' +
         num(limit_states[c.limit_state].threshold) + ',' + num(plan.idle_years[c.idle]) + ',' +
         fit_status_name(c.fit.status) + ',' + num(c.fit.median_im) + ',' + (fitted ? num(c.fit.beta) : "nan") + ',' +
         num(c.band.median_low) + ',' + num(c.band.median_high) + ',' + num(c.band.beta_low) + ',' +
         num(c.band.beta_high) + ',' + std::to_string(runs) + ',' + std::to_string(exceed) + range + '\n';
  }
  return s;
}

std::string fragility_curves_csv(const FragilityPlan& plan, const std::vector<LimitState>& limit_states,
                                 const std::vector<FragilityCurve>& curves) {
  std::string s = "control,limit_state,idle_years,pga_g,probability,probability_p05,probability_p95\n";
  for (const auto& c : curves) {
    for (std::size_t i = 0; i < c.band.im.size(); ++i) {
      s += std::string(mode_label(plan, c.mode)) + ',' + limit_states[c.limit_state].name + ',' +
           num(plan.idle_years[c.idle]) + ',' + num(c.band.im[i]) + ',' + num(c.fit.probability(c.band.im[i])) + ',' +
           num(c.band.p_low[i]) + ',' + num(c.band.p_high[i]) + '\n';
    }
  }
  return s;
}

nlohmann::json fragility_summary(const FragilityPlan& plan, const std::vector<LimitState>& limit_states,
                                 const std::vector<FragilityCurve>& curves, const FragilitySession& session) {
  nlohmann::json records = nlohmann::json::array();
  for (const auto& r : plan.records) records.push_back({{"name", r.name}, {"source", r.source}});
  nlohmann::json controls = nlohmann::json::array();
  for (std::size_t m = 0; m < plan.modes.size(); ++m) controls.push_back(mode_label(plan, m));
  nlohmann::json states = nlohmann::json::array();
  for (const auto& l : limit_states) {
    states.push_back({{"name", l.name},
                      {"threshold", l.threshold},
                      {"unit", l.metric == Metric::kFloorAccel ? "m/s2" : "m"},
                      {"description", l.description}});
  }
  nlohmann::json fits = nlohmann::json::array();
  for (const auto& c : curves) {
    fits.push_back({{"control", mode_label(plan, c.mode)},
                    {"idle_years", plan.idle_years[c.idle]},
                    {"limit_state", limit_states[c.limit_state].name},
                    {"status", fit_status_name(c.fit.status)},
                    {"median_pga_g", number_or_null(c.fit.median_im)},
                    {"beta", c.fit.status == FitStatus::kFitted ? nlohmann::json(c.fit.beta) : nlohmann::json()}});
  }
  const double core_s = session.wall_s * session.ranks * session.threads_per_rank;
  nlohmann::json j{{"runs", plan.run_count()},
          {"runs_computed", session.computed},
          {"runs_resumed", session.resumed},
          {"records", records},
          {"synthetic", session.synthetic},
          {"pga_g", plan.pga_g},
          {"idle_years", plan.idle_years},
          {"controls", controls},
          {"step_s", plan.base.step_s},
          {"building", plan.base.building.name},
          {"dofs", plan.base.building.dofs()},
          {"seed", plan.seed},
          {"bootstrap_resamples", session.bootstrap},
          {"limit_states", states},
          {"curves", fits},
          {"warnings", session.warnings},
          {"ranks", session.ranks},
          {"threads_per_rank", session.threads_per_rank},
          {"wall_s", session.wall_s},
          {"runs_per_core_hour", session.computed > 0 && core_s > 0
                                     ? nlohmann::json(static_cast<double>(session.computed) / core_s * 3600.0)
                                     : nlohmann::json()},
          {"cpu_s_rank0", session.cpu_s_rank0},
          {"runs_per_cpu_hour",
           session.computed_rank0 > 0 && session.cpu_s_rank0 > 0
               ? nlohmann::json(static_cast<double>(session.computed_rank0) / session.cpu_s_rank0 * 3600.0)
               : nlohmann::json()},
          {"files", {"runs.csv", "fragility.csv", "fragility_curves.csv", "summary.json"}}};
  // The thesis building keeps the thesis's summary; any other is named.
  if (run::is_thesis_building(plan.base.building)) {
    j.erase("building");
    j.erase("dofs");
  }
  return j;
}

std::vector<std::string> write_fragility_outputs(const std::filesystem::path& dir, const FragilityPlan& plan,
                                                 const std::vector<RunMetrics>& runs,
                                                 const std::vector<LimitState>& limit_states,
                                                 const std::vector<FragilityCurve>& curves,
                                                 const FragilitySession& session) {
  report::write_file_atomically(dir / "runs.csv", runs_csv(plan, runs));
  report::write_file_atomically(dir / "fragility.csv", fragility_csv(plan, limit_states, curves));
  report::write_file_atomically(dir / "fragility_curves.csv", fragility_curves_csv(plan, limit_states, curves));
  std::vector<std::string> problems;
  for (std::size_t m = 0; m < plan.modes.size(); ++m) {
    for (std::size_t s = 0; s < limit_states.size(); ++s) {
      report::PlotSpec spec;
      spec.title = std::string("Fragility: ") + mode_label(plan, m) + ", " + limit_states[s].name + " (" +
                   limit_states[s].description + ")";
      spec.x_label = "PGA [g]";
      spec.y_label = "P(limit state exceeded)";
      for (const auto& c : curves) {
        if (c.mode != m || c.limit_state != s) continue;
        report::Series line;
        line.label = "idle " + num(plan.idle_years[c.idle]) + " years";
        line.x = c.band.im;
        for (double x : c.band.im) line.y.push_back(c.fit.probability(x));
        spec.series.push_back(std::move(line));
        if (c.idle == 0 || c.idle + 1 == plan.idle_years.size()) {
          report::Series lo{"5-95 % band, idle " + num(plan.idle_years[c.idle]) + " years", c.band.im, c.band.p_low,
                            "lines"};
          report::Series hi{"", c.band.im, c.band.p_high, "lines"};
          spec.series.push_back(std::move(lo));
          spec.series.push_back(std::move(hi));
        }
      }
      const std::string png = std::string("fragility_") + mode_label(plan, m) + "_" + limit_states[s].name + ".png";
      const auto r = report::plot_png(spec, dir / png);
      if (!r) problems.push_back(png + ": " + r.reason);
    }
  }
  report::write_summary_json(dir, fragility_summary(plan, limit_states, curves, session));
  return problems;
}

}  // namespace mrd::risk
