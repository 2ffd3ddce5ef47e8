#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>

#include "host_sim/io/text.hpp"
#include "host_sim/report/output_dir.hpp"
#include "host_sim/report/summary_json.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/run_outputs.hpp"
#include "host_sim/run/study.hpp"
#include "host_sim/run/sweep_report.hpp"
#include "host_sim/run/thesis_building.hpp"
#include "host_sim/run/validity.hpp"

namespace mrd::run {
namespace {

using io::format_number;

std::string pct(double now, double before) { return format_number("%+.1f %%", 100.0 * (now - before) / before); }

/// "a → b (±x %)": the two values as shown, in `format`, and the change from
/// `before` to `now` in %.
std::string change(const char* format, double shown_before, double shown_now, double before, double now) {
  return format_number(format, shown_before) + " → " + format_number(format, shown_now) + " (" + pct(now, before) +
         ")";
}

std::string comparison_png(const StudyRow& row) {
  return row.motion + "_" + control::mode_name(row.mode) + ".png";
}

bool thesis_building(const StudyResult& r) { return is_thesis_building(r.options.building); }

/// A damper or fluid file was given.
bool own_damper_or_fluid(const StudyResult& r) {
  return !r.options.damper_name.empty() || !r.options.fluid_name.empty();
}

void write_title(std::ostream& md, const StudyResult& r) {
  if (thesis_building(r)) {
    md << "# Chapter-6 study: idle time and the seismic performance of a base-isolated building\n\n";
  } else {
    const structure::BuildingParams& b = r.options.building;
    md << "# Chapter-6 study on " << b.name << ": idle time and the seismic performance of the building\n\n"
       << "Building: " << b.name << " (building file), " << b.dofs() << " degrees of freedom, "
       << (b.base == structure::BaseKind::kFixed ? "fixed base" : "isolated base") << ", " << b.isolators.size()
       << " isolator group(s), " << b.dampers.size() << " damper placement(s).";
    if (!own_damper_or_fluid(r)) md << " The damper records, the sine tests and the settling time are the thesis damper's.";
    md << "\n\n";
  }
  if (own_damper_or_fluid(r)) {
    const std::string& d = r.options.damper_name;
    const std::string& f = r.options.fluid_name;
    md << "Damper: " << (d.empty() ? "the thesis's 200 kN damper" : d + " (damper file)") << "; MR fluid: "
       << (f.empty() ? "the thesis's model fluid" : f + " (fluid file)")
       << ". The sine tests of Table 5.1 below check the thesis damper's model against Table 5.2.\n\n";
  }
  if (r.synthetic_motions) {
    md << "> The four records of Table 6.2 were not found (no shared data folder): this report uses four "
          "synthetic Kanai-Tajimi motions instead. Its numbers are not the thesis's.\n\n";
  }
}

/// §6.1: the first three modes (fewer for a building with fewer DOFs).
void write_structure(std::ostream& md, const StudyResult& r) {
  const bool thesis = thesis_building(r);
  md << (thesis ? "## Structure (Table 6.1, Fig. 6.2)" : "## Structure: " + r.options.building.name)
     << "\n\n| mode | frequency | damping ratio |\n|---:|---:|---:|\n";
  for (std::size_t i = 0; i < std::min<std::size_t>(3, r.modal.frequencies_hz.size()); ++i) {
    md << "| " << i + 1 << " | " << format_number("%.4f Hz", r.modal.frequencies_hz[i]) << " | "
       << format_number("%.2f %%", 100.0 * r.modal.damping_ratios[i]) << " |\n";
  }
  if (thesis) {
    md << "\nThesis: 0.25 Hz; 4.97 %, 3.17 %, 5.07 %.\n\n";
  } else {
    md << "\nModes of the building without the MR dampers";
    if (!r.modal.isolator_stiffness.empty()) md << ", the " << r.modal.isolator_stiffness;
    md << ".\n\n";
  }
}

/// §5.3: settling time and the sine tests of Table 5.1.
void write_idle_model(std::ostream& md, const StudyResult& r) {
  const bool measured = r.options.settling.measured_max_settling_time_s > 0.0;
  md << "## Damper after idle time (§5.3)\n\nMaximum settling time ("
     << (measured ? "measured, fluid file" : "Eq. 5.4") << "): "
     << format_number("%.4f", r.max_settling_time_years)
     << " years (thesis 0.8531). ";
  if (r.options.idle_years >= r.max_settling_time_years) {
    md << "Past it the settling quotient saturates at 1, so " << r.options.idle_years
       << " years idle is a fully settled damper.\n\n";
  } else {
    md << r.options.idle_years << " years idle is a settling quotient of "
       << format_number("%.4f", r.options.idle_years / r.max_settling_time_years) << " (Eq. 5.5).\n\n";
  }
  md << "Sine tests of Table 5.1, model against Table 5.2 (a):\n\n| case | initial force | max force | rise to 90 % | "
        "rise to 95 % |\n|---|---:|---:|---:|---:|\n";
  for (const auto& [c, m] : r.sine_cases) {
    md << "| " << c.name << " | " << format_number("%.1f", m.initial_force_n / 1e3) << " / " << c.initial_force_kn
       << " kN | " << format_number("%.1f", m.max_force_n / 1e3) << " / " << c.max_force_kn << " kN | "
       << format_number("%.2f", m.rise_time_90_s) << " / " << c.rise_time_90_s << " s | "
       << format_number("%.2f", m.rise_time_95_s) << " / " << c.rise_time_95_s << " s |\n";
  }
  md << "\n(model / measured)\n\n";
}

/// §6.4, Fig. 6.9–6.11: the table of peaks and the plots drawn.
void write_earthquakes(std::ostream& md, const StudyResult& r, const std::vector<std::string>& figures) {
  const StudyOptions& o = r.options;
  // Another building than the thesis's adds its story drift and, isolated
  // on bearings, their summed force.
  const bool drift_column = !thesis_building(r);
  const bool isolator_column = drift_column && !o.building.isolators.empty();
  md << "## Earthquakes at " << o.pga_g << " g: fully mixed against " << o.idle_years
     << " years idle (Fig. 6.9-6.11)\n\n"
     << "| record | control | peak base displacement [mm] | peak damper force [kN] | peak superstructure accel [m/s²] |"
     << (isolator_column ? " peak isolator force [kN] |" : "") << (drift_column ? " peak story drift [mm] |" : "")
     << "\n|---|---|---:|---:|---:|" << (isolator_column ? "---:|" : "") << (drift_column ? "---:|" : "") << "\n";
  for (const auto& row : r.rows) {
    const auto& a = row.fully_mixed;
    const auto& b = row.idle;
    md << "| " << row.label << " | " << control::mode_name(row.mode) << " | "
       << change("%.1f", a.peak_base_displacement_m * 1e3, b.peak_base_displacement_m * 1e3,
                 a.peak_base_displacement_m, b.peak_base_displacement_m)
       << " | "
       << change("%.1f", a.peak_damper_force_n / 1e3, b.peak_damper_force_n / 1e3, a.peak_damper_force_n,
                 b.peak_damper_force_n)
       << " | "
       << change("%.3f", a.peak_superstructure_accel_m_s2, b.peak_superstructure_accel_m_s2,
                 a.peak_superstructure_accel_m_s2, b.peak_superstructure_accel_m_s2)
       << " |";
    if (isolator_column) {
      md << " "
         << change("%.1f", a.peak_isolator_force_n / 1e3, b.peak_isolator_force_n / 1e3, a.peak_isolator_force_n,
                   b.peak_isolator_force_n)
         << " |";
    }
    if (drift_column) {
      md << " "
         << change("%.2f", a.peak_story_drift_m * 1e3, b.peak_story_drift_m * 1e3, a.peak_story_drift_m,
                   b.peak_story_drift_m)
         << " |";
    }
    md << "\n";
  }
  md << "\n(fully mixed → " << o.idle_years << " years idle)\n\n";
  for (const auto& f : figures) md << "![" << f << "](" << f << ")\n\n";
}

/// Fig. 6.12–6.20.
void write_sweep_section(std::ostream& md, const StudyResult& r, const std::vector<std::string>& pngs) {
  md << "## Idle-time sweep, 0 to 1 year every 0.05 year (Fig. 6.12-6.20)\n\n"
     << r.sweep->rows.size() << " closed-loop runs in " << format_number("%.2f", r.sweep->wall_s)
     << " s. The curves flatten past the maximum settling time, " << format_number("%.3f", r.max_settling_time_years)
     << (r.max_settling_time_years > 1.0 ? " years, beyond the sweep's last idle time" : " years")
     << ". Data: [sweep/sweep.csv](sweep/sweep.csv).\n\n";
  for (const auto& p : pngs) md << "![" << p << "](sweep/" << p << ")\n\n";
}

void write_model(std::ostream& md, const StudyResult& r) {
  md << "## Model\n\nDamper: Bingham plastic with exponential current laws and transition function (Eq. 4.1-4.4, "
        "Table 4.1), coil dynamics Eq. 4.5 at unity DC gain, idle time through the participant ratio "
        "(Eq. 5.5-5.12, Table 5.6) with the mixing integral calibrated to Table 5.2. ";
  const structure::BuildingParams& b = r.options.building;
  if (thesis_building(r)) {
    md << "Structure: 6-DOF shear building of Table 6.1, exact zero-order hold at " << r.options.step_s * 1e3
       << " ms.";
  } else {
    md << "Structure: " << b.name << ", " << b.dofs() << "-DOF shear building of its building file, exact zero-order "
       << "hold at " << r.options.step_s * 1e3 << " ms";
    if (!b.isolators.empty()) {
      md << " in " << plant::structural_substeps(b, r.options.step_s)
         << " sub-steps per step, the isolators' hysteretic force held over each";
    }
    md << ".";
  }
  md << " Passive-on is " << fw::kPassiveOnCurrent_a << " A.\n";
}

/// A run's peaks; `building_peaks`: with the isolator force and story drift
/// (a building other than the thesis's, whose summary keeps the thesis's keys).
nlohmann::json peaks_json(const plant::PlantSummary& s, bool building_peaks) {
  nlohmann::json j{{"peak_base_displacement_m", s.peak_base_displacement_m},
                   {"peak_damper_force_kn", s.peak_damper_force_n / 1e3},
                   {"peak_superstructure_accel_m_s2", s.peak_superstructure_accel_m_s2},
                   {"sq", s.sq}};
  if (building_peaks) {
    j["peak_isolator_force_kn"] = s.peak_isolator_force_n / 1e3;
    j["peak_story_drift_m"] = s.peak_story_drift_m;
  }
  return j;
}

}  // namespace

std::vector<std::string> study_warnings(const StudyResult& r) {
  std::vector<ValidityPeaks> peaks;
  std::vector<double> base_m;
  const auto add = [&](const plant::PlantSummary& s) {
    peaks.push_back(validity_peaks(s));
    base_m.push_back(s.peak_base_displacement_m);
  };
  for (const auto& row : r.rows) {
    add(row.fully_mixed);
    add(row.idle);
  }
  if (r.sweep) {
    for (const auto& row : r.sweep->rows) add(row.summary);
  }
  std::vector<std::string> w = validity_warnings(peaks, r.options.damper.rating);
  for (std::string& s : bearing_capacity_warnings(base_m, r.options.building)) w.push_back(std::move(s));
  return w;
}

namespace {

nlohmann::json study_summary_json(const StudyResult& r) {
  nlohmann::json runs = nlohmann::json::array();
  for (const auto& row : r.rows) {
    runs.push_back({{"record", row.motion},
                    {"control", control::mode_name(row.mode)},
                    {"fully_mixed", peaks_json(row.fully_mixed, !thesis_building(r))},
                    {"idle", peaks_json(row.idle, !thesis_building(r))},
                    {"plot", comparison_png(row)}});
  }
  nlohmann::json sweep;
  if (r.sweep) sweep = {{"runs", r.sweep->rows.size()}, {"wall_time_s", r.sweep->wall_s}, {"csv", "sweep/sweep.csv"}};
  nlohmann::json j{{"pga_g", r.options.pga_g},
                        {"idle_years", r.options.idle_years},
                        {"synthetic_motions", r.synthetic_motions},
                        {"max_settling_time_years", r.max_settling_time_years},
                        {"runs", runs},
                        {"sweep", sweep},
                        {"warnings", study_warnings(r)},
                        {"report", "report.md"}};
  // The thesis building keeps the thesis's summary; any other is named.
  if (!thesis_building(r)) {
    j["building"] = r.options.building.name;
    j["dofs"] = r.options.building.dofs();
  }
  return j;
}

/// One comparison plot per row; the names of those drawn go to `figures`.
void write_comparison_plots(const std::filesystem::path& dir, const StudyResult& r, std::vector<std::string>& figures,
                            std::vector<std::string>& problems) {
  const std::string idle_label = format_number("%.3g", r.options.idle_years) + " years idle";
  for (const auto& row : r.rows) {
    const std::string png = comparison_png(row);
    const auto p = write_comparison_plot(dir / png, row.label + ", " + control::mode_name(row.mode), "fully mixed",
                                         row.fully_mixed_record, idle_label, row.idle_record);
    if (p.empty()) figures.push_back(png);
    problems.insert(problems.end(), p.begin(), p.end());
  }
}

}  // namespace

std::vector<std::string> write_study_outputs(const std::filesystem::path& dir, const StudyResult& r) {
  std::vector<std::string> problems;
  std::vector<std::string> figures;
  write_comparison_plots(dir, r, figures, problems);
  std::vector<std::string> sweep_pngs;
  if (r.sweep) {
    const auto sweep_dir = dir / "sweep";
    report::prepare_output_dir(sweep_dir);
    const auto p = write_sweep_outputs(sweep_dir, r.sweep->spec, r.sweep->rows, &sweep_pngs);
    problems.insert(problems.end(), p.begin(), p.end());
  }

  std::ostringstream md;
  write_title(md, r);
  write_structure(md, r);
  write_idle_model(md, r);
  write_earthquakes(md, r, figures);
  if (r.sweep) write_sweep_section(md, r, sweep_pngs);
  write_model(md, r);
  report::write_file_atomically(dir / "report.md", md.str());
  report::write_summary_json(dir, study_summary_json(r));
  return problems;
}

}  // namespace mrd::run
