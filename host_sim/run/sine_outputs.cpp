#include "host_sim/run/sine_outputs.hpp"

#include <cmath>
#include <numbers>

#include "host_sim/run/validity.hpp"

#include <cstdio>
#include <sstream>
#include <utility>

#include "host_sim/report/output_dir.hpp"
#include "host_sim/report/plot.hpp"
#include "host_sim/report/summary_json.hpp"
#include "host_sim/report/time_series.hpp"

namespace mrd::run {
namespace {

/// Plots keep every fifth sample.
constexpr std::size_t kSinePlotStride = 5;

double pct_error(double model, double measured) { return 100.0 * (model - measured) / measured; }

nlohmann::json metrics_json(double fully_mixed_force_kn, double initial_force_kn, double max_force_kn,
                            double rise_time_90_s, double rise_time_95_s) {
  return nlohmann::json{{"fully_mixed_force_kn", fully_mixed_force_kn},
                        {"initial_force_kn", initial_force_kn},
                        {"max_force_kn", max_force_kn},
                        {"rise_time_90_s", rise_time_90_s},
                        {"rise_time_95_s", rise_time_95_s}};
}

}  // namespace

std::vector<std::string> sine_warnings(const SineRun& run) {
  const double a_m = run.spec.amplitude_m;
  return validity_warnings(ValidityPeaks{a_m, 2.0 * std::numbers::pi * run.spec.frequency_hz * a_m,
                                         std::abs(run.spec.current_a), run.metrics.max_force_n},
                           run.rating);
}

nlohmann::json sine_summary_json(const SineRun& run) {
  const SineMetrics& m = run.metrics;
  nlohmann::json j = metrics_json(m.fully_mixed_force_n / 1e3, m.initial_force_n / 1e3, m.max_force_n / 1e3,
                                  m.rise_time_90_s, m.rise_time_95_s);
  j["sq"] = m.sq;
  j["amplitude_mm"] = run.amplitude_mm;
  j["freq_hz"] = run.spec.frequency_hz;
  j["current_a"] = run.spec.current_a;
  j["idle_years"] = run.idle_years;
  j["duration_s"] = run.spec.duration_s;
  j["warnings"] = sine_warnings(run);
  return j;
}

std::vector<std::string> write_sine_outputs(const std::filesystem::path& dir, const SineRun& run) {
  const SineRecord& rec = run.record;
  report::TimeSeries ts({"time_s", "disp_m", "vel_m_s", "force_n", "current_a", "participant_ratio"});
  ts.reserve(rec.time_s.size());
  for (std::size_t k = 0; k < rec.time_s.size(); ++k) {
    ts.add_row({rec.time_s[k], rec.disp_m[k], rec.vel_m_s[k], rec.force_n[k], rec.current_a[k], rec.pr[k]});
  }
  report::write_csv(ts, dir / "sine.csv");

  std::vector<double> t, x_mm, f_kn;
  for (std::size_t k = 0; k < rec.time_s.size(); k += kSinePlotStride) {
    t.push_back(rec.time_s[k]);
    x_mm.push_back(rec.disp_m[k] * 1e3);
    f_kn.push_back(rec.force_n[k] / 1e3);
  }
  char title[160];
  std::snprintf(title, sizeof title, "Sine %.3g mm, %.3g Hz, %.3g A after %.3g years idle", run.amplitude_mm,
                run.spec.frequency_hz, run.spec.current_a, run.idle_years);
  report::PlotSpec ft{title, "time [s]", "damper force [kN]", {{"model", t, f_kn, "lines"}}};
  ft.key = false;
  report::PlotSpec fd{title, "displacement [mm]", "damper force [kN]", {{"model", x_mm, f_kn, "lines"}}};
  fd.key = false;
  std::vector<std::string> problems;
  for (const auto& [plot, name] : {std::pair{&ft, "force_time.png"}, std::pair{&fd, "force_displacement.png"}}) {
    const auto r = report::plot_png(*plot, dir / name);
    if (!r.ok) problems.push_back(std::string(name) + ": " + r.reason);
  }
  report::write_summary_json(dir, sine_summary_json(run));
  return problems;
}

std::string thesis_cases_markdown(const std::vector<ThesisSineResult>& results) {
  std::ostringstream os;
  char buf[256];
  os << "| case | metric | model | measured (Table 5.2) | error |\n|---|---|---:|---:|---:|\n";
  for (const auto& [c, m] : results) {
    const struct {
      const char* name;
      double model, measured;
      const char* unit;
    } rows[] = {
        {"fully mixed force", m.fully_mixed_force_n / 1e3, c.fully_mixed_force_kn, "kN"},
        {"initial force", m.initial_force_n / 1e3, c.initial_force_kn, "kN"},
        {"max force", m.max_force_n / 1e3, c.max_force_kn, "kN"},
        {"rise time to 90 %", m.rise_time_90_s, c.rise_time_90_s, "s"},
        {"rise time to 95 %", m.rise_time_95_s, c.rise_time_95_s, "s"},
    };
    for (const auto& r : rows) {
      std::snprintf(buf, sizeof buf, "| %s | %s | %.2f %s | %.2f %s | %+.1f %% |\n", c.name, r.name, r.model, r.unit,
                    r.measured, r.unit, pct_error(r.model, r.measured));
      os << buf;
    }
  }
  return os.str();
}

nlohmann::json thesis_cases_json(const std::vector<ThesisSineResult>& results) {
  nlohmann::json cases = nlohmann::json::array();
  for (const auto& [c, m] : results) {
    cases.push_back({{"name", c.name},
                     {"model", metrics_json(m.fully_mixed_force_n / 1e3, m.initial_force_n / 1e3, m.max_force_n / 1e3,
                                            m.rise_time_90_s, m.rise_time_95_s)},
                     {"measured", metrics_json(c.fully_mixed_force_kn, c.initial_force_kn, c.max_force_kn,
                                               c.rise_time_90_s, c.rise_time_95_s)}});
  }
  return nlohmann::json{{"thesis_cases", cases}};
}

void write_thesis_cases_outputs(const std::filesystem::path& dir, const std::vector<ThesisSineResult>& results) {
  report::write_file_atomically(dir / "thesis_cases.md", "# Sine tests of Table 5.1: model against Table 5.2 (a)\n\n" +
                                                             thesis_cases_markdown(results));
  report::write_summary_json(dir, thesis_cases_json(results));
}

}  // namespace mrd::run
