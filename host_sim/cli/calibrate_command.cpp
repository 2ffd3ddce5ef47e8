#include <sys/stat.h>

#include <cstdio>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "host_sim/cli/command.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/discrepancy/calibrate.hpp"
#include "host_sim/discrepancy/calibrate_report.hpp"
#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/plausibility.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::cli {
namespace calibrate_command {
namespace {

constexpr CommandHelp kCalibrateHelp{
    "calibrate", "Fit a baseline damper model to characterization records",
    R"(Fits the chapter-4 damper model to measured records of the user's damper, jointly over all
records (each record's residual divided by its RMS force), and writes DIR/damper.toml for
`mrd discrepancy --baseline`. Laws (all with the current laws of Eq. 4.2-4.3,
value(I) = limit + (at_zero - limit) exp(-rate_per_a |I|)):
  bingham       F = TF(v) (Y sgn v + C v), Eq. 4.1-4.4             v_tf_m_s
  bingham_tanh  F = Y tanh(v / v_tf) + C v (a smoother transition)  v_tf_m_s
  bouc_wen      F = Y z + C v + k0 x, normalized Spencer et al. (1997)  yield_disp_m, stiffness_n_m
and, with its own current laws ([spencer]: alpha quadratic, c0 and c1 affine, gamma exponential
in |I|; A = 300, n = 2, beta = gamma, x0 = 0 held):
  spencer       Spencer et al. (1997)'s modified Bouc-Wen model, F = c1 y' + k1 (x - x0),
                y' = (alpha z + c0 x' + k0 (x - y)) / (c0 + c1), z' of Bouc-Wen on x' - y'
--law auto fits them all (--law bingham both Bingham transitions; --transition linear or
tanh only one); spencer takes no extra and auto chooses it only on --check records (not by the
cross-validation below: a fit through its ODE per motion left out); its fit weighs each record
alike (a record's squared residuals over its number of samples) and has no force-channel lag
(force_delay_s 0: c1 and z's pre-yield are the force's lag at reversals).
Each other form is then fitted again with each extra in turn, on top of those kept before:
  transition time (bingham only): TF's band widens to v_tf_m_s + transition_time_s |a|, so the
    force builds over a time after a reversal, not over a velocity      transition_time_s
  series compliance (bingham only): the law acts on the fluid's velocity v - F'/k_s, so the
    force turns over at a reversal as the fluid column is compressed, with a lag that grows
    with the force (F/v over k_s)                               series_compliance_m_per_n = 1/k_s
  lost motion: a share of the force builds only after the piston has moved m_per_n * Y(I)
    past a reversal (a plateau after each reversal, longer at higher current)   m_per_n, share
and then, with --check records or cross-validation only (bingham):
  current exponent: value(I) = limit + (at_zero - limit) exp(-rate_per_a |I|^q), q fitted per
    law (q > 1: a force that rises slowly at low current, an S-shaped law)   current_exponent
  viscous exponent: C v becomes C v_r (|v| / v_r)^m sgn v (Herschel-Bulkley; v_r the records'
    median peak velocity, held)                          viscous_exponent, viscous_ref_m_s
  stiffness: a spring k x beside the law (the accumulator's gas charge)     stiffness_n_m
An extra is kept when it lowers the BIC by 10 or more, its parameters are off their bounds and
it also lowers the RMS gap of the --check records (--no-transition-time, --no-series-compliance,
--no-lost-motion: not fitted). The form chosen: of the laws each with the extras it kept, the
lowest RMS gap on the --check records. So the check records' gaps are those of a validation set; --test records are
judged only after everything is chosen (an untouched test set). A note says when every
check record repeats the amplitude and frequency of a fitted one (within 1.25x): such a
check judges the current laws, not other motions.
Without --check, the --measured records' own motions judge (cross-validation): the records are
grouped by motion (half range and dominant frequency within 1.25x of a group's first record),
and each candidate is fitted again to the records of the other motions, from its fit to all,
with its gap taken on the motion left out, for each motion in turn; the RMS of those gaps
stands for the check records' above, and the chosen form keeps its fit to all the records
(summary.json cross_validation: the records left out together). It takes about as many fits again
as there are motions; beyond 5 motions they are dealt in order of stroke to 5 folds, each left
out in turn. With one motion, or --no-cross-validation, no extra is kept (each is fitted and
reported) and the form is the one of lowest BIC. From 3 motions on (or with --check) the
expected gap also covers each record's gap where it was left out (or the check records').
--floors fits the chosen form again to each record alone (its current laws constants at the
record's current), from the calibrated baseline: that record's floor, the gap no one model of
the form gets below on it. A gap above its floor is what the form loses by being one model for
all the records (other strokes, frequencies, currents, test sessions); the floor is what it
cannot describe in the record itself.
With three or more currents the current laws are fitted whole; with two,
rate_per_a is held at the thesis value; with one, the laws are constants.
The coil time constants (Eq. 4.5) leave no trace while the current holds: with constant-current
records they keep the thesis values, marked identified = false (a later record whose current
changes is then named in `mrd discrepancy`'s findings). When a --measured record's current
changes (a step above 2 % of its largest current), tau_slow_s and tau_fast_s are fitted with
the rest (weights 1/2 each; equal, one first-order lag) and marked identified = true; a record
with the coil current measured (current_A beside current_cmd_A) puts the laws on that current,
and only tau_slow_s, the field's lag behind it, is fitted from it. The participant ratio is not
identifiable from such records: thesis values.
Standard errors: sigma^2 (J^T J)^-1 at the optimum, inflated by n/n_eff (effective sample count
of the residual).

Input (--measured, --check, --test): CSV or .mat records as for `mrd discrepancy`. A record takes
one role, once: the same file (by identity: a link or another path to it is the same file) given
twice is refused. Records whose values are probably in another unit (a displacement half range
above 1 m, a velocity above 10 m/s, a current above 20 A) or of another damper (peak forces more
than 10 times beyond what their currents and velocities allow one damper) are warned about.
Files: damper.toml; summary.json (chosen_law, choice_reason, records, currents_a, notes, warnings, fits:
law, parameters {value, sigma, fitted, at_bound}, record_gaps, held_out_gaps (on the --check
records, or each record of a motion left out and fitted to the others; [] where not judged),
expected_gap (the largest of both) with expected_gap_basis, samples, rss_normalized, n_eff, bic; held_out: gap per law of the --check records; test: the same for
the --test records, and test_gap_rms: the chosen form's RMS gap over them; floors: measured,
check and test lists with --floors, else null; validity);
report.md; loops_<n>.png per --measured record (force-velocity and force-displacement; the
plain laws and the chosen form).
Gap: sqrt(sum (F_model - F_meas)^2 / sum F_meas^2), a fraction.)"};

struct CalibrateCliOptions {
  std::vector<std::string> measured;
  std::vector<std::string> check;
  std::vector<std::string> test;
  std::string out_dir;
  std::string law = "auto";
  bool no_plots = false;
  bool no_lost_motion = false;
  bool no_transition_time = false;
  bool no_current_exponent = false;
  bool no_viscous_exponent = false;
  bool no_stiffness = false;
  bool no_series_compliance = false;
  bool floors = false;
  bool no_cross_validation = false;
  unsigned threads = 0;
  std::string transition = "auto";
  std::string lost_motion_form = "both";
};

const std::map<std::string, discrepancy::LostMotionForm> kLostMotionForms{
    {"both", discrepancy::LostMotionForm::both},
    {"share", discrepancy::LostMotionForm::share},
    {"viscous", discrepancy::LostMotionForm::viscous}};

void add_options(CLI::App& app, CalibrateCliOptions& o) {
  app.add_option("--measured", o.measured, "Characterization records (CSV or .mat)")->required();
  add_out_option(app, o.out_dir, "Folder for damper.toml, summary.json, report.md and plots");
  app.add_option("--law", o.law, "bingham, bouc_wen, spencer or auto (all, chosen as above)")->capture_default_str();
  app.add_option("--transition", o.transition, "Bingham transition: linear (Eq. 4.4), tanh or auto (both)")
      ->capture_default_str();
  app.add_option("--check", o.check, "Records not fitted: the calibrated models' gap on each is reported");
  app.add_option("--test", o.test,
                 "Records judged after the calibration only (no extra and no form is chosen on them)");
  app.add_flag("--no-plots", o.no_plots, "Skip the PNG plots");
  app.add_flag("--no-lost-motion", o.no_lost_motion, "Do not try the lost motion at reversals");
  app.add_option("--lost-motion-form", o.lost_motion_form,
                 "The force inside the lost motion's play: share (of the law's force), viscous (over a band of "
                 "velocity) or both")
      ->check(CLI::IsMember(kLostMotionForms))
      ->capture_default_str();
  app.add_flag("--no-transition-time", o.no_transition_time, "Do not try the transition time (bingham)");
  app.add_flag("--no-current-exponent", o.no_current_exponent, "Do not try the current laws' exponent (bingham)");
  app.add_flag("--no-viscous-exponent", o.no_viscous_exponent, "Do not try the viscous force's exponent (bingham)");
  app.add_flag("--no-stiffness", o.no_stiffness, "Do not try a spring beside the law (bingham)");
  app.add_flag("--no-series-compliance", o.no_series_compliance,
               "Do not try a compliance in series with the law (bingham)");
  app.add_flag("--no-cross-validation", o.no_cross_validation,
               "Without --check, keep no extra and choose the form by BIC instead of leaving out each motion in turn");
  app.add_flag("--floors", o.floors,
               "Also fit the chosen form to each record alone: its floor on the record, beside the gap (one fit per "
               "record)");
  add_threads_option(app, o.threads,
                     "Threads for the fits that do not depend on each other (the laws, each motion left out, each "
                     "record's floor; 0: all cores); the result is the same whatever the count");
}

discrepancy::CalibrateOptions calibrate_options(const CalibrateCliOptions& o) {
  discrepancy::CalibrateOptions opt;
  opt.lost_motion = !o.no_lost_motion;
  opt.lost_motion_form = kLostMotionForms.at(o.lost_motion_form);
  opt.transition_time = !o.no_transition_time;
  opt.current_exponent = !o.no_current_exponent;
  opt.viscous_exponent = !o.no_viscous_exponent;
  opt.stiffness = !o.no_stiffness;
  opt.series_compliance = !o.no_series_compliance;
  opt.cross_validate = !o.no_cross_validation;
  opt.threads = o.threads;
  if (o.transition == "linear") {
    opt.transition = discrepancy::TransitionShape::linear;
  } else if (o.transition == "tanh") {
    opt.transition = discrepancy::TransitionShape::tanh;
  } else if (o.transition != "auto") {
    throw io::UsageError("--transition: expected linear, tanh or auto, got '" + o.transition + "'");
  }
  if (o.law == "bingham") {
    opt.law = discrepancy::BaseLaw::bingham;
  } else if (o.law == "bouc_wen") {
    opt.law = discrepancy::BaseLaw::bouc_wen;
  } else if (o.law == "spencer") {
    opt.law = discrepancy::BaseLaw::spencer;
  } else if (o.law != "auto") {
    throw io::UsageError("--law: expected bingham, bouc_wen, spencer or auto, got '" + o.law + "'");
  }
  return opt;
}

/// Refuses one file given in two roles, or twice in one: `--measured`,
/// `--check` and `--test` records are the fitted, choosing and judged sets,
/// and a record in two of them would judge a choice by what made it. Files
/// are compared by identity (device and inode), so that `a.csv`, `./a.csv`,
/// `d/../a.csv` and a link to it are one; a file that cannot be examined is
/// left to the reader, which names it.
void check_roles_exclusive(const CalibrateCliOptions& o) {
  struct Given {
    const char* option;
    const std::string* path;
  };
  std::vector<Given> given;
  for (const auto& [option, paths] : {std::pair{"--measured", &o.measured}, std::pair{"--check", &o.check},
                                      std::pair{"--test", &o.test}})
    for (const std::string& p : *paths) given.push_back({option, &p});
  std::map<std::pair<dev_t, ino_t>, const Given*> seen;
  for (const Given& g : given) {
    struct stat st {};
    if (::stat(g.path->c_str(), &st) != 0) continue;
    const auto [at, fresh] = seen.emplace(std::pair{st.st_dev, st.st_ino}, &g);
    if (fresh) continue;
    const Given& first = *at->second;
    throw io::UsageError(std::string(first.option) + " '" + *first.path + "' and " + g.option + " '" + *g.path +
                         "' are one file: a record takes one role, once (--measured fits it, --check chooses with "
                         "it, --test judges it)");
  }
}

struct Outcome {
  discrepancy::CalibrationResult result;
  discrepancy::HeldOut held_out;
  discrepancy::HeldOut test;
  discrepancy::RecordFloors floors;
};

void print_summary(const Outcome& out) {
  const auto& r = out.result;
  std::printf("%-32s", "record");
  for (const auto& f : r.fits) std::printf("  %10s", discrepancy::baseline_form_name(f.baseline).c_str());
  std::printf("   (gap)\n");
  for (std::size_t i = 0; i < r.sources.size(); ++i) {
    std::printf("%-32s", r.sources[i].c_str());
    for (const auto& f : r.fits) std::printf("  %8.2f %%", 100.0 * f.record_gaps[i]);
    std::printf("\n");
  }
  for (const auto& [set, tag] : {std::pair{&out.held_out, " (check)"}, std::pair{&out.test, " (test)"}}) {
    for (std::size_t i = 0; i < set->sources.size(); ++i) {
      std::printf("%-32s", (set->sources[i] + tag).c_str());
      for (std::size_t l = 0; l < r.fits.size(); ++l) std::printf("  %8.2f %%", 100.0 * set->gaps[l][i]);
      std::printf("\n");
    }
  }
  if (!out.floors.empty()) {
    // The chosen form's gap against its floor, record by record.
    const auto rows = [](const std::vector<std::string>& sources, const char* tag, std::span<const double> gaps,
                         std::span<const double> floors) {
      for (std::size_t i = 0; i < sources.size(); ++i)
        std::printf("floor: %-40s gap %6.2f %%  floor %6.2f %%\n", (sources[i] + tag).c_str(), 100.0 * gaps[i],
                    100.0 * floors[i]);
    };
    rows(r.sources, "", r.best().record_gaps, out.floors.measured);
    rows(out.held_out.sources, " (check)", out.held_out.gaps[r.chosen], out.floors.check);
    rows(out.test.sources, " (test)", out.test.gaps[r.chosen], out.floors.test);
  }
  for (const auto& n : r.notes) std::printf("note: %s\n", n.c_str());
  std::printf("chosen: %s\n", r.choice_reason.c_str());
  if (!out.test.sources.empty())
    std::printf("test records (seen by no choice): RMS gap of the chosen form %.2f %%\n",
                100.0 * discrepancy::rms_over_records(out.test.gaps[r.chosen]));
}

/// The plausibility warnings about every record of the calibration, in the
/// order given (plausibility.hpp).
std::vector<std::string> record_warnings(std::span<const discrepancy::MeasuredData> records,
                                         std::span<const discrepancy::MeasuredData> checks,
                                         std::span<const discrepancy::MeasuredData> tests,
                                         const discrepancy::CalibrateOptions& opt) {
  std::vector<discrepancy::RecordReach> reach;
  for (const auto set : {records, checks, tests})
    for (const discrepancy::MeasuredData& d : set)
      reach.push_back(discrepancy::record_reach(d, opt.smoothing_half_window_s));
  return discrepancy::plausibility_warnings(reach);
}

void execute(const CalibrateCliOptions& o) {
  const discrepancy::CalibrateOptions opt = calibrate_options(o);
  check_roles_exclusive(o);
  std::vector<discrepancy::MeasuredData> records, checks, tests;
  for (const auto& p : o.measured) records.push_back(discrepancy::read_measured(p));
  for (const auto& p : o.check) checks.push_back(discrepancy::read_measured(p));
  for (const auto& p : o.test) tests.push_back(discrepancy::read_measured(p));
  const std::vector<std::string> warnings = record_warnings(records, checks, tests, opt);
  print_warnings("calibrate", warnings);
  compute_print_write(
      "calibrate", o.out_dir,
      [&] {
        Outcome out{discrepancy::calibrate(records, opt, checks), {}, {}, {}};
        out.held_out = discrepancy::held_out_gaps(out.result, checks, opt);
        out.test = discrepancy::held_out_gaps(out.result, tests, opt);
        if (o.floors) out.floors = discrepancy::record_floors(out.result, records, checks, tests, opt);
        return out;
      },
      print_summary,
      [&](const std::filesystem::path& dir, const Outcome& out) {
        return discrepancy::write_calibration_outputs(dir, records, out.result, out.held_out, opt, !o.no_plots,
                                                        out.test, out.floors, warnings);
      });
}

}  // namespace
}  // namespace calibrate_command

Command add_calibrate_command(CLI::App& parent) {
  using namespace calibrate_command;
  return make_command(parent, kCalibrateHelp, add_options, execute);
}

}  // namespace mrd::cli
