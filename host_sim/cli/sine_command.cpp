#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "host_sim/cli/command.hpp"
#include "mrd/units.hpp"
#include "host_sim/report/output_dir.hpp"
#include "host_sim/report/plot.hpp"
#include "host_sim/report/time_series.hpp"
#include "host_sim/run/mixing_calibration.hpp"
#include "host_sim/run/sine_test.hpp"

namespace mrd::cli {
namespace {

constexpr const char* kSineHelp = R"(Drives the damper model (Bingham + transition, Eq. 4.1-4.4; idle-time participant ratio,
Eq. 5.5-5.12; coil dynamics Eq. 4.5) with x(t) = A sin(2 pi f t) at a constant current, after an
idle time. The current is steady from the start, as in the thesis's tests (§5.2).

Fields of DIR/summary.json (definitions of Table 5.2):
  fully_mixed_force_kn  largest |F| of the same test on fully mixed fluid (SQ = 0), kN
  initial_force_kn      |F| at the first velocity peak (t = 0), before any fluid is displaced, kN
  max_force_kn          largest |F| over the test, kN
  rise_time_90_s        first time |F| reaches 90 % of max_force_kn, s from the start
  rise_time_95_s        first time |F| reaches 95 % of max_force_kn, s from the start
  sq                    settling quotient at the start (Eq. 5.5)
Files: DIR/sine.csv (time_s, disp_m, vel_m_s, force_n, current_a, participant_ratio at every
step), DIR/force_time.png and DIR/force_displacement.png.

--thesis-cases runs the three cases of Table 5.1 and prints model against measured (Table 5.2)
with the errors; with --out it writes DIR/thesis_cases.md and DIR/summary.json.
--calibrate refits the effective mixing area behind the integral of Q dt (Eq. 5.9) to the six rise
times of Table 5.2 and prints it.)";

struct SineOptions {
  double amplitude_mm = 25.4;
  double freq_hz = 0.5;
  double current_a = 2.5;
  double idle_years = 0.0;
  double duration_s = 60.0;
  double step_s = 1.0e-3;
  bool thesis_cases = false;
  bool calibrate = false;
  std::string out_dir;
};

double pct_error(double model, double measured) { return 100.0 * (model - measured) / measured; }

std::string thesis_cases_markdown() {
  std::ostringstream os;
  char buf[256];
  os << "| case | metric | model | measured (Table 5.2) | error |\n|---|---|---:|---:|---:|\n";
  for (const auto& c : run::thesis_sine_cases()) {
    const run::SineMetrics m = run::run_sine_test(c.spec);
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

void run_thesis_cases(const SineOptions& o) {
  const std::string md = thesis_cases_markdown();
  std::printf("Table 5.1 sine tests: model against Table 5.2 (a)\n\n%s", md.c_str());
  if (o.out_dir.empty()) return;
  const std::filesystem::path dir(o.out_dir);
  report::write_file_atomically(dir / "thesis_cases.md",
                                "# Sine tests of Table 5.1: model against Table 5.2 (a)\n\n" + md);
  nlohmann::json cases = nlohmann::json::array();
  for (const auto& c : run::thesis_sine_cases()) {
    const run::SineMetrics m = run::run_sine_test(c.spec);
    cases.push_back({{"name", c.name},
                     {"model", {{"fully_mixed_force_kn", m.fully_mixed_force_n / 1e3},
                                {"initial_force_kn", m.initial_force_n / 1e3},
                                {"max_force_kn", m.max_force_n / 1e3},
                                {"rise_time_90_s", m.rise_time_90_s},
                                {"rise_time_95_s", m.rise_time_95_s}}},
                     {"measured", {{"fully_mixed_force_kn", c.fully_mixed_force_kn},
                                   {"initial_force_kn", c.initial_force_kn},
                                   {"max_force_kn", c.max_force_kn},
                                   {"rise_time_90_s", c.rise_time_90_s},
                                   {"rise_time_95_s", c.rise_time_95_s}}}});
  }
  report::write_file_atomically(dir / "summary.json", nlohmann::json{{"thesis_cases", cases}}.dump(2) + "\n");
  std::printf("\nwrote %s/thesis_cases.md and summary.json\n", o.out_dir.c_str());
}

void run_calibration() {
  const run::MixingCalibration c = run::calibrate_mixing_area({});
  std::printf("effective mixing area %.5f m^2 (integral of Q dt in litres), RMS log error %.3f\n", c.flow_area_m2,
              c.rms_log_error);
  for (const auto& k : c.cases) {
    std::printf("  %-38s t90 %7.3f s (measured %6.3f)   t95 %7.3f s (measured %6.3f)\n", k.name.c_str(),
                k.model_rise_90_s, k.thesis_rise_90_s, k.model_rise_95_s, k.thesis_rise_95_s);
  }
}

void run_single(const SineOptions& o) {
  run::SineTestSpec spec{units::mm_to_m(o.amplitude_mm), o.freq_hz, o.current_a, o.idle_years, o.duration_s, o.step_s};
  run::SineRecord rec;
  const bool keep = !o.out_dir.empty();
  const run::SineMetrics m = run::run_sine_test(spec, {}, {}, keep ? &rec : nullptr);
  std::printf("sine %.4g mm, %.4g Hz, %.4g A, idle %.4g years (SQ %.3f), %.4g s\n", o.amplitude_mm, o.freq_hz,
              o.current_a, o.idle_years, m.sq, o.duration_s);
  std::printf("  fully mixed force   %9.2f kN\n  initial force       %9.2f kN (%.1f %% of fully mixed)\n",
              m.fully_mixed_force_n / 1e3, m.initial_force_n / 1e3, 100.0 * m.initial_force_n / m.fully_mixed_force_n);
  std::printf("  max force           %9.2f kN (%.1f %% of fully mixed)\n", m.max_force_n / 1e3,
              100.0 * m.max_force_n / m.fully_mixed_force_n);
  std::printf("  rise time to 90 %%   %9.3f s\n  rise time to 95 %%   %9.3f s\n", m.rise_time_90_s, m.rise_time_95_s);
  if (!keep) return;
  const std::filesystem::path dir(o.out_dir);
  report::TimeSeries ts({"time_s", "disp_m", "vel_m_s", "force_n", "current_a", "participant_ratio"});
  ts.reserve(rec.time_s.size());
  for (std::size_t k = 0; k < rec.time_s.size(); ++k) {
    ts.add_row({rec.time_s[k], rec.disp_m[k], rec.vel_m_s[k], rec.force_n[k], rec.current_a[k], rec.pr[k]});
  }
  report::write_csv(ts, dir / "sine.csv");
  std::vector<double> t, x_mm, f_kn;
  for (std::size_t k = 0; k < rec.time_s.size(); k += 5) {
    t.push_back(rec.time_s[k]);
    x_mm.push_back(rec.disp_m[k] * 1e3);
    f_kn.push_back(rec.force_n[k] / 1e3);
  }
  char title[160];
  std::snprintf(title, sizeof title, "Sine %.3g mm, %.3g Hz, %.3g A after %.3g years idle", o.amplitude_mm, o.freq_hz,
                o.current_a, o.idle_years);
  report::PlotSpec ft{title, "time [s]", "damper force [kN]", {{"model", t, f_kn, "lines"}}};
  ft.key = false;
  report::PlotSpec fd{title, "displacement [mm]", "damper force [kN]", {{"model", x_mm, f_kn, "lines"}}};
  fd.key = false;
  for (const auto& [spec_p, name] : {std::pair{&ft, "force_time.png"}, std::pair{&fd, "force_displacement.png"}}) {
    const auto r = report::plot_png(*spec_p, dir / name);
    if (!r.ok) std::fprintf(stderr, "mrd sine: warning: plot %s not written: %s\n", name, r.reason.c_str());
  }
  const nlohmann::json j{{"fully_mixed_force_kn", m.fully_mixed_force_n / 1e3},
                         {"initial_force_kn", m.initial_force_n / 1e3},
                         {"max_force_kn", m.max_force_n / 1e3},
                         {"rise_time_90_s", m.rise_time_90_s},
                         {"rise_time_95_s", m.rise_time_95_s},
                         {"sq", m.sq},
                         {"amplitude_mm", o.amplitude_mm},
                         {"freq_hz", o.freq_hz},
                         {"current_a", o.current_a},
                         {"idle_years", o.idle_years},
                         {"duration_s", o.duration_s}};
  report::write_file_atomically(dir / "summary.json", j.dump(2) + "\n");
  std::printf("wrote %s/summary.json, sine.csv and plots\n", o.out_dir.c_str());
}

}  // namespace

Command add_sine_command(CLI::App& parent) {
  auto o = std::make_shared<SineOptions>();
  CLI::App* app = parent.add_subcommand("sine", "Sine characterization test of the damper after an idle time (§5.2)");
  app->add_option("--amplitude-mm", o->amplitude_mm, "Displacement amplitude, mm")->capture_default_str();
  app->add_option("--freq-hz", o->freq_hz, "Frequency, Hz")->capture_default_str();
  app->add_option("--current-a", o->current_a, "Constant coil current, A")->capture_default_str();
  app->add_option("--idle-years", o->idle_years, "Idle time before the test, years")->capture_default_str();
  app->add_option("--duration-s", o->duration_s, "Test length, s")->capture_default_str();
  app->add_option("--step-s", o->step_s, "Simulation step, s")->capture_default_str();
  app->add_flag("--thesis-cases", o->thesis_cases, "Run the three cases of Table 5.1 against Table 5.2");
  app->add_flag("--calibrate", o->calibrate, "Refit the mixing area of Eq. 5.9 to the Table 5.2 rise times");
  app->add_option("--out", o->out_dir, "Folder for summary.json, sine.csv and plots");
  app->footer(kSineHelp);
  return {app, [o] {
            require_positive("--amplitude-mm", o->amplitude_mm, "an amplitude");
            require_positive("--freq-hz", o->freq_hz, "a frequency");
            require_finite_at_least("--current-a", o->current_a, -30.0);
            if (o->current_a > 30.0) throw io::UsageError("--current-a: expected at most the drive's 30 A peak");
            require_finite_at_least("--idle-years", o->idle_years, 0.0);
            require_positive("--duration-s", o->duration_s, "a duration");
            if (o->duration_s > 1.0e5) throw io::UsageError("--duration-s: expected at most 100000 s");
            require_finite_at_least("--step-s", o->step_s, 1e-6);
            if (o->step_s > 0.1 / o->freq_hz) throw io::UsageError("--step-s: expected at most a tenth of the period");
            if (!o->out_dir.empty()) report::prepare_output_dir(o->out_dir);
            if (o->calibrate) run_calibration();
            if (o->thesis_cases) run_thesis_cases(*o);
            if (!o->calibrate && !o->thesis_cases) run_single(*o);
          }};
}

}  // namespace mrd::cli
