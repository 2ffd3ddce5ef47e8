#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "host_sim/cli/command.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/discrepancy/baseline_file.hpp"
#include "host_sim/discrepancy/discrepancy_report.hpp"
#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/plausibility.hpp"
#include "host_sim/discrepancy/workflow.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::cli {
namespace discrepancy_command {
namespace {

constexpr CommandHelp kDiscrepancyHelp{
    "discrepancy", "Name the physical effect behind a model-measurement gap",
    R"(Model-discrepancy workflow. Simulates a baseline damper model over the measured input (the
thesis's chapter-4 model: Bingham + transition, Eq. 4.1-4.4, Table 4.1, coil current by Eq. 4.5;
or a model calibrated to your damper by 'mrd calibrate', passed with --baseline), checks that the
record lies inside what the baseline describes, localizes where the force gap concentrates, then
tests named effects added to the model:
  idle_settling        participant ratio from a fitted SQ (Eq. 5.6-5.12)     sq [0-1]
  backlash             free play in the mounting (5.2 Case 3)                 free_play_m [0-0.01],
                       with a compliant stop over a share of it               contact_share [0-1]
  gas_spring           accumulator stiffness (3.1)                            stiffness_n_m [0-5e6]*
  thermal_fade         yield/viscosity falling with dissipated energy         yield_coeff_per_k, viscous_coeff_per_k
  time_delay           transport delay of the measured force                  delay_s [0-0.1]
  coil_lag             coil time constants of Eq. 4.5 scaled                  tau_scale [1-10]
                       ([0.005-10] when the baseline's coil was assumed: not identified)
  force_offset         load-cell zero offset                                  offset_n [-3e4-3e4]*
  direction_asymmetry  force x(1+a) in extension, x(1-a) in compression        asymmetry [-0.5-0.5]
  preyield_hysteresis  yield force building over x_y after reversals           yield_disp_m [0-0.01]
  (* bounds for the 200 kN damper; they scale with the baseline's force)
Each is fitted (Ceres, bounded least squares) on 70 % of the record, scored by delta BIC with the
effective sample count of the residual, checked for physical plausibility, and must also shrink
the gap on the 30 % held out (of forty equal blocks, the 3rd, 6th and 9th of every ten); the best
one is added; repeated
until no candidate earns its parameters, then each effect is checked again without it.

Verdict: baseline_mismatch (force scale, velocity or current far outside the baseline: nothing is
fitted; a force scale that agrees is said to be a record outside the range described), none (no
effect needed, residual without structure), explained (the effects take at
least half of the discrepancy found on the held-out part), unexplained (otherwise: where the
residual concentrates, what it looks like, which candidates were rejected and why).

Input (--measured): CSV with a header of named columns with units, at least
time_s, displacement_m, current_cmd_A, force_N (units converted: _ms, _mm, _cm, _in, _mA, _kN,
_kip, _lbf; velocity_m_s optional, derived from the displacement when absent; current_A is
taken as the command when there is no current_cmd column, and beside one it is the measured coil
current: the model's field then lags it by Eq. 4.5's slow branch alone, the fast branch (drive
and coil) being what was measured; other columns ending in a unit are kept), uniform or
non-uniform time. Or a MATLAB .mat file with vectors named like the columns.
Force sign of Eq. 4.1 (positive when the damper resists positive velocity).
A record whose values are probably in another unit (a displacement half range above 1 m, a
velocity above 10 m/s, a current above 20 A) is warned about (stderr and summary.json).
--baseline: a damper.toml whose every number lies in its physical range (the error names the
file, line, field and the range).

Fields of DIR/summary.json:
  verdict            none | explained | unexplained | baseline_mismatch
  velocity, coil_current   measured, or derived (velocity) / commanded (coil current)
  findings           sentences behind the verdict (numbers, where, what it looks like, rejections)
  warnings           values of the record probably in another unit (see above)
  baseline           name, expected_gap, expected_gap_basis, mismatch, mismatch_reasons,
                     force_ratio (least-squares measured/baseline) with min_force_ratio and
                     max_force_ratio, record ranges,
                     outside_coverage (an amplitude or frequency beyond those calibrated on, or a
                     current that changes where the baseline's coil was not identified)
  effects            the explanation, in the order added ([] unless explained)
  gap_before         normalized RMS force error of the baseline, sqrt(sum(F_meas-F)^2/sum F_meas^2),
                     on the samples the fits saw (70 %), full rate
  gap_after          the same for the updated model (fractions, not %)
  gap_validation_before, gap_validation_after   the same on the 30 % held out
  gap_reduction      1 - gap_after/gap_before
  parameters         fitted parameters of the named effects (SI units in the key names)
  rejected, rejected_parameters   effects fitted but not accepted as the explanation
  residual_before, residual_after   structured_share and per signature (offset, drift, stiffness,
                     lag, force_scale, asymmetry, low_velocity_loop, transition_shape,
                     current_law, inertia) the share of the held-out residual power it removes
  candidates         round 1: every effect with score (delta BIC), rss_reduction,
                     held_out_reduction, gap, parameters, flags (parameters at a bound),
                     plausible, verdict
  rounds             every round: model so far, candidates (round 2 also alternative pairs of
                     round-1 effects), chosen ("none" ends the search), model_after
  dropped            effects removed again by the backward check
  regions            regimes (velocity_reversal, near_zero_velocity, current_low/mid/high,
                     current_transient, early, late, displacement_extremes, ...) with
                     fraction_of_time, share_of_gap_before/after, concentration_before,
                     rms_before_n, rms_after_n, magnitude_bias_before_n, concentrated
  time_windows       the record in ten windows: rms_before_n, rms_after_n
  settings           thresholds and fit sampling used
Files: fit.csv (time series of input, coil current, measured/baseline/updated force, residuals),
force_time.png, residual.png, loops.png (force-displacement and force-velocity), report.md.)"};

struct DiscrepancyCliOptions {
  std::string measured;
  std::string out_dir;
  std::string effects;
  std::string baseline;
  std::size_t max_effects = 3;
  double min_delta_bic = 10.0;
  double min_improvement = 0.05;
  unsigned threads = 0;
  bool no_plots = false;
};

/// The workflow's options; throws io::UsageError for a bad option.
discrepancy::DiscrepancyOptions discrepancy_options(const DiscrepancyCliOptions& o) {
  require_finite_at_least("--min-delta-bic", o.min_delta_bic, 0.0);
  require_finite_at_least("--min-improvement", o.min_improvement, 0.0);
  if (o.min_improvement >= 1.0) throw io::UsageError("--min-improvement: expected a fraction below 1");
  discrepancy::DiscrepancyOptions opt;
  if (!o.effects.empty()) {
    opt.catalogue = discrepancy::parse_effect_list(o.effects, "--effects");
    if (opt.catalogue.empty()) throw io::UsageError("--effects: expected at least one effect");
  }
  opt.max_effects = o.max_effects;
  opt.min_delta_bic = o.min_delta_bic;
  opt.min_rss_reduction = o.min_improvement;
  opt.threads = o.threads;
  if (!o.baseline.empty()) opt.baseline = discrepancy::read_baseline_file(o.baseline).baseline;
  return opt;
}

void print_summary(const discrepancy::MeasuredData& data, const discrepancy::DiscrepancyResult& r) {
  std::printf("%s: %zu samples, %.3f s, velocity %s, coil current %s\n", data.source.c_str(), data.size(),
              data.duration_s(), r.velocity_derived ? "derived" : "measured",
              data.current_a.empty() ? "from the command" : "measured");
  for (std::size_t i = 0; i < r.rounds.size(); ++i) {
    const auto& rd = r.rounds[i];
    std::printf("round %zu (model: %s, gap %.2f %%):\n", i + 1, discrepancy::EffectSet{rd.model}.label().c_str(),
                100.0 * rd.gap);
    for (const auto& c : rd.candidates) {
      const std::string name = c.alternative ? discrepancy::EffectSet{c.model}.label()
                                             : std::string(discrepancy::effect_name(c.effect));
      std::printf("  %-14s dBIC %10.1f  removes %6.2f %%  %s\n", name.c_str(), c.delta_bic, 100.0 * c.rss_reduction,
                  c.verdict.c_str());
    }
  }
  std::printf("verdict: %s\n", discrepancy::verdict_name(r.verdict));
  for (const auto& f : r.findings) std::printf("  %s\n", f.c_str());
  std::printf("effects: %s\n", discrepancy::EffectSet{r.effects}.label().c_str());
  std::printf("gap: %.2f %% before, %.2f %% after; held out: %.2f %% before, %.2f %% after\n", 100.0 * r.gap_before,
              100.0 * r.gap_after, 100.0 * r.gap_validation_before, 100.0 * r.gap_validation_after);
}

void add_options(CLI::App& app, DiscrepancyCliOptions& o) {
  app.add_option("--measured", o.measured, "Measured record: CSV or .mat (see below)")->required();
  add_out_option(app, o.out_dir, "Folder for summary.json, fit.csv, plots and report.md");
  app.add_option("--baseline", o.baseline, "damper.toml from `mrd calibrate` (default: the thesis damper)");
  app.add_option("--effects", o.effects, "Catalogue to test, comma-separated (default: all)");
  app.add_option("--max-effects", o.max_effects, "Most effects to add")->capture_default_str();
  app.add_option("--min-delta-bic", o.min_delta_bic, "Smallest delta BIC that earns an effect")->capture_default_str();
  app.add_option("--min-improvement", o.min_improvement,
                  "Smallest fraction of the residual power an effect must remove")
      ->capture_default_str();
  add_threads_option(app, o.threads, "Threads for the candidate fits (0: all cores)");
  app.add_flag("--no-plots", o.no_plots, "Skip the PNG plots");
}

void execute(const DiscrepancyCliOptions& o) {
  const discrepancy::DiscrepancyOptions opt = discrepancy_options(o);
  const discrepancy::MeasuredData data = discrepancy::read_measured(o.measured);
  const std::vector<std::string> warnings =
      discrepancy::plausibility_warnings(std::span(&data, 1), opt.smoothing_half_window_s);
  print_warnings("discrepancy", warnings);
  compute_print_write(
      "discrepancy", o.out_dir,
      [&] {
        discrepancy::DiscrepancyResult r = discrepancy::run_discrepancy(data, opt);
        r.warnings = warnings;
        return r;
      },
      [&](const discrepancy::DiscrepancyResult& r) { print_summary(data, r); },
      [&](const std::filesystem::path& dir, const discrepancy::DiscrepancyResult& r) {
        return discrepancy::write_discrepancy_outputs(dir, data, r, opt, !o.no_plots);
      });
}

}  // namespace
}  // namespace discrepancy_command

Command add_discrepancy_command(CLI::App& parent) {
  using namespace discrepancy_command;
  return make_command(parent, kDiscrepancyHelp, add_options, execute);
}

}  // namespace mrd::cli
