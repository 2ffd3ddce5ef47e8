#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "host_sim/cli/command.hpp"
#include "host_sim/cli/damper_option.hpp"
#include "host_sim/cli/fluid_option.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/io/usage_error.hpp"
#include "mrd/units.hpp"
#include "host_sim/run/mixing_calibration.hpp"
#include "host_sim/run/sine_cases.hpp"
#include "host_sim/run/sine_outputs.hpp"
#include "host_sim/run/sine_rig.hpp"

namespace mrd::cli {
namespace sine_command {
namespace {

constexpr CommandHelp kSineHelp{
    "sine", "Sine characterization test of the damper after an idle time (§5.2)",
    R"(Drives the damper model (Bingham + transition, Eq. 4.1-4.4; idle-time participant ratio,
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
times of Table 5.2 and prints it.
--damper FILE tests another damper (README "Your damper and fluid"; default the thesis damper,
dampers/thesis-200kn.toml, whose outputs are the same bytes with or without the file): its force
law, current laws, coil and participant ratio, its [geometry] for the settling time (with the
thesis's model fluid), and its [rating] for the warnings. --thesis-cases and --calibrate are the
thesis damper's (Table 5.2 was measured on it) and refuse --damper.)"};

struct SineOptions {
  double amplitude_mm = 25.4;
  double freq_hz = 0.5;
  double current_a = 2.5;
  double idle_years = 0.0;
  double duration_s = 60.0;
  double step_s = 1.0e-3;
  bool thesis_cases = false;
  bool calibrate = false;
  std::string damper;
  std::string out_dir;
};

/// The single test the options ask for; throws io::UsageError for a bad option.
run::SineRigSpec sine_spec(const SineOptions& o) {
  require_positive("--amplitude-mm", o.amplitude_mm, "an amplitude");
  require_at_most("--amplitude-mm", o.amplitude_mm, 292.1, "the actuator's 292.1 mm half-stroke (Table 3.1)");
  require_positive("--freq-hz", o.freq_hz, "a frequency");
  require_at_most("--freq-hz", o.freq_hz, 100.0, "100 Hz");
  require_finite_at_least("--current-a", o.current_a, -30.0);
  require_at_most("--current-a", o.current_a, 30.0, "the drive's 30 A peak");
  check_idle_years(o.idle_years);
  require_positive("--duration-s", o.duration_s, "a duration");
  require_at_most("--duration-s", o.duration_s, kMaxDuration_s, "100000 s");
  require_step_s(o.step_s, 0.1 / o.freq_hz, "a tenth of the period");
  return {units::mm_to_m(o.amplitude_mm), o.freq_hz, o.current_a, units::years_to_s(o.idle_years), o.duration_s, o.step_s};
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

void run_thesis_cases(const std::optional<std::filesystem::path>& out) {
  const std::vector<run::ThesisSineResult> results = run::run_thesis_sine_cases();
  std::printf("Table 5.1 sine tests: model against Table 5.2 (a)\n\n%s", run::thesis_cases_markdown(results).c_str());
  if (!out) return;
  run::write_thesis_cases_outputs(*out, results);
  const auto shown = shown_path(*out);
  commit_out_dir();
  std::printf("\nwrote %s/thesis_cases.md and summary.json\n", shown.c_str());
}

void print_single(const run::SineRun& r) {
  const run::SineMetrics& m = r.metrics;
  std::printf("sine %.4g mm, %.4g Hz, %.4g A, idle %.4g years (SQ %.3f), %.4g s\n", r.amplitude_mm,
              r.spec.frequency_hz, r.spec.current_a, r.idle_years, m.sq, r.spec.duration_s);
  std::printf("  fully mixed force   %9.2f kN\n  initial force       %9.2f kN (%.1f %% of fully mixed)\n",
              m.fully_mixed_force_n / 1e3, m.initial_force_n / 1e3, 100.0 * m.initial_force_n / m.fully_mixed_force_n);
  std::printf("  max force           %9.2f kN (%.1f %% of fully mixed)\n", m.max_force_n / 1e3,
              100.0 * m.max_force_n / m.fully_mixed_force_n);
  std::printf("  rise time to 90 %%   %9.3f s\n  rise time to 95 %%   %9.3f s\n", m.rise_time_90_s, m.rise_time_95_s);
}

void run_single(const SineOptions& o, const run::SineRigSpec& spec, const DamperAndFluid& d,
                const std::optional<std::filesystem::path>& out) {
  run::SineRun r{o.amplitude_mm, o.idle_years, spec, {}, {}, d.params.rating};
  r.metrics = run::run_sine_rig(spec, d.params, d.settling, out ? &r.record : nullptr);
  print_single(r);
  std::fflush(stdout);
  print_warnings("sine", run::sine_warnings(r));
  if (!out) return;
  const auto problems = run::write_sine_outputs(*out, r);
  const auto shown = shown_path(*out);
  commit_out_dir();
  warn_plots_not_written("sine", problems);
  std::printf("wrote %s/summary.json, sine.csv and plots\n", shown.c_str());
}

void add_options(CLI::App& app, SineOptions& o) {
  app.add_option("--amplitude-mm", o.amplitude_mm, "Displacement amplitude, mm")->capture_default_str();
  app.add_option("--freq-hz", o.freq_hz, "Frequency, Hz")->capture_default_str();
  app.add_option("--current-a", o.current_a, "Constant coil current, A")->capture_default_str();
  add_idle_years_option(app, o.idle_years, "Idle time before the test, years");
  app.add_option("--duration-s", o.duration_s, "Test length, s")->capture_default_str();
  add_step_s_option(app, o.step_s, "Simulation step, s");
  app.add_flag("--thesis-cases", o.thesis_cases, "Run the three cases of Table 5.1 against Table 5.2");
  app.add_flag("--calibrate", o.calibrate, "Refit the mixing area of Eq. 5.9 to the Table 5.2 rise times");
  add_damper_option(app, o.damper);
  add_out_option(app, o.out_dir, "Folder for summary.json, sine.csv and plots");
}

void execute(const SineOptions& o) {
  const run::SineRigSpec spec = sine_spec(o);
  if (!o.damper.empty() && (o.thesis_cases || o.calibrate))
    throw io::UsageError(std::string("--damper: ") + (o.thesis_cases ? "--thesis-cases" : "--calibrate") +
                         " is the thesis damper's (Table 5.2 was measured on it); leave out one of the two");
  const DamperAndFluid d = load_damper_and_fluid("sine", o.damper, "");
  const auto out = open_optional_out_dir(o.out_dir);
  if (o.calibrate) run_calibration();
  if (o.thesis_cases) run_thesis_cases(out);
  if (!o.calibrate && !o.thesis_cases) run_single(o, spec, d, out);
}

}  // namespace
}  // namespace sine_command

Command add_sine_command(CLI::App& parent) {
  using namespace sine_command;
  return make_command(parent, kSineHelp, add_options, execute);
}

}  // namespace mrd::cli
