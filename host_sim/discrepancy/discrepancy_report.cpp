#include "host_sim/discrepancy/discrepancy_report.hpp"

#include <algorithm>
#include <cmath>

#include "mrd/physics/participant_ratio.hpp"
#include "mrd/physics/settling.hpp"
#include "mrd/units.hpp"
#include "host_sim/discrepancy/report_format.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/report/output_dir.hpp"
#include "host_sim/report/summary_json.hpp"
#include "host_sim/report/plot.hpp"
#include "host_sim/report/time_series.hpp"

namespace mrd::discrepancy {
namespace {

using nlohmann::json;

json effects_json(const std::vector<Effect>& effects);
json effect_params_json(const std::vector<Effect>& effects, std::span<const double> params, const EffectForms& forms);

/// {parameter: flag} for the flagged parameters only.
json flags_json(Effect e, const std::vector<std::string>& flags) {
  json j = json::object();
  const auto& info = effect_info(e);
  for (std::size_t i = 0; i < info.params.size() && i < flags.size(); ++i) {
    if (!flags[i].empty()) j[std::string(info.params[i].name)] = flags[i];
  }
  return j;
}

json signatures_json(const SignatureAnalysis& a) {
  json sig = json::array();
  for (const auto& s : a.signatures) {
    sig.push_back(json{{"name", s.name}, {"looks_like", s.looks_like}, {"held_out_share", s.held_out_share}});
  }
  return json{{"structured_share", a.structured_share}, {"signatures", sig}};
}

json candidate_json(const CandidateResult& c) {
  return json{{"name", effect_name(c.effect)},
              {"model", effects_json(c.model)},
              {"alternative", c.alternative},
              {"score", c.delta_bic},
              {"delta_bic", c.delta_bic},
              {"rss_reduction", c.rss_reduction},
              {"held_out_reduction", c.held_out_reduction},
              {"gap", c.gap},
              {"effective_samples", c.n_eff},
              {"parameters", effect_params_json({c.effect}, c.params, c.forms)[std::string(effect_name(c.effect))]},
              {"flags", flags_json(c.effect, c.flags)},
              {"plausible", c.plausible},
              {"chosen", c.chosen},
              {"verdict", c.verdict}};
}

json effects_json(const std::vector<Effect>& effects) {
  json a = json::array();
  for (const Effect e : effects) a.push_back(effect_name(e));
  return a;
}

json round_json(const RoundResult& rd) {
  json jr{{"model", effects_json(rd.model)},
          {"gap", rd.gap},
          {"chosen", rd.chosen ? json(effect_name(*rd.chosen)) : json("none")},
          {"model_after", rd.chosen ? effects_json(rd.model_after) : effects_json(rd.model)},
          {"candidates", json::array()}};
  for (const auto& c : rd.candidates) jr["candidates"].push_back(candidate_json(c));
  return jr;
}

json region_json(const RegionStat& s) {
  return json{{"name", s.name},
              {"description", s.description},
              {"fraction_of_time", s.fraction_of_time},
              {"share_of_gap_before", s.share_of_gap_before},
              {"share_of_gap_after", s.share_of_gap_after},
              {"concentration_before", s.concentration_before},
              {"concentrated", s.concentrated},
              {"rms_before_n", s.rms_before_n},
              {"rms_after_n", s.rms_after_n},
              {"magnitude_bias_before_n", s.magnitude_bias_before_n}};
}

json window_json(const TimeWindowStat& w) {
  return json{{"start_s", w.start_s},
              {"end_s", w.end_s},
              {"rms_before_n", w.rms_before_n},
              {"rms_after_n", w.rms_after_n},
              {"share_of_gap_before", w.share_of_gap_before}};
}

json settings_json(const DiscrepancyResult& r, const DiscrepancyOptions& o) {
  json cat = json::array();
  for (const Effect e : o.catalogue) cat.push_back(effect_name(e));
  return json{{"catalogue", cat},
              {"min_delta_bic", o.min_delta_bic},
              {"min_rss_reduction", o.min_rss_reduction},
              {"max_effects", o.max_effects},
              {"fit_samples", r.fit_samples},
              {"fit_stride", r.fit_stride},
              {"smoothing_half_window_s", o.smoothing_half_window_s},
              {"baseline_effective_samples", r.n_eff_baseline}};
}

/// {effect: params_json} for `effects`, whose parameters `params` holds packed in that order.
/// `forms`: the effects' forms, by which the parameters are packed (EffectSet::forms).
json effect_params_json(const std::vector<Effect>& effects, std::span<const double> params,
                        const EffectForms& forms) {
  json out = json::object();
  const EffectSet set{effects, forms};
  for (const Effect e : effects) {
    const auto off = *set.offset(e);
    const auto own = set.params_of(e);
    json j = params_json(e, params.subspan(off, own.size()));
    if (set.form(e) != 0) {
      // A form other than the first: its parameters by their own names.
      j = json::object();
      for (std::size_t i = 0; i < own.size(); ++i) j[std::string(own[i].name)] = params[off + i];
    }
    j["form"] = std::string(form_name(e, set.form(e)));
    out[std::string(effect_name(e))] = j;
  }
  return out;
}



void note(std::vector<std::string>& problems, const report::PlotResult& r, const std::filesystem::path& png) {
  if (!r.ok) problems.push_back(png.filename().string() + ": " + r.reason);
}

/// fit.csv: input, coil current, measured/baseline/updated force and residuals at every sample.
void write_fit_csv(const std::filesystem::path& dir, const MeasuredData& data, const DiscrepancyResult& r) {
  const std::size_t n = data.size();
  report::TimeSeries ts({"time_s", "displacement_m", "velocity_m_s", "current_cmd_A", "coil_current_A",
                         "force_measured_N", "force_baseline_N", "force_updated_N", "residual_before_N",
                         "residual_after_N"});
  ts.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    ts.add_row({data.time_s[k], r.disp_m[k], r.vel_m_s[k], data.current_cmd_a[k], r.coil_current_a[k],
                data.force_n[k], r.baseline_force_n[k], r.updated_force_n[k], data.force_n[k] - r.baseline_force_n[k],
                data.force_n[k] - r.updated_force_n[k]});
  }
  report::write_csv(ts, dir / "fit.csv");
}

std::string model_label(const DiscrepancyResult& r) {
  if (!r.rejected.empty()) return "fitted, rejected: " + EffectSet{r.rejected}.label();
  return r.effects.empty() ? "updated (= baseline)" : "updated: " + EffectSet{r.effects}.label();
}

/// force_time.png and residual.png, thinned to about 20000 points.
void plot_force_and_residual(const std::filesystem::path& dir, const MeasuredData& data, const DiscrepancyResult& r,
                             std::vector<std::string>& problems) {
  const std::size_t n = data.size();
  const std::size_t stride = std::max<std::size_t>(1, n / 20000);
  const auto t = thin(data.time_s, stride);
  const std::string label = model_label(r);
  std::vector<double> res_b(n), res_a(n);
  for (std::size_t k = 0; k < n; ++k) {
    res_b[k] = data.force_n[k] - r.baseline_force_n[k];
    res_a[k] = data.force_n[k] - r.updated_force_n[k];
  }
  report::PlotSpec ft{data.source + ": force", "time [s]", "force [kN]",
                      {{"measured", t, thin(data.force_n, stride, 1e-3)},
                       {"baseline (" + r.baseline_name + ")", t, thin(r.baseline_force_n, stride, 1e-3)},
                       {label, t, thin(r.updated_force_n, stride, 1e-3)}}};
  note(problems, report::plot_png(ft, dir / "force_time.png"), dir / "force_time.png");
  report::PlotSpec rs{data.source + ": residual (measured - model)", "time [s]", "force residual [kN]",
                      {{"before (baseline)", t, thin(res_b, stride, 1e-3)},
                       {"after (" + label + ")", t, thin(res_a, stride, 1e-3)}}};
  note(problems, report::plot_png(rs, dir / "residual.png"), dir / "residual.png");
}

/// loops.png: force against displacement and velocity, thinned to about 8000 points.
void plot_loops(const std::filesystem::path& dir, const MeasuredData& data, const DiscrepancyResult& r,
                std::vector<std::string>& problems) {
  const std::size_t ls = std::max<std::size_t>(1, data.size() / 8000);
  const std::string label = model_label(r);
  const auto x_mm = thin(r.disp_m, ls, 1e3);
  const auto v_mm_s = thin(r.vel_m_s, ls, 1e3);
  const auto fm = thin(data.force_n, ls, 1e-3);
  const auto fb = thin(r.baseline_force_n, ls, 1e-3);
  const auto fu = thin(r.updated_force_n, ls, 1e-3);
  report::MultiPlot mp;
  mp.title = data.source + ": force-displacement and force-velocity loops";
  mp.columns = 2;
  mp.width_px = 1400;
  mp.height_px = 650;
  mp.panels.push_back({"force - displacement",
                       "displacement [mm]",
                       "force [kN]",
                       {{"measured", x_mm, fm}, {"baseline", x_mm, fb}, {label, x_mm, fu}}});
  mp.panels.push_back({"force - velocity",
                       "velocity [mm/s]",
                       "force [kN]",
                       {{"measured", v_mm_s, fm}, {"baseline", v_mm_s, fb}, {label, v_mm_s, fu}}});
  // One key, above the force–displacement loop, clear of the loops' tops.
  mp.panels[0].key_headroom = 0.3;
  mp.panels[1].key = false;
  note(problems, report::plot_png(mp, dir / "loops.png"), dir / "loops.png");
}

std::string markdown(const MeasuredData& data, const DiscrepancyResult& r) {
  std::string md = "# Model discrepancy: " + data.source + "\n\n";
  md += std::to_string(data.size()) + " samples over " + g4(data.duration_s()) + " s; velocity " +
        (r.velocity_derived ? "derived from the displacement" : "measured") + "; coil current " +
        (data.current_a.empty() ? "from the command (Eq. 4.5)" : "measured (Eq. 4.5's slow branch on it)") +
        ".\n\n";
  md += "Baseline: " + r.baseline_name + " (expected gap " + pct(r.expected_gap) +
        (r.expected_gap > 0.0 ? std::string(", the largest on ") + gap_basis_phrase(r.expected_gap_basis) : "") +
        ").\n\n";
  md += "**Verdict: " + std::string(verdict_name(r.verdict)) + "**\n\n";
  for (const auto& f : r.findings) md += "- " + f + "\n";
  md += "\n**Effects named:** " + (r.effects.empty() ? std::string("none") : EffectSet{r.effects}.label()) + "\n\n";
  md += "**Gap** (normalized RMS force error), on the samples the fits saw: " + pct(r.gap_before) + " before, " +
        pct(r.gap_after) + " after; held out (30 %, never fitted): " + pct(r.gap_validation_before) + " before, " +
        pct(r.gap_validation_after) + " after.\n\n";
  if (!r.effects.empty()) {
    md += "| effect | parameter | value |\n|---|---|---:|\n";
    const EffectSet set{r.effects, r.forms};
    for (const Effect e : r.effects) {
      const auto off = *set.offset(e);
      const auto& info = effect_info(e);
      const auto own = set.params_of(e);
      for (std::size_t i = 0; i < own.size(); ++i) {
        md += "| " + std::string(info.name) + " (" + std::string(form_name(e, set.form(e))) + ") | " +
              std::string(own[i].name) + " | " + g4(r.params[off + i]) + " |\n";
      }
    }
    md += "\n";
  }
  md += "## Selection\n\nScore: delta BIC with the effective sample count of the residual (positive favours the "
        "effect).\n\n";
  for (std::size_t i = 0; i < r.rounds.size(); ++i) {
    const auto& rd = r.rounds[i];
    md += "### Round " + std::to_string(i + 1) + " (model: " + EffectSet{rd.model}.label() + ", gap " + pct(rd.gap) +
          ")\n\n| candidate | delta BIC | residual power removed | held out | gap | verdict |\n|---|---:|---:|---:|---:|---|\n";
    for (const auto& c : rd.candidates) {
      md += "| " + (c.alternative ? EffectSet{c.model}.label() + " (instead)" : std::string(effect_name(c.effect))) +
            " | " + g4(c.delta_bic) + " | " + pct(c.rss_reduction) + " | " + pct(c.held_out_reduction) +
            " | " + pct(c.gap) + " | " + c.verdict + " |\n";
    }
    md += "\n";
  }
  if (!r.dropped.empty()) md += "Dropped again by the backward check: " + EffectSet{r.dropped}.label() + "\n\n";
  md += "## Where the baseline gap concentrates\n\n| region | share of time | share of gap | concentration | RMS "
        "before [kN] | RMS after [kN] | magnitude bias [kN] |\n|---|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& s : r.regions) {
    md += "| " + s.name + (s.concentrated ? " **(concentrated)**" : "") + " | " + pct(s.fraction_of_time) + " | " +
          pct(s.share_of_gap_before) + " | " + g4(s.concentration_before) + " | " + g4(s.rms_before_n / 1e3) + " | " +
          g4(s.rms_after_n / 1e3) + " | " + g4(s.magnitude_bias_before_n / 1e3) + " |\n";
  }
  md += "\n| window [s] | RMS before [kN] | RMS after [kN] |\n|---|---:|---:|\n";
  for (const auto& w : r.windows) {
    md += "| " + g4(w.start_s) + " - " + g4(w.end_s) + " | " + g4(w.rms_before_n / 1e3) + " | " +
          g4(w.rms_after_n / 1e3) + " |\n";
  }
  md += "\n## What the residual looks like (held-out share of its power per signature)\n\n| signature | looks like | "
        "baseline | updated |\n|---|---|---:|---:|\n";
  for (const auto& s : r.signatures_before.signatures) {
    double after = 0.0;
    for (const auto& a : r.signatures_after.signatures) {
      if (a.name == s.name) after = a.held_out_share;
    }
    md += "| " + s.name + " | " + s.looks_like + " | " + pct(s.held_out_share) + " | " + pct(after) + " |\n";
  }
  md += "| all together | | " + pct(r.signatures_before.structured_share) + " | " +
        pct(r.signatures_after.structured_share) + " |\n";
  md += "\n![force](force_time.png)\n\n![residual](residual.png)\n\n![loops](loops.png)\n";
  return md;
}

}  // namespace

json params_json(Effect e, std::span<const double> params) {
  json j = json::object();
  const auto& info = effect_info(e);
  for (std::size_t i = 0; i < info.params.size() && i < params.size(); ++i) j[std::string(info.params[i].name)] = params[i];
  if (e == Effect::idle_settling && !params.empty()) {
    const physics::ParticipantRatioParams prp{};
    const auto c = physics::pr_coefficients(prp, params[0]);  // Eq. 5.6–5.8
    j["a_pr"] = c.a_pr;
    j["b_pr"] = c.b_pr;
    j["c_pr"] = c.c_pr;
    const double t_max_s = physics::max_settling_time_s(physics::SettlingParams{});  // Eq. 5.4
    // Eq. 5.5 inverted; at SQ = 1 the idle time is only bounded below.
    j["idle_years_equivalent"] = units::s_to_years(params[0] * t_max_s);
    j["idle_years_at_least"] = params[0] >= 1.0 - 1e-9;
  }
  return j;
}

json summary_json(const MeasuredData& data, const DiscrepancyResult& r, const DiscrepancyOptions& o) {
  json j;
  j["measured"] = data.source;
  j["samples"] = data.size();
  j["duration_s"] = data.duration_s();
  j["velocity"] = r.velocity_derived ? "derived" : "measured";
  j["coil_current"] = data.current_a.empty() ? "commanded" : "measured";
  j["verdict"] = verdict_name(r.verdict);
  j["findings"] = r.findings;
  j["warnings"] = r.warnings;
  j["baseline"] = json{{"name", r.baseline_name},
                       {"expected_gap", r.expected_gap},
                       {"expected_gap_basis", gap_basis_name(r.expected_gap_basis)},
                       {"mismatch", r.baseline_check.mismatch},
                       {"mismatch_reasons", r.baseline_check.reasons},
                       {"force_ratio", r.baseline_check.force_ratio},
                       {"min_force_ratio", r.baseline_check.min_force_ratio},
                       {"max_force_ratio", kMaxForceRatio},
                       {"record_velocity_max_m_s", r.baseline_check.velocity_max_m_s},
                       {"record_current_min_a", r.baseline_check.current_min_a},
                       {"record_current_max_a", r.baseline_check.current_max_a},
                       {"record_amplitude_m", r.baseline_check.amplitude_m},
                       {"record_frequency_hz", r.baseline_check.frequency_hz},
                       {"outside_coverage", r.baseline_check.outside_coverage}};
  j["effects"] = effects_json(r.effects);
  j["gap_before"] = r.gap_before;
  j["gap_after"] = r.gap_after;
  j["gap_validation_before"] = r.gap_validation_before;
  j["gap_validation_after"] = r.gap_validation_after;
  j["gap_reduction"] = r.gap_before > 0.0 ? 1.0 - r.gap_after / r.gap_before : 0.0;
  j["parameters"] = effect_params_json(r.effects, r.params, r.forms);
  j["rejected"] = effects_json(r.rejected);
  j["rejected_parameters"] = effect_params_json(r.rejected, r.rejected_params, r.forms);
  j["residual_before"] = signatures_json(r.signatures_before);
  j["residual_after"] = signatures_json(r.signatures_after);
  j["candidates"] = json::array();
  if (!r.rounds.empty()) {
    for (const auto& c : r.rounds.front().candidates) j["candidates"].push_back(candidate_json(c));
  }
  j["rounds"] = json::array();
  for (const auto& rd : r.rounds) j["rounds"].push_back(round_json(rd));
  j["dropped"] = effects_json(r.dropped);
  if (r.filter_check.checked) {
    // filter_check.hpp: the selected delay against a first-order low-pass in its place.
    j["delay_against_lowpass"] = json{{"delay_s", r.filter_check.delay_s},
                                      {"lowpass_tau_s", r.filter_check.tau_s},
                                      {"delta_bic", r.filter_check.delta_bic},
                                      {"held_out_reduction", r.filter_check.held_out_reduction},
                                      {"lowpass_better", r.filter_check.lowpass_better}};
  }
  if (r.filter_check.compliance_checked) {
    // filter_check.hpp: the selected delay or pre-yield hysteresis against a series compliance in its place.
    j["selected_against_compliance"] = json{{"compliance_m_per_n", r.filter_check.compliance_m_per_n},
                                            {"delta_bic", r.filter_check.compliance_delta_bic},
                                            {"held_out_reduction", r.filter_check.compliance_held_out_reduction},
                                            {"compliance_better", r.filter_check.compliance_better}};
  }
  j["regions"] = json::array();
  for (const auto& s : r.regions) j["regions"].push_back(region_json(s));
  j["time_windows"] = json::array();
  for (const auto& w : r.windows) j["time_windows"].push_back(window_json(w));
  j["settings"] = settings_json(r, o);
  return j;
}

std::vector<std::string> write_discrepancy_outputs(const std::filesystem::path& dir, const MeasuredData& data,
                                                   const DiscrepancyResult& r, const DiscrepancyOptions& options,
                                                   bool plots) {
  write_fit_csv(dir, data, r);
  std::vector<std::string> problems;
  if (plots) {
    plot_force_and_residual(dir, data, r, problems);
    plot_loops(dir, data, r, problems);
  }
  report::write_file_atomically(dir / "report.md", markdown(data, r));
  report::write_summary_json(dir, summary_json(data, r, options));
  return problems;
}

json synth_json(const SynthCase& c, const SynthSpec& spec) {
  json params = effect_params_json(c.effects, c.params, EffectForms{});
  for (std::size_t i = 0; i < c.effects.size(); ++i) {
    params[std::string(effect_name(c.effects[i]))]["effect_rms_n"] = c.effect_rms_n[i];
  }
  json j{{"effects", effects_json(c.effects)},
              {"parameters", params},
              {"input", c.input_description},
              {"current", c.current_description},
              {"force_noise_rms_n", c.force_noise_rms_n},
              {"displacement_noise_m", c.disp_noise_m},
              {"true_gap", c.true_gap},
              {"draws", c.draws},
              {"seed", spec.seed},
              {"duration_s", c.data.duration_s()},
              {"rate_hz", spec.rate_hz},
              {"jitter", spec.jitter},
              {"samples", c.data.size()}};
  if (spec.baseline) j["baseline"] = {{"name", spec.baseline->name}, {"law", baseline_form_name(*spec.baseline)}};
  return j;
}

std::filesystem::path write_synth_outputs(const std::filesystem::path& dir, const SynthCase& c, const SynthSpec& spec,
                                          RecordFormat format) {
  const auto data_path = dir / (format == RecordFormat::mat ? "measured.mat" : "measured.csv");
  if (format == RecordFormat::mat) {
    write_measured_mat(c.data, data_path);
  } else {
    report::write_file_atomically(data_path, measured_to_csv(c.data));
  }
  report::write_summary_json(dir, synth_json(c, spec));
  return data_path;
}

}  // namespace mrd::discrepancy
