#include "host_sim/discrepancy/calibrate_report.hpp"

#include <algorithm>
#include <string_view>
#include <tuple>
#include <utility>

#include "host_sim/discrepancy/baseline_file.hpp"
#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/discrepancy/effects.hpp"
#include "host_sim/discrepancy/report_format.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/report/output_dir.hpp"
#include "host_sim/report/plot.hpp"
#include "host_sim/report/summary_json.hpp"

namespace mrd::discrepancy {
namespace {

using nlohmann::json;

json fit_json(const LawFit& f, const CalibrationResult& r) {
  json params = json::object();
  for (const ParamEstimate& p : f.params)
    params[p.name] = {{"value", p.value}, {"sigma", p.sigma}, {"fitted", p.fitted}, {"at_bound", p.at_bound}};
  json gaps = json::array();
  for (std::size_t i = 0; i < r.sources.size(); ++i) gaps.push_back({{"file", r.sources[i]}, {"gap", f.record_gaps[i]}});
  json held = json::array();
  for (std::size_t i = 0; i < f.held_out_gaps.size(); ++i)
    held.push_back({{"file", f.held_out_sources[i]}, {"gap", f.held_out_gaps[i]}});
  return {{"law", baseline_form_name(f.baseline)},
          {"parameters", params},
          {"record_gaps", gaps},
          {"held_out_gaps", held},
          {"expected_gap", f.baseline.expected_gap},
          {"expected_gap_basis", gap_basis_name(f.baseline.expected_gap_basis)},
          {"samples", f.samples},
          {"rss_normalized", f.rss},
          {"n_eff", f.n_eff},
          {"bic", f.bic},
          {"iterations", f.iterations},
          {"converged", f.converged}};
}

/// loops_<n>.png: measured and calibrated force against velocity and
/// displacement, for each plain law and the chosen form.
void plot_record(const std::filesystem::path& png, const MeasuredData& data, const CalibrationResult& r,
                 const CalibrateOptions& options, std::vector<std::string>& problems) {
  const ModelInput in = model_input(data, options.smoothing_half_window_s);
  const std::size_t ls = std::max<std::size_t>(1, data.size() / 8000);
  const auto v_mm_s = thin(in.vel_m_s, ls, 1e3);
  const auto x_mm = thin(in.disp_m, ls, 1e3);
  report::MultiPlot mp;
  mp.title = data.source + ": measured and calibrated force";
  mp.columns = 2;
  mp.width_px = 1400;
  mp.height_px = 650;
  report::PlotSpec fv{"force - velocity", "velocity [mm/s]", "force [kN]", {{"measured", v_mm_s, thin(data.force_n, ls, 1e-3)}}};
  report::PlotSpec fx{"force - displacement", "displacement [mm]", "force [kN]", {{"measured", x_mm, thin(data.force_n, ls, 1e-3)}}};
  ModelWorkspace ws;
  std::vector<double> force;
  // The plain laws and the chosen form (the report's table has every form's gap).
  for (std::size_t i = 0; i < r.fits.size(); ++i) {
    const Baseline& b = r.fits[i].baseline;
    const bool plain = !b.has_transition_time() && !b.has_lost_motion();
    if (!plain && i != r.chosen) continue;
    const DamperModel m(in, b);
    m.simulate(EffectSet{}, {}, ws, force);
    // A form with many extras is named in report.md; in the key, its law
    // and how many extras (a long name runs out of the key's box).
    std::string name = baseline_form_name(b);
    const auto extras = std::count(name.begin(), name.end(), '+');
    if (name.size() > 40) name = name.substr(0, name.find('+')) + " + " + std::to_string(extras) + " extras";
    const std::string label = name + (i == r.chosen ? " (chosen)" : "");
    fv.series.push_back({label, v_mm_s, thin(force, ls, 1e-3)});
    fx.series.push_back({label, x_mm, thin(force, ls, 1e-3)});
  }
  // Up to five series: one key, above the force–velocity loop.
  fv.key_headroom = 0.5;
  fx.key = false;
  mp.panels = {fv, fx};
  const report::PlotResult res = report::plot_png(mp, png);
  if (!res.ok) problems.push_back(png.filename().string() + ": " + res.reason);
}

/// Appends " text |" (a Markdown table cell).
void cell(std::string& md, std::string_view text) {
  md += ' ';
  md += text;
  md += " |";
}

/// "- <what> records: RMS gap of the chosen form X, its floor Y": the
/// chosen form's gaps and floors over one set of records, each as an RMS.
std::string floor_line(std::string_view what, std::span<const double> gaps, std::span<const double> floors) {
  return "- " + std::string(what) + " records: RMS gap of the chosen form " + pct(rms_over_records(gaps)) +
         ", its floor " + pct(rms_over_records(floors)) + "\n";
}

std::string markdown(const CalibrationResult& r, const HeldOut& h, const HeldOut& test, const RecordFloors& floors,
                     bool plots) {
  const bool with_floors = !floors.empty();
  std::string md = "# Damper calibration\n\n";
  md += "Chosen law: **" + std::string(baseline_form_name(r.best().baseline)) + "** (" + r.choice_reason + ").\n\n";
  for (const std::string& n : r.notes) md += "- " + n + "\n";
  md += "\n## Parameters (value ± standard error)\n\n";
  for (const LawFit& f : r.fits) {
    md += "### " + std::string(baseline_form_name(f.baseline)) + "\n\n| parameter | value | sigma | |\n|---|---|---|---|\n";
    for (const ParamEstimate& p : f.params)
      md += "| " + p.name + " | " + g4(p.value) + " | " + (p.fitted ? g4(p.sigma) : "-") + " | " +
            (p.fitted ? (p.at_bound ? "at its search bound" : "") : "held") + " |\n";
    md += "\nBIC " + io::format_number("%.1f", f.bic) + ", " + std::to_string(f.samples) + " samples, n_eff " +
          io::format_number("%.0f", f.n_eff) + ".\n\n";
  }
  md += "## Gap per record (normalized RMS of model - measured force)\n\n| record |";
  for (const LawFit& f : r.fits) cell(md, baseline_form_name(f.baseline));
  if (with_floors) cell(md, "floor: the chosen form fitted to the record alone");
  md += "\n|---|";
  for (std::size_t i = 0; i < r.fits.size() + (with_floors ? 1 : 0); ++i) md += "---|";
  md += "\n";
  for (std::size_t i = 0; i < r.sources.size(); ++i) {
    md += "| " + r.sources[i] + " |";
    for (const LawFit& f : r.fits) cell(md, pct(f.record_gaps[i]));
    if (with_floors) cell(md, pct(floors.measured[i]));
    md += "\n";
  }
  for (const auto& [set, tag, floor] : {std::tuple{&h, " (check)", &floors.check},
                                        std::tuple{&test, " (test)", &floors.test}}) {
    for (std::size_t i = 0; i < set->sources.size(); ++i) {
      md += "| " + set->sources[i] + tag + " |";
      for (std::size_t l = 0; l < r.fits.size(); ++l) cell(md, pct(set->gaps[l][i]));
      if (with_floors) cell(md, pct((*floor)[i]));
      md += "\n";
    }
  }
  if (!h.sources.empty() || !test.sources.empty())
    md += "\n(check) records are not fitted but choose the extras and the form; (test) records are seen by nothing "
          "in the calibration.\n";
  if (with_floors) {
    md += "\nA record's floor is the gap of the chosen form fitted to that record alone (its current laws constants "
          "at the record's current): what the form cannot describe in the record. The gap above it is what the form "
          "loses by being one model for every record.\n\n";
    md += floor_line("fitted", r.best().record_gaps, floors.measured);
    if (!h.sources.empty()) md += floor_line("check", h.gaps[r.chosen], floors.check);
    if (!test.sources.empty()) md += floor_line("test", test.gaps[r.chosen], floors.test);
  }
  if (!test.sources.empty())
    md += "\nRMS gap of the chosen form on the test records: **" + pct(rms_over_records(test.gaps[r.chosen])) + "**.\n";
  const ValidityRange& v = r.best().baseline.range;
  md += "\n## Validity range\n\ncurrent " + g4(v.current_min_a) + "-" + g4(v.current_max_a) + " A, |v| up to " +
        g4(v.velocity_max_m_s) + " m/s, |F| up to " + g4(v.force_peak_n) + " N, half range " + g4(v.amplitude_min_m) +
        "-" + g4(v.amplitude_max_m) + " m, frequency " + g4(v.frequency_min_hz) + "-" + g4(v.frequency_max_hz) +
        " Hz; expected gap " + pct(r.best().baseline.expected_gap) + " (the largest on " +
        gap_basis_phrase(r.best().baseline.expected_gap_basis) + ").\n";
  if (plots) {
    md += "\n## Loops\n\n";
    for (std::size_t i = 0; i < r.sources.size(); ++i)
      md += "![" + r.sources[i] + "](loops_" + std::to_string(i + 1) + ".png)\n";
  }
  return md;
}

}  // namespace

HeldOut held_out_gaps(const CalibrationResult& r, std::span<const MeasuredData> records,
                      const CalibrateOptions& options) {
  HeldOut h;
  for (const MeasuredData& d : records) h.sources.push_back(d.source);
  for (const LawFit& f : r.fits) h.gaps.push_back(baseline_gaps(f.baseline, records, options.smoothing_half_window_s));
  return h;
}

RecordFloors record_floors(const CalibrationResult& r, std::span<const MeasuredData> records,
                           std::span<const MeasuredData> check, std::span<const MeasuredData> test,
                           const CalibrateOptions& options) {
  const Baseline& form = r.best().baseline;
  return {record_floor_gaps(form, records, options), record_floor_gaps(form, check, options),
          record_floor_gaps(form, test, options)};
}

json calibration_json(const CalibrationResult& r, const HeldOut& h, const HeldOut& test, const RecordFloors& floors,
                      const std::vector<std::string>& warnings) {
  json fits = json::array();
  for (const LawFit& f : r.fits) fits.push_back(fit_json(f, r));
  const auto per_record = [&](const HeldOut& set) {
    json out = json::array();
    for (std::size_t i = 0; i < set.sources.size(); ++i) {
      json g = json::object();
      for (std::size_t l = 0; l < r.fits.size(); ++l) g[baseline_form_name(r.fits[l].baseline)] = set.gaps[l][i];
      out.push_back({{"file", set.sources[i]}, {"gap", g}});
    }
    return out;
  };
  const json held = per_record(h);
  const json test_json = per_record(test);
  const ValidityRange& v = r.best().baseline.range;
  json motions = nullptr;  // the records of each motion left out in turn, or null
  if (!r.cross_validation_groups.empty()) {
    motions = json::array();
    for (const auto& g : r.cross_validation_groups) {
      json names = json::array();
      for (const std::size_t i : g) names.push_back(r.sources.at(i));
      motions.push_back(std::move(names));
    }
  }
  return {{"chosen_law", baseline_form_name(r.best().baseline)},
          {"choice_reason", r.choice_reason},
          {"records", r.sources},
          {"currents_a", r.currents_a},
          {"notes", r.notes},
          {"cross_validation", motions},
          {"warnings", warnings},
          {"fits", fits},
          {"held_out", held},
          {"test", test_json},
          {"test_gap_rms", test.sources.empty() ? json(nullptr) : json(rms_over_records(test.gaps[r.chosen]))},
          {"floors", floors.empty() ? json(nullptr)
                                    : json{{"measured", floors.measured},
                                           {"check", floors.check},
                                           {"test", floors.test}}},
          {"validity",
           {{"current_min_a", v.current_min_a},
            {"current_max_a", v.current_max_a},
            {"velocity_max_m_s", v.velocity_max_m_s},
            {"force_peak_n", v.force_peak_n},
            {"amplitude_min_m", v.amplitude_min_m},
            {"amplitude_max_m", v.amplitude_max_m},
            {"frequency_min_hz", v.frequency_min_hz},
            {"frequency_max_hz", v.frequency_max_hz},
            {"expected_gap", r.best().baseline.expected_gap},
            {"expected_gap_basis", gap_basis_name(r.best().baseline.expected_gap_basis)}}}};
}

std::vector<std::string> write_calibration_outputs(const std::filesystem::path& dir,
                                                   std::span<const MeasuredData> records, const CalibrationResult& r,
                                                   const HeldOut& held_out, const CalibrateOptions& options,
                                                   bool plots, const HeldOut& test, const RecordFloors& floors,
                                                   const std::vector<std::string>& warnings) {
  std::vector<std::string> problems;
  write_baseline_file(baseline_file_of(r), dir / "damper.toml");
  if (plots) {
    for (std::size_t i = 0; i < records.size(); ++i)
      plot_record(dir / ("loops_" + std::to_string(i + 1) + ".png"), records[i], r, options, problems);
  }
  report::write_file_atomically(dir / "report.md", markdown(r, held_out, test, floors, plots));
  report::write_summary_json(dir, calibration_json(r, held_out, test, floors, warnings));
  return problems;
}

}  // namespace mrd::discrepancy
