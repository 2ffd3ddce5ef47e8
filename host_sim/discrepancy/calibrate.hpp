#pragma once
/// Calibrating a baseline (baseline.hpp) to the user's damper from
/// characterization records: a joint bounded least-squares fit of the
/// Bingham model (Eq. 4.1–4.4) and of the normalized Bouc–Wen model with the
/// exponential current laws of Eq. 4.2–4.3, and of Spencer et al. (1997)'s
/// model with its own current laws (α through its values at the records'
/// lowest, middle and highest current, c_0 and c_1 through the lowest and
/// highest, γ exponential, k_1, k_0; A = 300, n = 2, β = γ and x_0 = 0
/// held: A's scale is z's, β = γ the paper's and the laboratory's choice),
/// standard errors from the Jacobian, the choice between them, and the
/// validity range the records cover.
///
/// With check records, the chosen Bingham form is then fitted again with its
/// shape terms in turn (baseline.hpp: the current laws' exponent q, the
/// viscous exponent m, the spring k), each kept as the other extras are.
///
/// Joint fit: every record's residual (F_model − F_meas) is divided by that
/// record's RMS force, so that records weigh alike whatever their force
/// level; each record is thinned to about `samples_per_record` samples (as
/// make_fit_data); the spencer law's residuals are also weighted so that each
/// record counts alike whatever its number of samples, and it fits no force
/// channel lag (calibrate.cpp, fit_law). Positive parameters are fitted as logarithms (Ceres LM,
/// forward differences), from several starts built from a linear regression
/// F ≈ Y sgn v + C v (+ k x) per current.
///
/// What constant-current records identify: the current laws from the spread
/// of the currents (three or more currents: at_zero, limit and rate_per_a;
/// two: rate_per_a fixed at the thesis value; one: a constant value). The
/// coil time constants (Eq. 4.5) leave no trace in the force while the
/// current holds: they keep the thesis values (Baseline::coil_identified
/// false) unless some record's current command changes (command_changes,
/// baseline_check.hpp), and then they are fitted with the rest: both, or
/// only the slow one where the changing records measured the coil current
/// (the fast branch is then the measurement, damper_model.hpp). The
/// participant ratio (Eq. 5.6–5.11) is not identifiable from such records
/// and keeps the thesis values.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "host_sim/discrepancy/baseline.hpp"
#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/motion_timescale.hpp"

namespace mrd::discrepancy {

/// One parameter of a calibrated baseline.
struct ParamEstimate {
  std::string name;    ///< e.g. "yield_n.at_zero", "stiffness_n_m"
  double value = 0.0;  ///< physical, SI
  double sigma = 0.0;  ///< standard error, SI; 0 when not fitted
  bool fitted = false;
  bool at_bound = false;  ///< the fit ended on its search bound
};

/// Standard errors of a baseline's parameters, SI (0 = not fitted).
struct BaselineSigmas {
  CurrentLaw yield_n{0.0, 0.0, 0.0, 0.0};
  CurrentLaw viscous_ns_m{0.0, 0.0, 0.0, 0.0};
  double v_tf_m_s = 0.0;
  double yield_disp_m = 0.0;
  double stiffness_n_m = 0.0;
  double force_delay_s = 0.0;
  double lost_motion_m_per_n = 0.0;
  double lost_motion_share = 0.0;
  double lost_motion_band_m_s = 0.0;
  double transition_time_s = 0.0;
  double viscous_exponent = 0.0;
  double series_compliance_m_per_n = 0.0;
  double coil_tau_slow_s = 0.0;
  double coil_tau_fast_s = 0.0;
};

/// Which parameters of the current laws were fitted.
struct CurrentLawFitted {
  bool at_zero = true;
  bool limit = true;
  bool rate_per_a = true;
};

/// The fit of one law to all records.
struct LawFit {
  Baseline baseline;
  BaselineSigmas sigma;
  CurrentLawFitted yield_fitted, viscous_fitted;
  std::vector<ParamEstimate> params;  ///< every parameter of the law, fitted or held
  std::vector<double> record_gaps;    ///< normalized_rms_gap per record, full rate, over its moving_span
  /// The same on records this form was not fitted to, where the calibration
  /// judged it: each check record, or each record of a motion left out
  /// (the form fitted again to the other motions); empty where not judged.
  std::vector<double> held_out_gaps;
  std::vector<std::string> held_out_sources;  ///< the record of each held_out_gaps entry
  std::size_t samples = 0;            ///< residuals in the joint fit
  double rss = 0.0;                   ///< Σ of the normalized residuals squared (dimensionless)
  double n_eff = 0.0;                 ///< Σ over records of effective_sample_count(residual)
  double bic = 0.0;                   ///< with the n_eff common to the laws compared
  int iterations = 0;
  bool converged = false;
};

/// Which transitions of the Bingham law to fit (baseline.hpp).
enum class TransitionShape { both, linear, tanh };

/// Which forms of the force inside a lost motion's play to fit (baseline.hpp):
/// a share of the law's force, a force over a band of velocity, or both.
enum class LostMotionForm { both, share, viscous };

struct CalibrateOptions {
  /// Threads for the fits that do not depend on each other (the laws' plain
  /// fits, each motion left out) and, within a fit, for its Jacobian's
  /// columns (those left to it when fits run side by side); 0: all cores.
  /// The result is the same whatever the count.
  unsigned threads = 0;
  std::optional<BaseLaw> law;  ///< nullopt: fit every law (auto), choose as CalibrationResult says
  /// Whether auto fits the spencer law too (a fit of eleven parameters
  /// through a stiff ODE, minutes on a laboratory's fifteen records).
  bool auto_spencer = true;
  /// The Bingham law with Eq. 4.4's transition, with a tanh one, or both
  /// (each a law of its own in the BIC choice).
  TransitionShape transition = TransitionShape::both;
  /// Also fit the chosen law with a transition time (Bingham only,
  /// baseline.hpp), kept as the lost motion below.
  bool transition_time = true;
  /// Also fit the chosen law with a lost motion at reversals (baseline.hpp),
  /// kept when it lowers the BIC by at least kBicMargin and the gap on the
  /// check records (calibrate()).
  bool lost_motion = true;
  /// The lost motion's forms tried, each on the same fit (the one with the
  /// lower check gap kept when both are).
  LostMotionForm lost_motion_form = LostMotionForm::both;
  /// Also fit the chosen Bingham law with a spring k x beside it, then with
  /// a viscous exponent (baseline.hpp), each kept as the lost motion above.
  bool stiffness = true;
  bool viscous_exponent = true;
  /// Also fit the chosen Bingham law behind a compliance in series
  /// (baseline.hpp), after the transition time, kept as the lost motion.
  bool series_compliance = true;
  /// Also fit the chosen Bingham law's current laws with their exponents q
  /// (CurrentLaw, baseline.hpp), before the two above; three currents or more.
  bool current_exponent = true;
  /// Without check records, judge the extras and the form by leaving out
  /// one motion at a time (motion_groups): each candidate fitted again to
  /// the records of the other motions, from its fit to all of them, and its
  /// gap taken on the motion left out. Needs two motions or more; with one,
  /// or false, the extras are reported and not kept, as before.
  bool cross_validate = true;
  std::size_t samples_per_record = 4000;
  double smoothing_half_window_s = kDefaultSmoothingHalfWindow_s;
  std::string name = "calibrated";  ///< Baseline::name of the result
};

/// BIC improvement an extra (transition time, lost motion) needs to join the calibrated baseline (the
/// ΔBIC ≥ 10 "very strong" evidence of Kass & Raftery 1995, as for effects).
inline constexpr double kBicMargin = 10.0;

struct CalibrationResult {
  /// One per plain form fitted (bingham, bingham_tanh, bouc_wen), then,
  /// form by form, the form with each extra tried in turn: + transition time
  /// (Bingham), + lost motion, each on top of the extras kept before it. The
  /// chosen one: of the forms each with its kept extras, the lowest RMS gap
  /// on the check records; without check records (no extra kept), the plain
  /// form of lowest BIC, spencer excepted (auto chooses it only on check
  /// records: it has no extras, its own freedom is what they judge).
  std::vector<LawFit> fits;
  std::size_t chosen = 0;    ///< index into fits
  std::string choice_reason;
  std::vector<std::string> sources;            ///< record names
  std::vector<std::size_t> record_samples;     ///< samples per record in the fit
  std::vector<double> currents_a;              ///< distinct commanded currents found
  std::vector<std::string> notes;              ///< what was held and why
  /// Without check records, the motions that judged by leaving each out in
  /// turn (indices into the records; empty: not cross-validated).
  std::vector<std::vector<std::size_t>> cross_validation_groups;
  [[nodiscard]] const LawFit& best() const { return fits.at(chosen); }
};

/// Motions left out in turn (cross-validation) from which their gaps count
/// in the expected gap: with fewer, each fold is fitted to too little of what
/// the calibration fits (calibrate()).
inline constexpr std::size_t kExpectedGapMinMotions = 3;

/// Fits the baseline to `records` jointly. The chosen fit's baseline carries
/// the validity range of the records and expected_gap = its largest
/// per-record gap, on the records it was fitted to and on the check records
/// or, from kExpectedGapMinMotions motions on, each motion left out
/// (LawFit::held_out_gaps; Baseline::expected_gap_basis). Throws io::UsageError when there is no record.
///
/// `check` records (the same damper, not fitted) judge whether an extra
/// (transition time, lost motion) generalizes: it is kept only if it also
/// lowers the RMS over them of the per-record gaps. Without check records,
/// the records' motions judge in turn (CalibrateOptions::cross_validate):
/// the RMS gap of the records of each motion under the candidate fitted to
/// the others; with one motion an extra is fitted and reported but never kept.
[[nodiscard]] CalibrationResult calibrate(std::span<const MeasuredData> records, const CalibrateOptions& options = {},
                                          std::span<const MeasuredData> check = {});

/// The records grouped by motion: two records share a group when each's
/// half range and dominant frequency are within kCoverageFactor of the
/// group's first record's (baseline_check.hpp). Indices into `records`,
/// groups in order of their first record.
[[nodiscard]] std::vector<std::vector<std::size_t>> motion_groups(std::span<const MeasuredData> records,
                                                                  double smoothing_half_window_s =
                                                                      kDefaultSmoothingHalfWindow_s);

/// At most this many folds in cross-validation: each fold is a fit per
/// candidate form, so a campaign of many motions leaves out several at once.
inline constexpr std::size_t kMaxCrossValidationFolds = 5;

/// The records left out together in cross-validation: each motion
/// (motion_groups) its own fold up to kMaxCrossValidationFolds motions;
/// beyond, the motions in order of half range (then dominant frequency)
/// dealt to the folds in turn, so that each fold leaves out motions spread
/// over the strokes rather than one end of them.
/// Indices into `records`, ascending within a fold; the folds in order of
/// their first record.
[[nodiscard]] std::vector<std::vector<std::size_t>> cross_validation_folds(
    std::span<const MeasuredData> records, double smoothing_half_window_s = kDefaultSmoothingHalfWindow_s);

/// normalized_rms_gap of `baseline` on each record at full rate, over the
/// samples where the actuator moves (moving_span, damper_model.hpp).
[[nodiscard]] std::vector<double> baseline_gaps(const Baseline& baseline, std::span<const MeasuredData> records,
                                                double smoothing_half_window_s = kDefaultSmoothingHalfWindow_s);

/// The form of `form` (law, transition, extras) fitted to each record
/// alone, from `form` itself (a constant-current record: its current laws
/// constants at that current): normalized_rms_gap of that fit on each
/// record, as baseline_gaps.
/// It is the record's floor, the gap no one model of that form gets below on
/// it (up to the fit's local minimum, from a start whose gap is the
/// calibrated one's): a calibrated gap above its floor is what the form lost
/// by being one model for every record (other strokes, frequencies and
/// currents, or a difference between test sessions), the floor itself what
/// it cannot describe in that record. One fit per record.
[[nodiscard]] std::vector<double> record_floor_gaps(const Baseline& form, std::span<const MeasuredData> records,
                                                    const CalibrateOptions& options = {});

/// sqrt(mean of gaps²): the RMS over records of per-record gaps (0 for none).
[[nodiscard]] double rms_over_records(std::span<const double> gaps);

/// Currents (min/max of current_cmd), largest |v| (of model_input), largest
/// |F|, displacement half ranges and dominant frequencies covered by `records`.
[[nodiscard]] ValidityRange validity_range(std::span<const MeasuredData> records,
                                           double smoothing_half_window_s = kDefaultSmoothingHalfWindow_s);

}  // namespace mrd::discrepancy
