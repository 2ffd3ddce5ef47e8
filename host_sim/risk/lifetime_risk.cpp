#include "host_sim/risk/lifetime_risk.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/report/output_dir.hpp"
#include "host_sim/report/plot.hpp"
#include "host_sim/report/summary_json.hpp"
#include "host_sim/risk/fragility_report.hpp"
#include "mrd/units.hpp"

namespace mrd::risk {
namespace {

constexpr std::size_t kMaxFragilityFileBytes = std::size_t{64} << 20;
constexpr const char* kReference = "always-fully-mixed";

double parse_number(std::string_view field, const std::string& prefix, const char* column) {
  if (field == "inf") return std::numeric_limits<double>::infinity();
  if (field == "nan") return std::numeric_limits<double>::quiet_NaN();
  double v = 0.0;
  const auto* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, v);
  if (field.empty() || ec != std::errc() || ptr != end) {
    throw io::UsageError(prefix + "field '" + column + "': expected a number, got '" + io::excerpt(field, 40) + "'");
  }
  return v;
}

std::string num4(double v) { return io::format_number("%.4g", v); }

std::string percent(double fraction) { return io::format_number("%.0f", 100.0 * fraction) + " %"; }

/// The part of `total` not in `in_range`, in [0, 1] (0 for a zero total).
double extrapolated_part(double total, double in_range) {
  if (!(total > 0.0)) return 0.0;
  return std::clamp(1.0 - in_range / total, 0.0, 1.0);
}

std::string pga_range(double lo_g, double hi_g) { return num4(lo_g) + "-" + num4(hi_g) + " g"; }

}  // namespace

std::vector<FragilityRow> parse_fragility_csv(std::string_view text, const std::string& file) {
  text = io::strip_bom(text);
  const auto header = io::split_commas(kFragilityCsvHeader);
  const auto range_columns = io::split_commas(kFragilityCsvRangeColumns);
  std::vector<FragilityRow> rows;
  std::size_t line_no = 0, pos = 0;
  bool seen_header = false;
  std::size_t fields = header.size();  // with the range columns when the header has them
  while (pos < text.size()) {
    const std::size_t eol = std::min(text.find('\n', pos), text.size());
    const std::string_view line = io::trim(text.substr(pos, eol - pos));
    pos = eol + 1;
    ++line_no;
    if (line.empty()) continue;
    const std::string prefix = io::line_prefix(file, line_no);
    const auto f = io::split_commas(line);
    if (!seen_header) {
      if (f.size() < header.size() || !std::equal(header.begin(), header.end(), f.begin())) {
        throw io::UsageError(prefix + "expected the header of mrd fragility's fragility.csv ('" +
                             std::string(kFragilityCsvHeader).substr(0, 40) + "...')");
      }
      seen_header = true;
      if (f.size() >= header.size() + range_columns.size() &&
          std::equal(range_columns.begin(), range_columns.end(), f.begin() + static_cast<long>(header.size()))) {
        fields += range_columns.size();
      }
      continue;
    }
    if (f.size() < fields) {
      throw io::UsageError(prefix + "expected " + std::to_string(fields) + " fields, got " + std::to_string(f.size()));
    }
    FragilityRow r;
    r.control = std::string(f[0]);
    r.limit_state = std::string(f[1]);
    if (r.control.empty()) throw io::UsageError(prefix + "field 'control': empty");
    if (r.limit_state.empty()) throw io::UsageError(prefix + "field 'limit_state': empty");
    r.threshold = parse_number(f[2], prefix, "threshold");
    r.idle_years = parse_number(f[3], prefix, "idle_years");
    if (!(r.idle_years >= 0.0) || !std::isfinite(r.idle_years)) {
      throw io::UsageError(prefix + "field 'idle_years': expected an idle time >= 0 years");
    }
    if (f[4] == "fitted") {
      r.fit.status = FitStatus::kFitted;
      r.fit.median_im = parse_number(f[5], prefix, "median_pga_g");
      r.fit.beta = parse_number(f[6], prefix, "beta");
      if (!(r.fit.median_im > 0.0) || !std::isfinite(r.fit.median_im)) {
        throw io::UsageError(prefix + "field 'median_pga_g': expected a median PGA > 0 g");
      }
      if (!(r.fit.beta > 0.0) || !std::isfinite(r.fit.beta)) {
        throw io::UsageError(prefix + "field 'beta': expected a log-standard deviation > 0");
      }
    } else if (f[4] == "none_exceeded") {
      r.fit.status = FitStatus::kNoneExceeded;
    } else if (f[4] == "all_exceeded") {
      r.fit.status = FitStatus::kAllExceeded;
    } else {
      throw io::UsageError(prefix + "field 'status': expected fitted, none_exceeded or all_exceeded, got '" +
                           io::excerpt(f[4], 40) + "'");
    }
    if (fields > header.size()) {
      const std::size_t c = header.size();
      r.pga_min_g = parse_number(f[c], prefix, "pga_g_min");
      r.pga_max_g = parse_number(f[c + 1], prefix, "pga_g_max");
      if (!(r.pga_min_g > 0.0) || !std::isfinite(r.pga_min_g)) {
        throw io::UsageError(prefix + "field 'pga_g_min': expected the lowest PGA level, > 0 g");
      }
      if (!(r.pga_max_g >= r.pga_min_g) || !std::isfinite(r.pga_max_g)) {
        throw io::UsageError(prefix + "field 'pga_g_max': expected the highest PGA level, >= pga_g_min");
      }
    }
    rows.push_back(std::move(r));
  }
  if (!seen_header) throw io::UsageError(file + ": empty; expected mrd fragility's fragility.csv");
  if (rows.empty()) throw io::UsageError(file + ": no fragility curves");
  return rows;
}

std::vector<FragilityRow> read_fragility_csv(const std::filesystem::path& path) {
  return parse_fragility_csv(io::read_regular_file(path, kMaxFragilityFileBytes), io::file_label(path));
}

double equivalent_idle_s(const fw::SettlingModel& model, double capacity_fraction) {
  const double tau = model.idle_of_pr(model.pr_of_capacity(capacity_fraction));
  if (!(tau > 0.0)) return 0.0;
  return std::min(tau, model.max_settling_time_s());
}

double frequency_at(const std::vector<double>& idle_years, const std::vector<double>& frequency, double tau_years) {
  if (tau_years <= idle_years.front()) return frequency.front();
  if (tau_years >= idle_years.back()) return frequency.back();
  std::size_t i = 0;
  while (tau_years > idle_years[i + 1]) ++i;
  const double w = (tau_years - idle_years[i]) / (idle_years[i + 1] - idle_years[i]);
  return (1.0 - w) * frequency[i] + w * frequency[i + 1];
}

RiskResult compute_risk(const std::vector<FragilityRow>& rows, const std::string& control, const HazardCurve& hazard,
                        schedule::ScheduleResult sched) {
  RiskResult r;
  r.control = control.empty() ? rows.front().control : control;
  r.hazard_source = hazard.source;
  std::map<std::string, std::vector<std::pair<double, LognormalFit>>> by_state;
  bool range_known = true;
  double pga_lo_g = std::numeric_limits<double>::infinity(), pga_hi_g = 0.0;
  for (const auto& row : rows) {
    if (row.control != r.control) continue;
    range_known = range_known && std::isfinite(row.pga_min_g) && std::isfinite(row.pga_max_g);
    pga_lo_g = std::min(pga_lo_g, row.pga_min_g);
    pga_hi_g = std::max(pga_hi_g, row.pga_max_g);
    if (!by_state.count(row.limit_state)) r.limit_states.push_back(row.limit_state);
    by_state[row.limit_state].push_back({row.idle_years, row.fit});
  }
  if (r.limit_states.empty())
    throw io::UsageError("--control: no fragility curves for control mode '" + r.control + "'");
  if (range_known) {
    r.fitted_pga_min_g = pga_lo_g;
    r.fitted_pga_max_g = pga_hi_g;
  }
  // λ_LS(τ_k) from the PGAs within the fitted levels alone (range known).
  std::map<std::string, std::vector<double>> in_range_at_idle;
  for (const auto& name : r.limit_states) {
    auto& curves = by_state[name];
    std::sort(curves.begin(), curves.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<double> idle;
    std::vector<double> freq;
    for (const auto& [tau, fit] : curves) {
      if (!idle.empty() && tau == idle.back()) {
        throw io::UsageError("fragility.csv: two curves for " + r.control + ", " + name + " at idle " + num4(tau) +
                             " years");
      }
      idle.push_back(tau);
      freq.push_back(limit_state_frequency(hazard, [&fit = fit](double x) { return fit.probability(x); }));
      if (range_known) {
        const double in = limit_state_frequency(hazard, [&fit = fit, pga_lo_g, pga_hi_g](double x) {
          return x >= pga_lo_g && x <= pga_hi_g ? fit.probability(x) : 0.0;
        });
        in_range_at_idle[name].push_back(in);
        r.extrapolated_fraction_at_idle[name].push_back(extrapolated_part(freq.back(), in));
      }
    }
    if (r.idle_years.empty()) {
      r.idle_years = idle;
    } else if (idle != r.idle_years) {
      throw io::UsageError("fragility.csv: limit state " + name + " has other idle times than " +
                           r.limit_states.front());
    }
    r.frequency_at_idle[name] = freq;
  }

  fw::SettlingModel model;
  model.init(sched.config.estimator.model);
  const auto& grid = r.idle_years;
  std::size_t beyond = 0, days_all = 0;
  for (const auto& p : sched.policies) {
    PolicyRisk pr;
    pr.name = p.name;
    pr.cycles_per_year = p.mixing_cycles_per_year;
    for (std::size_t k = 0; k < grid.size(); ++k) {
      pr.idle_fraction.push_back(
          {grid[k], k + 1 < grid.size() ? grid[k + 1] : std::numeric_limits<double>::infinity(), 0.0});
    }
    std::map<std::string, double> sums, in_range_sums;
    double tau_sum = 0.0;
    const std::size_t days = p.daily_min_capacity.size();
    for (double c : p.daily_min_capacity) {
      const double tau = units::s_to_years(equivalent_idle_s(model, c));
      tau_sum += tau;
      if (tau > grid.back()) ++beyond;
      std::size_t bin = 0;
      while (bin + 1 < grid.size() && tau >= grid[bin + 1]) ++bin;
      pr.idle_fraction[bin].fraction += 1.0;
      for (const auto& name : r.limit_states) {
        sums[name] += frequency_at(grid, r.frequency_at_idle[name], tau);
        if (range_known) in_range_sums[name] += frequency_at(grid, in_range_at_idle[name], tau);
      }
    }
    days_all += days;
    for (auto& b : pr.idle_fraction) b.fraction /= static_cast<double>(std::max<std::size_t>(days, 1));
    pr.mean_equivalent_idle_years = tau_sum / static_cast<double>(std::max<std::size_t>(days, 1));
    for (const auto& name : r.limit_states) {
      pr.annual_exceedance[name] = sums[name] / static_cast<double>(days);
      if (range_known) pr.extrapolated_fraction[name] = extrapolated_part(sums[name], in_range_sums[name]);
    }
    r.policies.push_back(std::move(pr));
  }
  r.days_beyond_study_fraction = static_cast<double>(beyond) / static_cast<double>(std::max<std::size_t>(days_all, 1));
  PolicyRisk ref;
  ref.name = kReference;
  ref.cycles_per_year = std::numeric_limits<double>::quiet_NaN();
  ref.idle_fraction.push_back({0.0, 0.0, 1.0});
  for (const auto& name : r.limit_states) {
    ref.annual_exceedance[name] = frequency_at(grid, r.frequency_at_idle[name], 0.0);
    if (range_known) {
      ref.extrapolated_fraction[name] =
          extrapolated_part(ref.annual_exceedance[name], frequency_at(grid, in_range_at_idle[name], 0.0));
    }
  }
  r.policies.push_back(std::move(ref));
  r.schedule = std::move(sched);
  r.warnings = risk_warnings(r, hazard);
  return r;
}

std::vector<std::string> risk_warnings(const RiskResult& r, const HazardCurve& hazard) {
  std::vector<std::string> out;
  if (r.days_beyond_study_fraction > 0.0) {
    out.push_back(io::format_number("%.1f", 100.0 * r.days_beyond_study_fraction) +
                  " % of the days are idler than the study's longest idle time (" + num4(r.idle_years.back()) +
                  " years); their curves are held at it");
  }
  if (!std::isfinite(r.fitted_pga_min_g)) {
    out.push_back(std::string("fragility.csv does not give the PGA levels its curves were fitted over (columns ") +
                  kFragilityCsvRangeColumns +
                  ", written by mrd fragility since they exist): how much of the result is extrapolated is not "
                  "checked");
    return out;
  }
  const std::string fitted = pga_range(r.fitted_pga_min_g, r.fitted_pga_max_g);
  const std::string reach = pga_range(hazard.pga_g.front(), hazard.pga_g.back());
  for (const auto& name : r.limit_states) {
    const auto& part = r.extrapolated_fraction_at_idle.at(name);
    const auto worst = std::max_element(part.begin(), part.end());
    if (*worst <= kMaterialExtrapolation) continue;
    out.push_back("the hazard curve (" + reach + ") reaches beyond the fragility's fitted PGA levels (" + fitted +
                  "): " + percent(*worst) + " of the annual exceedance of " + name + " at idle " +
                  num4(r.idle_years[static_cast<std::size_t>(worst - part.begin())]) +
                  " years comes from extrapolated curves");
  }
  const PolicyRisk& ref = r.policies.back();
  for (const auto& name : r.limit_states) {
    const double ref_f = ref.annual_exceedance.at(name);
    if (!(ref_f > 0.0)) continue;  // no ratio reported
    const double ref_part = ref.extrapolated_fraction.at(name);
    std::string listed;
    for (std::size_t i = 0; i + 1 < r.policies.size(); ++i) {
      const PolicyRisk& p = r.policies[i];
      const double part = p.extrapolated_fraction.at(name);
      if (part <= kMainlyExtrapolation && ref_part <= kMainlyExtrapolation) continue;
      listed += (listed.empty() ? "" : ", ") + p.name + " " + num4(p.annual_exceedance.at(name) / ref_f) + "x (" +
                percent(part) + ")";
    }
    if (listed.empty()) continue;
    out.push_back("the ratios to " + ref.name + " for " + name + " rest mainly on extrapolated curves: " + listed +
                  ", against " + percent(ref_part) + " for " + ref.name +
                  " (in brackets: the part of the annual exceedance from PGAs outside " + fitted + ")");
  }
  return out;
}

nlohmann::json risk_summary(const RiskResult& r) {
  const auto value = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  const PolicyRisk& ref = r.policies.back();
  nlohmann::json policies = nlohmann::json::array();
  for (const auto& p : r.policies) {
    nlohmann::json ex = nlohmann::json::object(), rel = nlohmann::json::object(), bins = nlohmann::json::array();
    for (const auto& [name, f] : p.annual_exceedance) {
      ex[name] = f;
      const double base = ref.annual_exceedance.at(name);
      rel[name] = base > 0.0 ? nlohmann::json(f / base) : nlohmann::json(nullptr);
    }
    for (const auto& b : p.idle_fraction) {
      bins.push_back({{"from_years", b.from_years}, {"to_years", value(b.to_years)}, {"fraction", b.fraction}});
    }
    policies.push_back({{"name", p.name},
                        {"cycles_per_year", value(p.cycles_per_year)},
                        {"annual_exceedance", ex},
                        {"relative_to_fully_mixed", rel},
                        {"extrapolated_fraction", p.extrapolated_fraction},
                        {"mean_equivalent_idle_years", p.mean_equivalent_idle_years},
                        {"idle_time_fraction", bins}});
  }
  nlohmann::json at_idle = nlohmann::json::object();
  for (const auto& [name, f] : r.frequency_at_idle) at_idle[name] = f;
  nlohmann::json extrapolated = nlohmann::json::object();
  for (const auto& [name, f] : r.extrapolated_fraction_at_idle) extrapolated[name] = f;
  const auto& o = r.schedule.options;
  return {{"control", r.control},
          {"hazard", r.hazard_source},
          {"limit_states", r.limit_states},
          {"idle_years", r.idle_years},
          {"annual_exceedance_at_idle", at_idle},
          {"days_beyond_study_fraction", r.days_beyond_study_fraction},
          {"fitted_pga_g", std::isfinite(r.fitted_pga_min_g)
                               ? nlohmann::json{{"min", r.fitted_pga_min_g}, {"max", r.fitted_pga_max_g}}
                               : nlohmann::json(nullptr)},
          {"extrapolated_fraction_at_idle", extrapolated},
          {"warnings", r.warnings},
          {"reference", kReference},
          {"schedule",
           {{"years", o.world.years},
            {"seed", o.world.seed},
            {"threshold", o.threshold},
            {"actuator", o.actuator ? "yes" : "no"},
            {"earthquakes_per_year", o.world.earthquakes_per_year},
            {"ambient_median_litres_per_day", o.world.ambient_median_m3_per_day * 1e3}}},
          {"policies", policies},
          {"files", {"risk.csv", "risk.png", "report.md", "summary.json"}}};
}

std::vector<std::string> write_risk_outputs(const std::filesystem::path& dir, const RiskResult& r) {
  // risk.csv: one row per policy, a column per limit state.
  std::string csv = "policy,cycles_per_year,mean_equivalent_idle_years";
  for (const auto& n : r.limit_states) csv += "," + n + "_per_year";
  csv += "\n";
  std::string md = "# Lifetime risk per mixing policy\n\nControl mode: " + r.control + ". Hazard: " + r.hazard_source +
                   ".\nService life: " + num4(r.schedule.options.world.years) + " years (mrd schedule, seed " +
                   std::to_string(r.schedule.options.world.seed) + ").\n\n| policy | cycles/year | mean idle (years) |";
  for (const auto& n : r.limit_states) md += " " + n + " (1/year) | vs fully mixed |";
  md += "\n|---|---|---|";
  for (std::size_t i = 0; i < r.limit_states.size(); ++i) md += "---|---|";
  md += "\n";
  const PolicyRisk& ref = r.policies.back();
  for (const auto& p : r.policies) {
    char b[200];
    std::snprintf(b, sizeof b, "%s,%.9g,%.9g", p.name.c_str(), p.cycles_per_year, p.mean_equivalent_idle_years);
    csv += b;
    md += "| " + p.name + " | " + (std::isfinite(p.cycles_per_year) ? num4(p.cycles_per_year) : "-") + " | " +
          num4(p.mean_equivalent_idle_years) + " |";
    for (const auto& n : r.limit_states) {
      std::snprintf(b, sizeof b, ",%.9g", p.annual_exceedance.at(n));
      csv += b;
      const double base = ref.annual_exceedance.at(n);
      const std::string ratio = base > 0.0 ? num4(p.annual_exceedance.at(n) / base) + "x" : std::string("-");
      md += " ";
      md += num4(p.annual_exceedance.at(n));
      md += " | ";
      md += ratio;
      md += " |";
    }
    csv += "\n";
    md += "\n";
  }
  if (!r.warnings.empty()) {
    md += "\nWarnings:\n\n";
    for (const auto& w : r.warnings) md += "- " + w + "\n";
  }
  md += "\n![annual exceedance against idle time](risk.png)\n";
  report::write_file_atomically(dir / "risk.csv", csv);
  report::write_file_atomically(dir / "report.md", md);

  report::PlotSpec spec;
  spec.title =
      "Annual frequency of exceedance against the idle time the damper meets the earthquake with (" + r.control + ")";
  spec.x_label = "equivalent idle time [years]";
  spec.y_label = "annual exceedance [1/year]";
  for (const auto& n : r.limit_states) {
    spec.series.push_back({n, r.idle_years, r.frequency_at_idle.at(n), "linespoints"});
    report::Series pts{n + ": policies (at their mean idle time)", {}, {}, "points"};
    for (const auto& p : r.policies) {
      pts.x.push_back(p.mean_equivalent_idle_years);
      pts.y.push_back(p.annual_exceedance.at(n));
    }
    spec.series.push_back(std::move(pts));
  }
  std::vector<std::string> problems;
  const auto plotted = report::plot_png(spec, dir / "risk.png");
  if (!plotted) problems.push_back("risk.png: " + plotted.reason);
  report::write_summary_json(dir, risk_summary(r));
  return problems;
}

}  // namespace mrd::risk
