#include "host_sim/discrepancy/calibrate.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <thread>
#include <utility>

#include "host_sim/discrepancy/baseline_check.hpp"
#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/discrepancy/effects.hpp"
#include "host_sim/discrepancy/fit.hpp"
#include "host_sim/discrepancy/parallel.hpp"
#include "host_sim/discrepancy/physical_ranges.hpp"
#include "host_sim/discrepancy/solver_options.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::discrepancy {
namespace {

/// The parameters a calibration can fit.
enum Slot : std::size_t {
  kYa, kYb, kYc, kCa, kCb, kCc, kVtf, kXy, kK0, kDelay, kPlay, kShare, kTau, kBand, kCoilSlow, kCoilFast, kViscExp, kYq, kCq, kSeries,
  // The spencer law (physics/spencer_law.hpp): α at the records' lowest,
  // middle and highest current (Layout::node_a), c_0 and c_1 at the lowest
  // and highest, γ at 0 A and its rate, k_1, k_0.
  kSpA0, kSpA1, kSpA2, kSpC0a, kSpC0b, kSpC1a, kSpC1b, kSpGamma, kSpGammaRate, kSpK1, kSpK0, kSlots
};

constexpr std::array<const char*, kSlots> kSlotName{
    "yield_n.at_zero",      "yield_n.limit",        "yield_n.rate_per_a", "viscous_ns_m.at_zero", "viscous_ns_m.limit",
    "viscous_ns_m.rate_per_a", "v_tf_m_s",          "yield_disp_m",       "stiffness_n_m",
    "force_delay_s",        "lost_motion_m_per_n",  "lost_motion_share",  "transition_time_s",
    "lost_motion_band_m_s", "coil.tau_slow_s",      "coil.tau_fast_s",   "viscous_exponent",
    "yield_n.current_exponent", "viscous_ns_m.current_exponent", "series_compliance_m_per_n",
    "spencer.alpha_n_m(I_lo)", "spencer.alpha_n_m(I_mid)", "spencer.alpha_n_m(I_hi)", "spencer.c0_ns_m(I_lo)",
    "spencer.c0_ns_m(I_hi)", "spencer.c1_ns_m(I_lo)", "spencer.c1_ns_m(I_hi)", "spencer.gamma_per_m_pow_n",
    "spencer.gamma_rate_per_a", "spencer.k1_n_m", "spencer.k0_n_m"};

/// Search bounds, SI (the fit works on their logarithms).
/// The force-channel lag between 10 µs (none, in effect) and 100 ms; the
/// lost motion between 1 nm and 10 mm per kN, its share between 0.1 % and all;
/// the transition time between 1 µs (none: 10 µm/s at 10 m/s²) and 100 ms;
/// the band of the force inside the play between 10 µm/s and 10 m/s; the
/// coil's time constants between 0.1 ms (a current drive faster than any
/// sampling here) and 10 s (a field that never settles within a test).
/// Spencer: α between 1 N/m and 1e10 N/m, c_0 and c_1 between 1 mN·s/m and
/// 1e10 N·s/m (the laws' ranges less a decade), γ between 0.01 and 1e20
/// 1/m^n (z saturating between 120 m and 1 nm with A = 300, n = 2), its
/// rate as the exponential laws', k_1 as the Bouc–Wen k_0 and k_0 from
/// 0.1 mN/m (none, in effect: the laboratory's published 0.15 N/m).
constexpr std::array<double, kSlots> kLower{1e-3,  1e-3, 0.02, 1e-3, 1e-3, 0.02, 1e-5, 1e-7,
                                            1e-2,  1e-5, 1e-12, 1e-3, 1e-6, 1e-5, 1e-4, 1e-4, 0.05, 0.2, 0.2, 1e-11,
                                            1.0,   1.0,  1.0,  1e-3, 1e-3, 1e-3, 1e-3, 1e-2,
                                            0.02,  1e-2, 1e-4};
constexpr std::array<double, kSlots> kUpper{1e9, 1e9, 20.0, 1e10, 1e10, 20.0, 1.0, 0.1,
                                            1e9, 0.1, 1e-5, 1.0,  0.1,  10.0, 10.0, 10.0, 3.0, 5.0, 5.0, 1e-4,
                                            1e10, 1e10, 1e10, 1e10, 1e10, 1e10, 1e10, 1e20,
                                            20.0, 1e9, 1e9};

/// Whether slot `s` is searched inside the physical range `r` that damper.toml
/// holds it to (physical_ranges.hpp).
constexpr bool searched_within(Slot s, const PhysicalRange& r) { return r.min <= kLower[s] && kUpper[s] <= r.max; }
// Every value a calibration can write reads back from its damper.toml.
static_assert(searched_within(kYa, kYieldForceRange) && searched_within(kYb, kYieldForceRange) &&
              searched_within(kYc, kCurrentRateRange) && searched_within(kCa, kViscousRange) &&
              searched_within(kCb, kViscousRange) && searched_within(kCc, kCurrentRateRange) &&
              searched_within(kVtf, kVelocityBandRange) && searched_within(kXy, kYieldDispRange) &&
              searched_within(kK0, kStiffnessRange) && searched_within(kDelay, kForceDelayRange) &&
              searched_within(kPlay, kPlayRange) && searched_within(kShare, kShareRange) &&
              searched_within(kTau, kTransitionTimeRange) && searched_within(kBand, kVelocityBandRange) &&
              searched_within(kCoilSlow, kCoilTimeConstantRange) && searched_within(kCoilFast, kCoilTimeConstantRange) &&
              searched_within(kViscExp, kViscousExponentRange) && searched_within(kYq, kCurrentExponentRange) &&
              searched_within(kCq, kCurrentExponentRange) && searched_within(kSeries, kSeriesComplianceRange) &&
              searched_within(kSpA0, kStiffnessRange) && searched_within(kSpA1, kStiffnessRange) &&
              searched_within(kSpA2, kStiffnessRange) && searched_within(kSpC0a, kViscousRange) &&
              searched_within(kSpC0b, kViscousRange) && searched_within(kSpC1a, kViscousRange) &&
              searched_within(kSpC1b, kViscousRange) && searched_within(kSpGamma, kSpencerGammaRange) &&
              searched_within(kSpGammaRate, kCurrentRateRange) && searched_within(kSpK1, kStiffnessRange) &&
              searched_within(kSpK0, kStiffnessRange));

double& slot_ref(Baseline& b, Slot s) {
  switch (s) {
    case kYa: return b.yield_n.at_zero;
    case kYb: return b.yield_n.limit;
    case kYc: return b.yield_n.rate_per_a;
    case kCa: return b.viscous_ns_m.at_zero;
    case kCb: return b.viscous_ns_m.limit;
    case kCc: return b.viscous_ns_m.rate_per_a;
    case kVtf: return b.v_tf_m_s;
    case kXy: return b.yield_disp_m;
    case kK0: return b.stiffness_n_m;
    case kDelay: return b.force_delay_s;
    case kPlay: return b.lost_motion_m_per_n;
    case kShare: return b.lost_motion_share;
    case kTau: return b.transition_time_s;
    case kBand: return b.lost_motion_band_m_s;
    case kCoilSlow: return b.coil.tau_slow_s;
    case kCoilFast: return b.coil.tau_fast_s;
    case kViscExp: return b.viscous_exponent;
    case kYq: return b.yield_n.current_exponent;
    case kCq: return b.viscous_ns_m.current_exponent;
    case kSeries: return b.series_compliance_m_per_n;
    case kSpGamma: return b.spencer.gamma_per_m_pow_n;
    case kSpGammaRate: return b.spencer.gamma_rate_per_a;
    case kSpK1: return b.spencer.k1_n_m;
    case kSpK0: return b.spencer.k0_n_m;
    default: break;
  }
  return b.v_tf_m_s;
}

bool is_spencer_node(Slot s) { return s >= kSpA0 && s <= kSpC1b; }

/// Which slots are free, and whether a law is a constant (one current).
struct Layout {
  std::vector<Slot> free;
  bool constant_laws = false;  ///< limit tied to at_zero
  /// The spencer law's current laws through values at currents (positive
  /// where the polynomials' coefficients may take either sign): α through
  /// alpha_nodes of node_a (1: node_a[0], a constant; 2: node_a[0] and
  /// node_a[2]; 3: all), c_0 and c_1 through viscous_nodes (1: node_a[0];
  /// 2: node_a[0] and node_a[2]). 0: not the spencer law.
  std::array<double, 3> node_a{0.0, 0.5, 1.0};
  int alpha_nodes = 0;
  int viscous_nodes = 0;

  /// The current of a node slot.
  double node_current(Slot s) const {
    switch (s) {
      case kSpA1: return node_a[1];
      case kSpA2: case kSpC0b: case kSpC1b: return node_a[2];
      default: return node_a[0];
    }
  }

  /// The value of slot `s` in `b`.
  double get(const Baseline& b, Slot s) const {
    if (!is_spencer_node(s)) return slot_ref(const_cast<Baseline&>(b), s);
    const double i = node_current(s);
    if (s <= kSpA2) return b.spencer.alpha_at(i);
    if (s <= kSpC0b) return b.spencer.c0_at(i);
    return b.spencer.c1_at(i);
  }

  /// The spencer law's polynomials through the node values `v` (indexed by slot).
  void set_spencer(Baseline& b, const std::array<double, kSlots>& v) const {
    physics::SpencerParams& p = b.spencer;
    const double i0 = node_a[0], i1 = node_a[1], i2 = node_a[2];
    if (alpha_nodes >= 3) {
      // Newton's form a0 + d1 (i − i0) + d2 (i − i0)(i − i1), expanded.
      const double d1 = (v[kSpA1] - v[kSpA0]) / (i1 - i0);
      const double d2 = ((v[kSpA2] - v[kSpA1]) / (i2 - i1) - d1) / (i2 - i0);
      p.alpha_per_a2_n_m = d2;
      p.alpha_per_a_n_m = d1 - d2 * (i0 + i1);
      p.alpha_n_m = v[kSpA0] - d1 * i0 + d2 * i0 * i1;
    } else if (alpha_nodes == 2) {
      const double d1 = (v[kSpA2] - v[kSpA0]) / (i2 - i0);
      p.alpha_per_a2_n_m = 0.0;
      p.alpha_per_a_n_m = d1;
      p.alpha_n_m = v[kSpA0] - d1 * i0;
    } else {
      p.alpha_per_a2_n_m = p.alpha_per_a_n_m = 0.0;
      p.alpha_n_m = v[kSpA0];
    }
    const auto line = [&](double at_lo, double at_hi, double& at_zero, double& per_a) {
      per_a = viscous_nodes >= 2 ? (at_hi - at_lo) / (i2 - i0) : 0.0;
      at_zero = at_lo - per_a * i0;
    };
    line(v[kSpC0a], v[kSpC0b], p.c0_ns_m, p.c0_per_a_ns_m);
    line(v[kSpC1a], v[kSpC1b], p.c1_ns_m, p.c1_per_a_ns_m);
  }

  Baseline apply(const Baseline& base, const double* theta) const {
    Baseline b = base;
    std::array<double, kSlots> node{};
    if (alpha_nodes > 0)
      for (std::size_t s = kSpA0; s <= kSpC1b; ++s) node[s] = get(base, static_cast<Slot>(s));
    for (std::size_t j = 0; j < free.size(); ++j) {
      if (is_spencer_node(free[j])) {
        node[free[j]] = std::exp(theta[j]);
      } else {
        slot_ref(b, free[j]) = std::exp(theta[j]);
      }
    }
    if (alpha_nodes > 0) set_spencer(b, node);
    if (constant_laws) {
      b.yield_n.limit = b.yield_n.at_zero;
      b.viscous_ns_m.limit = b.viscous_ns_m.at_zero;
    }
    return b;
  }
};

/// All records' thinned samples and their normalization.
struct JointData {
  std::vector<ModelInput> inputs;
  std::vector<std::span<const double>> force_n;
  std::vector<std::vector<std::size_t>> index;
  std::vector<double> rms_force_n;
  /// Per record, multiplies its normalized residuals (empty: 1 each);
  /// equal_record_weights.
  std::vector<double> weight;
  std::size_t total = 0;

  /// One model per record, on `b`.
  std::vector<DamperModel> models(const Baseline& b) const {
    std::vector<DamperModel> m;
    m.reserve(inputs.size());
    for (const ModelInput& in : inputs) m.emplace_back(in, b);
    return m;
  }

  /// (F_model − F_meas)/RMS at every fit sample of every record.
  bool residuals(const Baseline& b, double* out) const {
    std::vector<DamperModel> m = models(b);
    ModelWorkspace ws;
    return residuals(m, ws, b, out);
  }

  /// The same with `models` (one per record, from models()) put on `b`.
  bool residuals(std::vector<DamperModel>& models, ModelWorkspace& ws, const Baseline& b, double* out) const {
    std::size_t at = 0;
    for (std::size_t r = 0; r < inputs.size(); ++r) {
      DamperModel& m = models[r];
      m.set_baseline(b);
      std::span<double> dst(out + at, index[r].size());
      m.simulate_at(EffectSet{}, {}, ws, index[r], dst);
      const double inv = (weight.empty() ? 1.0 : weight[r]) / rms_force_n[r];
      for (std::size_t i = 0; i < index[r].size(); ++i) {
        dst[i] = (dst[i] - force_n[r][index[r][i]]) * inv;
        if (!std::isfinite(dst[i])) return false;
      }
      at += index[r].size();
    }
    return true;
  }
};

/// The joint residuals and their forward-difference Jacobian, one column per
/// free parameter. The columns are independent simulations: with `threads`
/// > 1 they are dealt to that many workers (column j to worker j mod
/// threads), each with its own models and scratch, so that a fit nobody
/// runs beside uses every core; each column is the same arithmetic whatever
/// the count, so the fit is the same to the bit.
class JointCost final : public ceres::CostFunction {
 public:
  JointCost(const JointData& data, const Layout& layout, const Baseline& base, unsigned threads)
      : data_(data),
        layout_(layout),
        base_(base),
        workers_(std::clamp<std::size_t>(threads, 1, std::max<std::size_t>(layout.free.size(), 1))) {
    set_num_residuals(static_cast<int>(data.total));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(layout.free.size()));
    for (std::size_t w = 0; w < workers_; ++w) models_.push_back(data.models(base));
    ws_.resize(workers_);
    column_.resize(workers_);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* theta = parameters[0];
    const std::size_t k = layout_.free.size();
    const std::size_t m = data_.total;
    if (!data_.residuals(models_[0], ws_[0], layout_.apply(base_, theta), residuals)) return false;
    if (jacobians == nullptr || jacobians[0] == nullptr) return true;
    std::vector<char> finite(workers_, 1);
    parallel_for(workers_, static_cast<unsigned>(workers_), [&](std::size_t w) {
      std::vector<double> tp(theta, theta + k);
      std::vector<double>& rp = column_[w];
      rp.resize(m);
      for (std::size_t j = w; j < k; j += workers_) {
        const double h = tp[j] + kStep > std::log(kUpper[layout_.free[j]]) ? -kStep : kStep;
        tp[j] = theta[j] + h;
        if (!data_.residuals(models_[w], ws_[w], layout_.apply(base_, tp.data()), rp.data())) {
          finite[w] = 0;
          return;
        }
        tp[j] = theta[j];
        for (std::size_t r = 0; r < m; ++r) jacobians[0][r * k + j] = (rp[r] - residuals[r]) / h;
      }
    });
    return std::all_of(finite.begin(), finite.end(), [](char f) { return f != 0; });
  }

 private:
  static constexpr double kStep = 1e-6;  ///< in ln(value): a relative step
  const JointData& data_;
  const Layout& layout_;
  Baseline base_;
  std::size_t workers_;
  // Each worker's models and scratch, put on each evaluated baseline in turn
  // (Ceres calls Evaluate from one thread: lm_solver_options).
  mutable std::vector<std::vector<DamperModel>> models_;
  mutable std::vector<ModelWorkspace> ws_;
  mutable std::vector<std::vector<double>> column_;  ///< each worker's perturbed residuals
};

/// Iterations of each start, and of the best start to the end (fit_law).
constexpr int kScreenIterations = 20;
constexpr int kMaxIterations = 100;

struct LocalResult {
  std::vector<double> theta;
  double cost = 0.0;
  int iterations = 0;
  bool converged = false;
};

LocalResult local_fit(const JointData& data, const Layout& layout, const Baseline& base, std::vector<double> theta,
                      int max_iterations, unsigned threads) {
  LocalResult out;
  out.theta = std::move(theta);
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  problem.AddResidualBlock(new JointCost(data, layout, base, threads), nullptr, out.theta.data());
  for (std::size_t j = 0; j < layout.free.size(); ++j) {
    problem.SetParameterLowerBound(out.theta.data(), static_cast<int>(j), std::log(kLower[layout.free[j]]));
    problem.SetParameterUpperBound(out.theta.data(), static_cast<int>(j), std::log(kUpper[layout.free[j]]));
  }
  const ceres::Solver::Options so = lm_solver_options(max_iterations);
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  out.cost = summary.final_cost;
  out.iterations = static_cast<int>(summary.iterations.size());
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  return out;
}

double sum_squares(std::span<const double> r) {
  double s = 0.0;
  for (const double v : r) s += v * v;
  return s;
}

/// Least-squares solution of A p = y (columns of A given), by the normal equations.
std::vector<double> least_squares(const std::vector<std::vector<double>>& cols, const std::vector<double>& y) {
  const std::size_t k = cols.size();
  Eigen::MatrixXd a(y.size(), k);
  for (std::size_t j = 0; j < k; ++j)
    for (std::size_t i = 0; i < y.size(); ++i) a(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = cols[j][i];
  const Eigen::VectorXd yy = Eigen::Map<const Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
  const Eigen::VectorXd p = a.colPivHouseholderQr().solve(yy);
  return {p.data(), p.data() + k};
}

/// Per current: Y, C (and k) of F ≈ Y sgn v + C v (+ k x) on the samples
/// above 30 % of their record's peak velocity.
struct CurrentPoint {
  double current_a = 0.0;
  double yield_n = 0.0;
  double viscous_ns_m = 0.0;
  double stiffness_n_m = 0.0;
};

long current_key(double current_a) { return std::lround(current_a * 1000.0); }

std::vector<CurrentPoint> regress_per_current(const JointData& d, bool with_stiffness) {
  std::map<long, std::array<std::vector<double>, 4>> groups;  // sgn v, v, x, F
  for (std::size_t r = 0; r < d.inputs.size(); ++r) {
    const ModelInput& in = d.inputs[r];
    double vmax = 0.0;
    for (const std::size_t k : d.index[r]) vmax = std::max(vmax, std::fabs(in.vel_m_s[k]));
    for (const std::size_t k : d.index[r]) {
      const double v = in.vel_m_s[k];
      if (std::fabs(v) < 0.3 * vmax) continue;
      auto& g = groups[current_key(in.current_cmd_a[k])];
      g[0].push_back(v > 0.0 ? 1.0 : -1.0);
      g[1].push_back(v);
      g[2].push_back(in.disp_m[k]);
      g[3].push_back(d.force_n[r][k]);
    }
  }
  std::vector<CurrentPoint> pts;
  for (const auto& [key, g] : groups) {
    if (g[3].size() < 10) continue;
    std::vector<std::vector<double>> cols{g[0], g[1]};
    if (with_stiffness) cols.push_back(g[2]);
    const std::vector<double> p = least_squares(cols, g[3]);
    pts.push_back({static_cast<double>(key) / 1000.0, p[0], p[1], with_stiffness ? p[2] : 0.0});
  }
  return pts;
}

/// Current law through points (I_j, value_j): for three or more currents the
/// best of a grid of rates with at_zero and limit by least squares; for two,
/// `rate_fixed`; for one, a constant.
CurrentLaw law_through(const std::vector<CurrentPoint>& pts, double CurrentPoint::*field, double rate_fixed,
                       double floor) {
  std::vector<double> x, y;
  for (const auto& p : pts) {
    x.push_back(std::fabs(p.current_a));
    y.push_back(std::max(p.*field, floor));
  }
  if (y.size() == 1) return {y[0], y[0], rate_fixed};
  const auto fit_rate = [&](double rate, double& sse) {
    std::vector<double> e(x.size()), one_minus(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      e[i] = std::exp(-rate * x[i]);
      one_minus[i] = 1.0 - e[i];
    }
    const std::vector<double> p = least_squares({e, one_minus}, y);
    CurrentLaw law{std::max(p[0], floor), std::max(p[1], floor), rate};
    sse = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) sse += std::pow(law.at(x[i]) - y[i], 2);
    return law;
  };
  double best_sse = 0.0;
  CurrentLaw best = fit_rate(rate_fixed, best_sse);
  if (y.size() >= 3) {
    for (const double rate : {0.25, 0.5, 1.0, 2.0, 4.0, 8.0}) {
      double sse = 0.0;
      const CurrentLaw law = fit_rate(rate, sse);
      if (sse < best_sse) {
        best_sse = sse;
        best = law;
      }
    }
  }
  return best;
}

double clamp_slot(double v, Slot s) { return std::clamp(v, kLower[s] * 1.01, kUpper[s] / 1.01); }

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Prepared {
  JointData data;
  std::vector<double> vmax_m_s;      ///< per record
  std::vector<double> half_range_m;  ///< per record
  std::vector<double> currents_a;    ///< distinct currents with ≥ 2 % of the samples
  /// Some record's commanded current changes (command_changes; a measured
  /// current's noise is no change): the coil's slow time constant is fitted
  /// (fit_law); otherwise the time constants leave no trace in the force.
  bool current_changes = false;
  /// Some record's commanded current changes and it has no measured one: the
  /// fast time constant (the drive and coil, which a measured current
  /// replaces: DamperModel) is fitted too.
  bool command_drives_coil = false;
};

Prepared prepare(std::span<const MeasuredData> records, const CalibrateOptions& opt) {
  Prepared p;
  std::map<long, std::size_t> count;
  std::size_t all = 0;
  for (const MeasuredData& rec : records) {
    ModelInput in = model_input(rec, opt.smoothing_half_window_s);
    const std::size_t n = rec.size();
    // Fitted and normalized over the samples where the actuator moves.
    const SampleRange moving = moving_span(in.vel_m_s);
    const std::size_t stride =
        std::max<std::size_t>(1, opt.samples_per_record > 0 ? moving.size() / opt.samples_per_record : 1);
    std::vector<std::size_t> idx;
    for (std::size_t k = moving.begin; k < moving.end; k += stride) idx.push_back(k);
    double ss = 0.0, vmax = 0.0;
    for (std::size_t k = moving.begin; k < moving.end; ++k) ss += rec.force_n[k] * rec.force_n[k];
    for (const double v : in.vel_m_s) vmax = std::max(vmax, std::fabs(v));
    for (const double c : rec.current_cmd_a) ++count[current_key(c)];
    if (command_changes(rec.current_cmd_a).steps > 0) {
      p.current_changes = true;
      if (rec.current_a.empty()) p.command_drives_coil = true;
    }
    all += n;
    p.data.rms_force_n.push_back(ss > 0.0 ? std::sqrt(ss / static_cast<double>(moving.size())) : 1.0);
    p.data.total += idx.size();
    p.data.index.push_back(std::move(idx));
    p.data.force_n.push_back(rec.force_n);
    p.vmax_m_s.push_back(vmax);
    p.half_range_m.push_back(half_range_m(in.disp_m));
    p.data.inputs.push_back(std::move(in));
  }
  for (const auto& [key, c] : count)
    if (static_cast<double>(c) >= 0.02 * static_cast<double>(all)) p.currents_a.push_back(static_cast<double>(key) / 1000.0);
  return p;
}

/// Weights that give each record the same share of the joint fit's sum of
/// squares whatever its number of fit samples: √(n̄/n_r), n̄ the mean.
std::vector<double> equal_record_weights(const JointData& d) {
  std::vector<double> w;
  const double mean_n = static_cast<double>(d.total) / static_cast<double>(std::max<std::size_t>(d.index.size(), 1));
  for (const auto& idx : d.index) w.push_back(idx.empty() ? 0.0 : std::sqrt(mean_n / static_cast<double>(idx.size())));
  return w;
}

/// The largest current in the records, A (0 with none).
double top_current_a(const Prepared& p) {
  return p.currents_a.empty() ? 0.0 : *std::max_element(p.currents_a.begin(), p.currents_a.end());
}

/// Standard errors of the free parameters (in ln value), from σ² (JᵀJ)⁻¹ n/n_eff.
std::vector<double> log_sigmas(const JointData& d, const Layout& layout, const Baseline& base,
                               const std::vector<double>& theta, double rss, double n_eff, unsigned threads) {
  const std::size_t k = theta.size();
  const std::size_t m = d.total;
  std::vector<double> res(m), jac(m * k);
  JointCost cost(d, layout, base, threads);
  const double* params[] = {theta.data()};
  double* jacs[] = {jac.data()};
  std::vector<double> sig(k, 0.0);
  if (m <= k || !cost.Evaluate(params, res.data(), jacs)) return sig;
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> j(
      jac.data(), static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(k));
  const Eigen::MatrixXd jtj = j.transpose() * j;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(jtj, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd s = svd.singularValues();
  Eigen::VectorXd inv_s = Eigen::VectorXd::Zero(s.size());
  for (Eigen::Index i = 0; i < s.size(); ++i)
    if (s(i) > 1e-12 * s(0)) inv_s(i) = 1.0 / s(i);
  const Eigen::MatrixXd cov_unit = svd.matrixV() * inv_s.asDiagonal() * svd.matrixU().transpose();
  const double sigma2 = rss / static_cast<double>(m - k);
  const double inflation = static_cast<double>(m) / std::max(n_eff, 1.0);
  for (std::size_t i = 0; i < k; ++i) {
    const double c = cov_unit(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) * sigma2 * inflation;
    sig[i] = c > 0.0 ? std::sqrt(c) : 0.0;
  }
  return sig;
}

/// The parts a baseline may carry beyond its law (baseline.hpp).
struct Extras {
  bool transition_time = false;
  bool lost_motion = false;
  bool viscous_play = false;  ///< the lost motion's force inside the play viscous (share held at 1)
  bool current_exponent = false;  ///< the current laws' exponents q fitted
  bool stiffness = false;     ///< a spring beside the Bingham law (stiffness_n_m)
  bool viscous_exponent = false;  ///< the Bingham law's viscous force as a power of v
  bool series_compliance = false;  ///< a compliance in series with the Bingham law
};

Extras extras_of(const Baseline& b) {
  return {b.has_transition_time(), b.has_lost_motion(), b.has_viscous_lost_motion(), b.has_current_exponent(),
          b.has_bingham_stiffness(), b.has_viscous_exponent(), b.has_series_compliance()};
}

/// `threads` with 0 read as every core.
unsigned resolved_threads(unsigned threads) {
  return threads ? threads : std::max(1u, std::thread::hardware_concurrency());
}

/// `o` for one of `count` fits run side by side on its threads: the threads
/// each fit's Jacobian may use (at least one).
CalibrateOptions side_by_side(const CalibrateOptions& o, std::size_t count) {
  CalibrateOptions each = o;
  each.threads = std::max<unsigned>(1u, resolved_threads(o.threads) / static_cast<unsigned>(std::max<std::size_t>(count, 1)));
  return each;
}

/// Fits `law` (with the tanh transition when `tanh` and the law is Bingham)
/// with `extras` to the records. With `from` given (a fit of the
/// same law with one extra fewer), starts from it with the new extra's
/// parameters on a grid; with `start_at` (a baseline of this form), from it
/// alone, its current laws taken at the records' current when they are one.
LawFit fit_law(const Prepared& p, BaseLaw law, bool tanh, const CalibrateOptions& opt,
               const LawFit* from = nullptr, Extras extras = {}, const Baseline* start_at = nullptr) {
  const bool spencer = law == BaseLaw::spencer;
  // The spencer law weighs records alike (equal_record_weights): a 25 mm /
  // 0.25 Hz laboratory record holds 4600 moving samples, a 2 mm / 5 Hz one
  // 540, and sample weights fit the slow strokes at the fast ones' expense
  // (held-out median 0.233 against 0.184 with equal weights, README).
  JointData weighted;
  if (spencer) {
    weighted = p.data;
    weighted.weight = equal_record_weights(p.data);
  }
  const JointData& d = spencer ? weighted : p.data;
  const std::size_t n_currents = p.currents_a.size();
  const Baseline thesis = thesis_baseline();
  const unsigned threads = resolved_threads(opt.threads);  // the Jacobian's columns side by side

  Layout layout;
  layout.constant_laws = n_currents <= 1;
  LawFit fit;
  fit.yield_fitted = {true, n_currents >= 2, n_currents >= 3};
  fit.viscous_fitted = fit.yield_fitted;
  if (spencer) {
    // α through three currents (quadratic), c_0 and c_1 through two
    // (affine), γ's rate: as many as the currents identify.
    std::vector<double> abs_a;
    for (const double c : p.currents_a) abs_a.push_back(std::fabs(c));
    if (abs_a.empty()) abs_a.push_back(0.0);
    const auto [lo, hi] = std::minmax_element(abs_a.begin(), abs_a.end());
    layout.node_a = {*lo, 0.5 * (*lo + *hi), *hi};
    layout.alpha_nodes = static_cast<int>(std::min<std::size_t>(n_currents, 3));
    layout.viscous_nodes = static_cast<int>(std::min<std::size_t>(n_currents, 2));
    if (layout.alpha_nodes == 0) layout.alpha_nodes = layout.viscous_nodes = 1;
    layout.free = {kSpA0};
    if (layout.alpha_nodes >= 3) layout.free.push_back(kSpA1);
    if (layout.alpha_nodes >= 2) layout.free.push_back(kSpA2);
    layout.free.push_back(kSpC0a);
    if (layout.viscous_nodes >= 2) layout.free.push_back(kSpC0b);
    layout.free.push_back(kSpC1a);
    if (layout.viscous_nodes >= 2) layout.free.push_back(kSpC1b);
    layout.free.push_back(kSpGamma);
    if (n_currents >= 2) layout.free.push_back(kSpGammaRate);
    layout.free.push_back(kSpK1);
    layout.free.push_back(kSpK0);
    fit.yield_fitted = fit.viscous_fitted = {false, false, false};
  } else {
    layout.free = {kYa};
    if (fit.yield_fitted.limit) layout.free.push_back(kYb);
    if (fit.yield_fitted.rate_per_a) layout.free.push_back(kYc);
    layout.free.push_back(kCa);
    if (fit.viscous_fitted.limit) layout.free.push_back(kCb);
    if (fit.viscous_fitted.rate_per_a) layout.free.push_back(kCc);
    if (extras.current_exponent) layout.free.insert(layout.free.end(), {kYq, kCq});
  }
  if (spencer) {
    // its shape is in its own slots
  } else if (law == BaseLaw::bingham) {
    layout.free.push_back(kVtf);
    if (extras.transition_time) layout.free.push_back(kTau);
    if (extras.stiffness) layout.free.push_back(kK0);
    if (extras.viscous_exponent) layout.free.push_back(kViscExp);
    if (extras.series_compliance) layout.free.push_back(kSeries);
  } else {
    layout.free.push_back(kXy);
    layout.free.push_back(kK0);
  }
  // The force channel's lag: records of one rig share it (filters, logger).
  // Not with the spencer law: its internal dashpot c_1 and the pre-yield of
  // z are the lag of the force through a reversal, and a channel lag fitted
  // beside them takes what the slow strokes lack (7–13 ms on two laboratory
  // families) into the fast ones (held-out 2 mm / 5 Hz median 0.253 with
  // it, 0.189 without; the published fit has none).
  if (!spencer) layout.free.push_back(kDelay);
  if (extras.lost_motion) {
    layout.free.push_back(kPlay);
    layout.free.push_back(extras.viscous_play ? kBand : kShare);
  }
  // The coil's two time constants of Eq. 4.5 (weights held at ½ each, the
  // unity DC gain of current_dynamics.hpp), when a record's current changes:
  // equal, they are one first-order lag from command to field, the form of
  // Spencer et al. (1997)'s filter u̇ = −η (u − v) for a small damper's drive.
  // A measured coil current stands for the fast branch: the slow one alone.
  if (p.current_changes) layout.free.push_back(kCoilSlow);
  if (p.command_drives_coil) layout.free.push_back(kCoilFast);

  // Base: the thesis's coil (the start of its fit when a current changes,
  // else held: not identifiable) and participant ratio (not identifiable
  // here), current laws from the per-current regression.
  Baseline base = thesis;
  base.name = opt.name;
  base.coil_identified = p.current_changes;
  base.law = law;
  base.tanh_transition = law == BaseLaw::bingham && tanh;
  if (extras.viscous_play) base.lost_motion_share = 1.0;  // the whole law's force waits for the play
  base.range = {};
  const std::vector<CurrentPoint> pts = regress_per_current(d, law != BaseLaw::bingham);
  double y_max = 1.0, c_max = 1.0;
  for (const auto& q : pts) {
    y_max = std::max(y_max, std::fabs(q.yield_n));
    c_max = std::max(c_max, std::fabs(q.viscous_ns_m));
  }
  if (!pts.empty()) {
    base.yield_n = law_through(pts, &CurrentPoint::yield_n, thesis.yield_n.rate_per_a, 1e-2 * y_max);
    base.viscous_ns_m = law_through(pts, &CurrentPoint::viscous_ns_m, thesis.viscous_ns_m.rate_per_a, 1e-2 * c_max);
  }
  const double vmax = median(p.vmax_m_s);
  // The viscous exponent's reference velocity: the start's, the fit's it
  // grows from, or the records' median peak velocity (held, not fitted).
  if (extras.viscous_exponent) {
    base.viscous_ref_m_s = vmax;
    if (start_at != nullptr && start_at->viscous_ref_m_s > 0.0) base.viscous_ref_m_s = start_at->viscous_ref_m_s;
    if (from != nullptr && from->baseline.viscous_ref_m_s > 0.0) base.viscous_ref_m_s = from->baseline.viscous_ref_m_s;
  }
  const double amp_min = *std::min_element(p.half_range_m.begin(), p.half_range_m.end());
  std::vector<double> ks;
  for (const auto& q : pts)
    if (q.stiffness_n_m > 0.0) ks.push_back(q.stiffness_n_m);
  const double k_start = ks.empty() ? 1e-2 * y_max / std::max(amp_min, 1e-6) : median(ks);

  // Starts: the transition velocity or the yield displacement on a grid,
  // the force lag at 1 ms and 10 ms (a lag near a period's fraction has
  // neighbouring minima on a sine).
  std::vector<Baseline> starts;
  if (start_at != nullptr) {
    Baseline s = *start_at;
    if (layout.constant_laws) {
      s.yield_n.at_zero = s.yield_n.at(top_current_a(p));
      s.viscous_ns_m.at_zero = s.viscous_ns_m.at(top_current_a(p));
    }
    starts.push_back(s);
  } else if (from != nullptr && extras.current_exponent && !from->baseline.has_current_exponent()) {
    // From the fit without it: both laws with an exponent of 1.5 or 2.5
    // (the value at 1 A unchanged).
    for (const double q : {1.5, 2.5}) {
      Baseline s = from->baseline;
      s.yield_n.current_exponent = s.viscous_ns_m.current_exponent = q;
      starts.push_back(s);
    }
  } else if (from != nullptr && extras.stiffness && !from->baseline.has_bingham_stiffness()) {
    // From the fit without it: a spring whose force at the largest half
    // range is 1 % or 5 % of the yield force at the largest current (an
    // accumulator's gas charge: tens of newtons on a 2 kN damper).
    const double y_top = std::max(std::fabs(from->baseline.yield_n.at(top_current_a(p))), 1e-3);
    const double amp_max = *std::max_element(p.half_range_m.begin(), p.half_range_m.end());
    for (const double f : {0.01, 0.05}) {
      Baseline s = from->baseline;
      s.stiffness_n_m = clamp_slot(f * y_top / std::max(amp_max, 1e-6), kK0);
      starts.push_back(s);
    }
  } else if (from != nullptr && extras.series_compliance && !from->baseline.has_series_compliance()) {
    // From the fit without it: a compliance over which the yield force at
    // the largest current deflects 5 % or 20 % of the smallest half range
    // (the fluid's and the body's give, short against the stroke).
    const double y_top = std::max(std::fabs(from->baseline.yield_n.at(top_current_a(p))), 1e-3);
    for (const double f : {0.05, 0.2}) {
      Baseline s = from->baseline;
      s.series_compliance_m_per_n = clamp_slot(f * amp_min / y_top, kSeries);
      starts.push_back(s);
    }
  } else if (from != nullptr && extras.viscous_exponent && !from->baseline.has_viscous_exponent()) {
    // From the fit without it: the viscous force the same at v_r, the
    // records' median peak velocity, and an exponent of 0.6 or 0.85
    // (shear thinning, as MR fluids show past yield).
    for (const double m : {0.6, 0.85}) {
      Baseline s = from->baseline;
      s.viscous_ref_m_s = vmax;
      s.viscous_exponent = m;
      starts.push_back(s);
    }
  } else if (from != nullptr && extras.lost_motion && !from->baseline.has_lost_motion()) {
    // From the fit without it: a play at the largest current of 5 % or 20 %
    // of the smallest half range (a plateau short against the stroke),
    // holding up a third or two thirds of the force, or (the viscous form,
    // its share held at 1 by `base`) with a force inside the play over a
    // band of 3 or 12 times the transition's.
    const double y_top = std::max(std::fabs(from->baseline.yield_n.at(top_current_a(p))), 1e-3);
    for (const double f : {0.05, 0.2})
      for (const auto& [share, band_per_v_tf] : {std::pair{0.33, 3.0}, std::pair{0.67, 12.0}}) {
        Baseline s = from->baseline;
        s.lost_motion_m_per_n = f * amp_min / y_top;
        if (extras.viscous_play) {
          s.lost_motion_band_m_s = band_per_v_tf * from->baseline.v_tf_m_s;
        } else {
          s.lost_motion_share = share;
        }
        starts.push_back(s);
      }
  } else if (from != nullptr) {
    // From the fit without it: a transition time of 2 ms or 8 ms (the
    // response time of MR fluid and valve, a few milliseconds), with the
    // band v_TF as fitted or a third of it (the time then takes over part
    // of the transition the band had to carry alone).
    for (const double tau_s : {2e-3, 8e-3})
      for (const double band_share : {1.0, 1.0 / 3.0}) {
        Baseline s = from->baseline;
        s.transition_time_s = tau_s;
        s.v_tf_m_s = band_share * from->baseline.v_tf_m_s;
        starts.push_back(s);
      }
  } else if (spencer) {
    // From the per-current regression F ≈ Y sgn v + C v + k x: at each
    // node current, z saturating at z_s = A x_y (the pre-yield stroke x_y,
    // over which ż ≈ A ẋ builds it, a share of the smallest half range as
    // for Bouc–Wen), c_1 = r c_0 with r = 10 (the dashpot that rolls the
    // force off through a reversal ten times the one in series with the
    // hysteresis, as in Spencer et al. 1997's and the laboratory's fits),
    // then α and the c's such that the saturated force is Y and the viscous
    // one C: α z_s r/(1 + r) = Y, c_0 r/(1 + r) = C.
    const auto at_current = [&](double i, double CurrentPoint::*field) {
      // Piecewise linear through the points (sorted by current), constant beyond.
      if (pts.empty()) return field == &CurrentPoint::yield_n ? y_max : c_max;
      std::vector<std::pair<double, double>> xy;
      for (const auto& q : pts) xy.emplace_back(std::fabs(q.current_a), std::max(q.*field, 0.0));
      std::sort(xy.begin(), xy.end());
      if (i <= xy.front().first) return xy.front().second;
      for (std::size_t j = 1; j < xy.size(); ++j)
        if (i <= xy[j].first)
          return xy[j - 1].second + (xy[j].second - xy[j - 1].second) * (i - xy[j - 1].first) /
                                        (xy[j].first - xy[j - 1].first);
      return xy.back().second;
    };
    // Two pre-yield shares (each start takes a stiff ODE through every
    // record, some ten times a Bouc–Wen start's cost); no force lag.
    const std::vector<double> coil_scales = p.current_changes ? std::vector{1.0, 1.0 / 30.0} : std::vector{1.0};
    constexpr double r = 10.0;
    for (const double coil_scale : coil_scales)
      for (const double f : {0.02, 0.1}) {
        Baseline s = base;
        s.coil.tau_slow_s *= coil_scale;
        s.coil.tau_fast_s *= coil_scale;
        physics::SpencerParams& q = s.spencer;
        q = physics::SpencerParams{};  // A = 300, n = 2, β = γ
        const double z_s = q.a * f * amp_min;
        q.gamma_per_m_pow_n = q.a / ((1.0 + q.beta_over_gamma) * z_s * z_s);
        q.gamma_rate_per_a = 1.0;
        q.k1_n_m = std::clamp(k_start, kLower[kSpK1] * 10.0, kUpper[kSpK1] / 10.0);
        q.k0_n_m = std::max(1e-3 * q.k1_n_m, kLower[kSpK0] * 10.0);
        std::array<double, kSlots> node{};
        for (std::size_t slot = kSpA0; slot <= kSpC1b; ++slot) {
          const Slot sl = static_cast<Slot>(slot);
          const double i = layout.node_current(sl);
          const double z_i = std::sqrt(q.a / ((1.0 + q.beta_over_gamma) * q.gamma_at(i)));
          double v = 0.0;
          if (sl <= kSpA2) {
            v = std::max(at_current(i, &CurrentPoint::yield_n), 1e-2 * y_max) * (1.0 + r) / (r * z_i);
          } else {
            const double c0 = std::max(at_current(i, &CurrentPoint::viscous_ns_m), 1e-2 * c_max) * (1.0 + r) / r;
            v = sl <= kSpC0b ? c0 : r * c0;
          }
          node[slot] = clamp_slot(v, sl);
        }
        layout.set_spencer(s, node);
        starts.push_back(s);
      }
    // The shape of a published fit of a small damper's (the laboratory's,
    // published_lab_spencer: its pre-yield, roll-off and current laws), its
    // forces scaled by the records' yield force at the top current over its
    // own there; x_0 at 0 (held: k_1 x_0 is a constant force).
    {
      Baseline s = base;
      physics::SpencerParams q = published_lab_spencer();
      const double i_top = layout.node_a[2];
      const double y_own = physics::spencer_yield_force_n(q.at(i_top));
      const double y_rec = at_current(i_top, &CurrentPoint::yield_n);
      const double f = y_own > 0.0 && y_rec > 0.0 ? y_rec / y_own : 1.0;
      for (double* c : {&q.alpha_n_m, &q.alpha_per_a_n_m, &q.alpha_per_a2_n_m, &q.c0_ns_m, &q.c0_per_a_ns_m,
                        &q.c1_ns_m, &q.c1_per_a_ns_m, &q.k0_n_m, &q.k1_n_m})
        *c *= f;
      q.x0_m = 0.0;
      s.spencer = q;
      starts.push_back(s);
    }
  } else {
    // With a current that changes, each start also with the thesis's coil
    // and with one 30 times faster (0.7 s / 30 ms → 23 ms / 1 ms: a small
    // damper's coil behind a current drive).
    const std::vector<double> coil_scales = p.current_changes ? std::vector{1.0, 1.0 / 30.0} : std::vector{1.0};
    for (const double coil_scale : coil_scales)
      for (const double f : {0.02, 0.1, 0.3})
        for (const double lag_s : {1e-3, 10e-3}) {
          Baseline s = base;
          s.force_delay_s = lag_s;
          s.coil.tau_slow_s *= coil_scale;
          s.coil.tau_fast_s *= coil_scale;
          if (law == BaseLaw::bingham) {
            s.v_tf_m_s = f * vmax;
          } else {
            s.yield_disp_m = f * amp_min;
            s.stiffness_n_m = k_start;
          }
          starts.push_back(s);
        }
  }

  if (spencer) {
    base.force_delay_s = 0.0;
    for (Baseline& s : starts) s.force_delay_s = 0.0;
  }
  // Every start for a few iterations, then the best one to convergence:
  // the starts sort out which basin (lag, transition) within a few steps,
  // while the last steps crawl along the valley of a law whose rate ends on
  // its bound (laws linear in the current; only (limit − at_zero)·rate is
  // identified).
  LocalResult best;
  bool have = false;
  for (const Baseline& s : starts) {
    std::vector<double> theta;
    Baseline sc = s;
    for (const Slot slot : layout.free) theta.push_back(std::log(clamp_slot(layout.get(sc, slot), slot)));
    const LocalResult r = local_fit(d, layout, base, std::move(theta), kScreenIterations, threads);
    if (!have || r.cost < best.cost) {
      best = r;
      have = true;
    }
  }
  if (!best.converged) {
    const int screened = best.iterations;
    best = local_fit(d, layout, base, best.theta, kMaxIterations, threads);
    best.iterations += screened;
  }

  fit.baseline = layout.apply(base, best.theta.data());
  fit.iterations = best.iterations;
  fit.converged = best.converged;
  fit.samples = d.total;

  std::vector<double> res(d.total);
  d.residuals(fit.baseline, res.data());
  fit.rss = sum_squares(res);
  std::size_t at = 0;
  for (std::size_t r = 0; r < d.inputs.size(); ++r) {
    fit.n_eff += effective_sample_count(std::span<const double>(res).subspan(at, d.index[r].size()));
    at += d.index[r].size();
  }

  const std::vector<double> sl = log_sigmas(d, layout, base, best.theta, fit.rss, fit.n_eff, threads);
  std::array<double, kSlots> sigma{};
  std::array<bool, kSlots> fitted{}, at_bound{};
  for (std::size_t j = 0; j < layout.free.size(); ++j) {
    const Slot s = layout.free[j];
    const double v = std::exp(best.theta[j]);
    sigma[s] = v * sl[j];
    fitted[s] = true;
    at_bound[s] = best.theta[j] <= std::log(kLower[s]) + 1e-3 || best.theta[j] >= std::log(kUpper[s]) - 1e-3;
  }
  if (layout.constant_laws) {
    sigma[kYb] = sigma[kYa];
    sigma[kCb] = sigma[kCa];
  }
  fit.sigma.yield_n = {sigma[kYa], sigma[kYb], sigma[kYc], sigma[kYq]};
  fit.sigma.viscous_ns_m = {sigma[kCa], sigma[kCb], sigma[kCc], sigma[kCq]};
  fit.sigma.v_tf_m_s = sigma[kVtf];
  fit.sigma.yield_disp_m = sigma[kXy];
  fit.sigma.stiffness_n_m = sigma[kK0];
  fit.sigma.force_delay_s = sigma[kDelay];
  fit.sigma.lost_motion_m_per_n = sigma[kPlay];
  fit.sigma.lost_motion_share = sigma[kShare];
  fit.sigma.lost_motion_band_m_s = sigma[kBand];
  fit.sigma.transition_time_s = sigma[kTau];
  fit.sigma.viscous_exponent = sigma[kViscExp];
  fit.sigma.series_compliance_m_per_n = sigma[kSeries];
  fit.sigma.coil_tau_slow_s = sigma[kCoilSlow];
  fit.sigma.coil_tau_fast_s = sigma[kCoilFast];

  std::vector<Slot> shown;
  if (spencer) {
    for (const Slot s : layout.free)
      if (s != kDelay && s != kCoilSlow && s != kCoilFast) shown.push_back(s);
  } else {
    shown = {kYa, kYb, kYc, kCa, kCb, kCc};
    if (extras.current_exponent) shown.insert(shown.end(), {kYq, kCq});
  }
  if (spencer) {
    // shown above
  } else if (law == BaseLaw::bingham) {
    shown.push_back(kVtf);
    if (extras.transition_time) shown.push_back(kTau);
    if (extras.stiffness) shown.push_back(kK0);
    if (extras.viscous_exponent) shown.push_back(kViscExp);
    if (extras.series_compliance) shown.push_back(kSeries);
  } else {
    shown.push_back(kXy);
    shown.push_back(kK0);
  }
  shown.push_back(kDelay);
  if (extras.lost_motion) {
    shown.push_back(kPlay);
    shown.push_back(extras.viscous_play ? kBand : kShare);
  }
  if (p.current_changes) shown.push_back(kCoilSlow);
  if (p.command_drives_coil) shown.push_back(kCoilFast);
  for (const Slot s : shown)
    fit.params.push_back({kSlotName[s], layout.get(fit.baseline, s), sigma[s], fitted[s], at_bound[s]});
  return fit;
}

}  // namespace

std::vector<double> baseline_gaps(const Baseline& baseline, std::span<const MeasuredData> records,
                                  double smoothing_half_window_s) {
  std::vector<double> gaps;
  ModelWorkspace ws;
  std::vector<double> force;
  for (const MeasuredData& rec : records) {
    const DamperModel m(model_input(rec, smoothing_half_window_s), baseline);
    m.simulate(EffectSet{}, {}, ws, force);
    const SampleRange moving = moving_span(m.input().vel_m_s);
    gaps.push_back(normalized_rms_gap(std::span<const double>(rec.force_n).subspan(moving.begin, moving.size()),
                                      std::span<const double>(force).subspan(moving.begin, moving.size())));
  }
  return gaps;
}

std::vector<double> record_floor_gaps(const Baseline& form, std::span<const MeasuredData> records,
                                      const CalibrateOptions& options) {
  std::vector<double> floors(records.size());
  const CalibrateOptions each = side_by_side(options, records.size());
  parallel_for(records.size(), options.threads, [&](std::size_t r) {
    const Prepared p = prepare(records.subspan(r, 1), options);
    const LawFit f = fit_law(p, form.law, form.tanh_transition, each, nullptr, extras_of(form), &form);
    floors[r] = baseline_gaps(f.baseline, records.subspan(r, 1), options.smoothing_half_window_s).front();
  });
  return floors;
}

double rms_over_records(std::span<const double> gaps) {
  if (gaps.empty()) return 0.0;
  double s = 0.0;
  for (const double g : gaps) s += g * g;
  return std::sqrt(s / static_cast<double>(gaps.size()));
}

ValidityRange validity_range(std::span<const MeasuredData> records, double smoothing_half_window_s) {
  ValidityRange v;
  bool first = true;
  for (const MeasuredData& rec : records) {
    if (rec.size() == 0) continue;
    const ModelInput in = model_input(rec, smoothing_half_window_s);
    const auto [ilo, ihi] = std::minmax_element(rec.current_cmd_a.begin(), rec.current_cmd_a.end());
    double vmax = 0.0, fmax = 0.0;
    for (const double x : in.vel_m_s) vmax = std::max(vmax, std::fabs(x));
    for (const double f : rec.force_n) fmax = std::max(fmax, std::fabs(f));
    const double amp = half_range_m(in.disp_m);
    const double freq = dominant_frequency_hz(rec.time_s, in.disp_m);
    if (first) {
      v.current_min_a = *ilo;
      v.current_max_a = *ihi;
      v.amplitude_min_m = v.amplitude_max_m = amp;
      v.frequency_min_hz = v.frequency_max_hz = freq;
      first = false;
    }
    v.current_min_a = std::min(v.current_min_a, *ilo);
    v.current_max_a = std::max(v.current_max_a, *ihi);
    v.velocity_max_m_s = std::max(v.velocity_max_m_s, vmax);
    v.force_peak_n = std::max(v.force_peak_n, fmax);
    v.amplitude_min_m = std::min(v.amplitude_min_m, amp);
    v.amplitude_max_m = std::max(v.amplitude_max_m, amp);
    v.frequency_min_hz = std::min(v.frequency_min_hz, freq);
    v.frequency_max_hz = std::max(v.frequency_max_hz, freq);
  }
  return v;
}

namespace {

/// Whether every check record repeats the motion of a fitted record: its
/// half range and dominant frequency inside that one record's coverage
/// (coverage_notes, within kCoverageFactor).
bool check_repeats_fitted_motions(std::span<const MeasuredData> records, std::span<const MeasuredData> check,
                                  double smoothing_half_window_s) {
  std::vector<ValidityRange> fitted;
  for (std::size_t i = 0; i < records.size(); ++i)
    fitted.push_back(validity_range(records.subspan(i, 1), smoothing_half_window_s));
  for (std::size_t i = 0; i < check.size(); ++i) {
    const ValidityRange m = validity_range(check.subspan(i, 1), smoothing_half_window_s);
    if (std::none_of(fitted.begin(), fitted.end(), [&](const ValidityRange& f) {
          return coverage_notes(f, m.amplitude_max_m, m.frequency_max_hz, 0.0).empty();
        }))
      return false;
  }
  return true;
}

}  // namespace

std::vector<std::vector<std::size_t>> motion_groups(std::span<const MeasuredData> records,
                                                    double smoothing_half_window_s) {
  std::vector<std::vector<std::size_t>> groups;
  std::vector<ValidityRange> first;  // each group's first record's motion
  for (std::size_t i = 0; i < records.size(); ++i) {
    const ValidityRange m = validity_range(records.subspan(i, 1), smoothing_half_window_s);
    const auto same = [&](const ValidityRange& f) {
      return coverage_notes(f, m.amplitude_max_m, m.frequency_max_hz, 0.0).empty() &&
             coverage_notes(m, f.amplitude_max_m, f.frequency_max_hz, 0.0).empty();
    };
    std::size_t g = 0;
    while (g < first.size() && !same(first[g])) ++g;
    if (g == first.size()) {
      first.push_back(m);
      groups.emplace_back();
    }
    groups[g].push_back(i);
  }
  return groups;
}

std::vector<std::vector<std::size_t>> cross_validation_folds(std::span<const MeasuredData> records,
                                                             double smoothing_half_window_s) {
  std::vector<std::vector<std::size_t>> groups = motion_groups(records, smoothing_half_window_s);
  if (groups.size() <= kMaxCrossValidationFolds) return groups;
  // Each motion's half range and dominant frequency (its first record's).
  struct Motion {
    double amplitude_m, frequency_hz;
    std::size_t group;
  };
  std::vector<Motion> motions;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const ValidityRange m = validity_range(records.subspan(groups[g].front(), 1), smoothing_half_window_s);
    motions.push_back({m.amplitude_max_m, m.frequency_max_hz, g});
  }
  std::stable_sort(motions.begin(), motions.end(), [](const Motion& a, const Motion& b) {
    return a.amplitude_m != b.amplitude_m ? a.amplitude_m < b.amplitude_m : a.frequency_hz < b.frequency_hz;
  });
  std::vector<std::vector<std::size_t>> folds(kMaxCrossValidationFolds);
  for (std::size_t j = 0; j < motions.size(); ++j) {
    const std::vector<std::size_t>& g = groups[motions[j].group];
    std::vector<std::size_t>& f = folds[j % kMaxCrossValidationFolds];
    f.insert(f.end(), g.begin(), g.end());
  }
  for (auto& f : folds) std::sort(f.begin(), f.end());
  std::sort(folds.begin(), folds.end(), [](const auto& a, const auto& b) { return a.front() < b.front(); });
  return folds;
}

CalibrationResult calibrate(std::span<const MeasuredData> records, const CalibrateOptions& options,
                            std::span<const MeasuredData> check) {
  if (records.empty()) throw io::UsageError("calibrate: expected at least one measured record");
  CalibrationResult res;
  const Prepared p = prepare(records, options);
  res.currents_a = p.currents_a;
  for (std::size_t r = 0; r < records.size(); ++r) {
    res.sources.push_back(records[r].source);
    res.record_samples.push_back(p.data.index[r].size());
  }
  if (p.currents_a.size() <= 1) {
    res.notes.push_back("one current in the records: yield_n and viscous_ns_m are constants (limit = at_zero), "
                        "rate_per_a held at the thesis value");
  } else if (p.currents_a.size() == 2) {
    res.notes.push_back("two currents in the records: rate_per_a held at the thesis value (Table 4.1)");
  }
  const auto measured = static_cast<std::size_t>(
      std::count_if(records.begin(), records.end(), [](const MeasuredData& r) { return !r.current_a.empty(); }));
  if (measured > 0)
    res.notes.push_back("coil current measured in " + std::to_string(measured) + " of " +
                        std::to_string(records.size()) +
                        " records: the laws act on it, lagged by Eq. 4.5's slow branch alone (the fast branch, the "
                        "drive and coil, is what was measured)");
  if (p.command_drives_coil) {
    res.notes.push_back("coil (Eq. 4.5): tau_slow_s and tau_fast_s fitted to the records whose current changes "
                        "(weights held at 1/2 each); participant ratio (Eq. 5.6-5.11): thesis values, assumed");
  } else if (p.current_changes) {
    res.notes.push_back("coil (Eq. 4.5): tau_slow_s (the field lagging the measured coil current) fitted to the "
                        "records whose current command changes; tau_fast_s not used with a measured current, thesis "
                        "value (a later record without the sensor gets it); participant ratio (Eq. 5.6-5.11): "
                        "thesis values, assumed");
  } else {
    res.notes.push_back("coil (Eq. 4.5) and participant ratio (Eq. 5.6-5.11): thesis values, assumed (constant-current "
                        "records do not identify them)");
  }

  std::vector<BaseLaw> laws;
  if (options.law) {
    laws.push_back(*options.law);
  } else {
    laws = {BaseLaw::bingham, BaseLaw::bouc_wen};
    if (options.auto_spencer) laws.push_back(BaseLaw::spencer);
  }
  std::vector<std::pair<BaseLaw, bool>> plain;  // each law, and its transition
  for (const BaseLaw law : laws) {
    for (const bool tanh : {false, true}) {
      if (law != BaseLaw::bingham && tanh) continue;
      if (law == BaseLaw::bingham && options.transition == (tanh ? TransitionShape::linear : TransitionShape::tanh))
        continue;
      plain.emplace_back(law, tanh);
    }
  }
  {
    std::vector<LawFit> fitted(plain.size());
    const CalibrateOptions each = side_by_side(options, plain.size());
    parallel_for(plain.size(), options.threads, [&](std::size_t j) {
      fitted[j] = fit_law(p, plain[j].first, plain[j].second, each);
      fitted[j].record_gaps = baseline_gaps(fitted[j].baseline, records, options.smoothing_half_window_s);
    });
    for (LawFit& f : fitted) res.fits.push_back(std::move(f));
  }

  // BIC with a common effective sample count (the smallest of the fits'), so
  // that the forms are judged on the same evidence.
  const auto score = [&res] {
    double n_eff = res.fits.front().n_eff;
    for (const auto& f : res.fits) n_eff = std::min(n_eff, f.n_eff);
    for (auto& f : res.fits) {
      std::size_t k = 0;
      for (const auto& q : f.params) k += q.fitted ? 1 : 0;
      f.bic = bic(f.rss, f.samples, n_eff, k);
    }
  };
  score();

  // Each plain form again with each extra in turn (baseline.hpp): first the
  // transition time (Bingham only), then the lost motion at reversals, each
  // on top of what was kept before. An extra is kept only when it earns its
  // parameters: a BIC lower by kBicMargin, parameters a fit can tell from
  // none (off their search bounds), a plausible size, and a lower RMS gap on
  // check records it was not fitted to (or, without them, on each of the
  // records' motions left out in turn). With neither it is reported, not
  // kept: on the fitted records alone any extra freedom wins against a
  // model-form error (a smooth tanh transition took the lost motion at
  // ΔBIC 10^4).
  //
  // The form is chosen only after its extras (below): a plain form can
  // stand in for an extra of another (the tanh turn-over of Eq. 4.4 records
  // with a lost motion wins against plain Eq. 4.4, ΔBIC 95), and the extras
  // fitted on that wrong shape would then be lost.
  const double amp_min = *std::min_element(p.half_range_m.begin(), p.half_range_m.end());
  // Without check records, the records' own motions judge in turn: each
  // motion left out, the candidate fitted again to the others from its fit
  // to all (fit_law's start_at), and the gaps of the left-out records pooled
  // over the motions. The same question as check records ask (does it hold
  // on a motion it was not fitted to?), on every motion the user measured.
  struct Fold {
    std::vector<MeasuredData> train_records;  ///< kept alive: `train` refers to their samples
    Prepared train;
    std::vector<MeasuredData> held;
  };
  std::vector<Fold> folds;
  if (check.empty() && options.cross_validate && records.size() >= 2) {
    std::vector<std::vector<std::size_t>> groups = cross_validation_folds(records, options.smoothing_half_window_s);
    if (groups.size() >= 2) {
      folds.resize(groups.size());
      for (std::size_t k = 0; k < groups.size(); ++k) {
        Fold& f = folds[k];
        for (std::size_t i = 0; i < records.size(); ++i) {
          if (std::find(groups[k].begin(), groups[k].end(), i) != groups[k].end())
            f.held.push_back(records[i]);
          else
            f.train_records.push_back(records[i]);
        }
        f.train = prepare(f.train_records, options);
      }
      res.cross_validation_groups = std::move(groups);
      const std::size_t motions =
          folds.size() < kMaxCrossValidationFolds ? folds.size()
                                                  : motion_groups(records, options.smoothing_half_window_s).size();
      res.notes.push_back(
          motions == folds.size()
              ? "no --check records: the extras and the form judged by leaving out each of the records' " +
                    std::to_string(folds.size()) + " motions in turn (fitted to the others, the gap taken on it)"
              : "no --check records: the extras and the form judged by leaving out the records' " +
                    std::to_string(motions) + " motions in " + std::to_string(folds.size()) +
                    " folds, each in turn (motions dealt to the folds in order of stroke; fitted to the others, the "
                    "gap taken on the fold)");
    }
  }
  const bool judged = !check.empty() || !folds.empty();
  // RMS gap of fit i on the check records (or over the left-out motions),
  // computed once per fit.
  std::map<std::size_t, double> check_gaps;
  const auto check_gap = [&](std::size_t i) {
    const auto [at, fresh] = check_gaps.try_emplace(i, 0.0);
    if (!fresh) return at->second;
    LawFit& fit = res.fits[i];
    fit.held_out_gaps.clear();
    fit.held_out_sources.clear();
    if (folds.empty()) {
      fit.held_out_gaps = baseline_gaps(fit.baseline, check, options.smoothing_half_window_s);
      for (const MeasuredData& c : check) fit.held_out_sources.push_back(c.source);
    } else {
      const Baseline& b = fit.baseline;
      std::vector<std::vector<double>> held(folds.size());
      const CalibrateOptions each = side_by_side(options, folds.size());
      parallel_for(folds.size(), options.threads, [&](std::size_t k) {
        const LawFit g = fit_law(folds[k].train, b.law, b.tanh_transition, each, nullptr, extras_of(b), &b);
        held[k] = baseline_gaps(g.baseline, folds[k].held, options.smoothing_half_window_s);
      });
      for (std::size_t k = 0; k < folds.size(); ++k) {
        fit.held_out_gaps.insert(fit.held_out_gaps.end(), held[k].begin(), held[k].end());
        for (const MeasuredData& h : folds[k].held) fit.held_out_sources.push_back(h.source);
      }
    }
    at->second = rms_over_records(fit.held_out_gaps);
    return at->second;
  };
  const std::string judge = folds.empty() ? "the check records" : "the left-out motions";
  // Tries `add` on top of fit `cur`; returns the index of the fit kept.
  const auto try_extra = [&](std::size_t cur, Extras add, const std::string& implausible) -> std::size_t {
    std::vector<Slot> slots;  // the new extra's parameters
    if (add.transition_time) slots.push_back(kTau);
    if (add.lost_motion) slots.insert(slots.end(), {kPlay, add.viscous_play ? kBand : kShare});
    // The yield law's exponent must be identified; the viscous law's may end
    // on its bound (a viscous coefficient that hardly changes with the
    // current leaves it free), reported as such below.
    if (add.current_exponent) slots.push_back(kYq);
    if (add.stiffness) slots.push_back(kK0);
    if (add.viscous_exponent) slots.push_back(kViscExp);
    if (add.series_compliance) slots.push_back(kSeries);
    const LawFit from = res.fits[cur];
    Extras extras = extras_of(from.baseline);
    extras.transition_time = extras.transition_time || add.transition_time;
    extras.lost_motion = extras.lost_motion || add.lost_motion;
    extras.viscous_play = extras.viscous_play || add.viscous_play;
    extras.current_exponent = extras.current_exponent || add.current_exponent;
    extras.stiffness = extras.stiffness || add.stiffness;
    extras.viscous_exponent = extras.viscous_exponent || add.viscous_exponent;
    extras.series_compliance = extras.series_compliance || add.series_compliance;
    LawFit f = fit_law(p, from.baseline.law, from.baseline.tanh_transition, options, &from, extras);
    f.record_gaps = baseline_gaps(f.baseline, records, options.smoothing_half_window_s);
    res.fits.push_back(std::move(f));
    score();
    const LawFit& x = res.fits.back();
    const LawFit& c = res.fits[cur];
    const std::string name = baseline_form_name(x.baseline);
    bool plausible = true;
    for (const ParamEstimate& q : x.params)
      for (const Slot slot : slots)
        if (q.name == kSlotName[slot] && q.at_bound) plausible = false;
    if (add.lost_motion &&
        !(x.baseline.lost_motion_m_per_n * std::fabs(x.baseline.yield_n.at(top_current_a(p))) < 2.0 * amp_min))
      plausible = false;
    if (!plausible) {
      res.notes.push_back(name + ": not kept (" + implausible + ")");
      return cur;
    }
    const std::string delta = io::format_number("%.1f", c.bic - x.bic);
    if (c.bic - x.bic < kBicMargin) {
      res.notes.push_back(name + ": not kept, BIC lower by " + delta + " only (needs " +
                          io::format_number("%.0f", kBicMargin) + ")");
      return cur;
    }
    if (!judged) {
      res.notes.push_back(name + ": not kept, lower BIC on the fitted records (delta " + delta +
                          ") but no --check records or second motion to show that it generalizes");
      return cur;
    }
    const double with = check_gap(res.fits.size() - 1);
    const double without = check_gap(cur);
    const std::string numbers = "RMS gap on " + judge + " " + io::format_number("%.4f", with) + " against " +
                                io::format_number("%.4f", without) + " without";
    if (with < without) {
      res.notes.push_back(name + ": kept, it generalizes (BIC delta " + delta + "; " + numbers + ")");
      return res.fits.size() - 1;
    }
    res.notes.push_back(name + ": not kept, lower BIC on the fitted records but it does not generalize (" + numbers +
                        ")");
    return cur;
  };
  const std::size_t n_plain = res.fits.size();
  std::vector<std::size_t> finals;
  for (std::size_t i = 0; i < n_plain; ++i) {
    std::size_t cur = i;
    if (res.fits[cur].baseline.law == BaseLaw::spencer) {
      // Its own pre-yield and roll-off are what the extras add to the others.
      finals.push_back(cur);
      continue;
    }
    if (options.transition_time && res.fits[cur].baseline.law == BaseLaw::bingham)
      cur = try_extra(cur, {.transition_time = true}, "the transition time on its search bound");
    if (options.series_compliance && res.fits[cur].baseline.law == BaseLaw::bingham)
      cur = try_extra(cur, {.series_compliance = true}, "the series compliance on its search bound");
    if (options.lost_motion) {
      // Each form of the force inside the play asked for, tried on the same
      // fit; of those kept, the lower gap on the check records.
      const LostMotionForm form = options.lost_motion_form;
      std::size_t kept = cur;
      for (const bool viscous : {false, true}) {
        if (form == (viscous ? LostMotionForm::share : LostMotionForm::viscous)) continue;
        const std::size_t k = try_extra(cur, {.lost_motion = true, .viscous_play = viscous},
                                        "a lost-motion parameter on its bound, or a play as wide as the stroke");
        if (k != cur && (kept == cur || check_gap(k) < check_gap(kept))) kept = k;
      }
      cur = kept;
    }
    // The law's shape (baseline.hpp): only with check records or motions to
    // leave out, the only ones that can keep it (each is a fit of its own on
    // every record).
    if (res.fits[cur].baseline.law == BaseLaw::bingham && judged) {
      if (options.current_exponent && p.currents_a.size() >= 3)
        cur = try_extra(cur, {.current_exponent = true}, "a current exponent on its search bound");
      if (options.viscous_exponent)
        cur = try_extra(cur, {.viscous_exponent = true}, "the viscous exponent on its search bound");
      if (options.stiffness) cur = try_extra(cur, {.stiffness = true}, "the stiffness on its search bound");
    }
    finals.push_back(cur);
  }
  const bool bingham_fitted = std::any_of(res.fits.begin(), res.fits.end(),
                                          [](const LawFit& f) { return f.baseline.law == BaseLaw::bingham; });
  if (!judged && bingham_fitted && (options.current_exponent || options.viscous_exponent || options.stiffness))
    res.notes.push_back(
        "the Bingham law's current exponent, viscous exponent and stiffness: not fitted (no --check records or second "
        "motion to show that they generalize)");
  // Without check records or a second motion no extra is kept and the
  // plain forms are chosen by BIC. With them, each form with its kept
  // extras is judged on them too: the BIC of the fitted records alone prefers whichever form's
  // extra absorbs the most of a model-form error (on the laboratory damper,
  // Bouc–Wen with a lost motion by ΔBIC 197, at an RMS gap on held-out
  // records of 0.204 against 0.153).
  score();
  const auto better = [&](std::size_t a, std::size_t b) {
    return !judged ? res.fits[a].bic < res.fits[b].bic : check_gap(a) < check_gap(b);
  };
  // Spencer's model, with its eleven parameters, is chosen by `auto` only on
  // check records: on the fitted records alone its freedom wins by BIC
  // against the others' model-form error whether or not it generalizes
  // (as for the extras above).
  // Cross-validation does not judge it in `auto`: each motion left out
  // would be a fit of its own through the stiff ODE (tens of minutes on the
  // laboratory's fifteen records), so `auto` still asks check records for it.
  const bool spencer_choosable = options.law.has_value() || !check.empty();
  std::vector<std::size_t> candidates;
  for (const std::size_t i : finals)
    if (spencer_choosable || res.fits[i].baseline.law != BaseLaw::spencer) candidates.push_back(i);
  if (candidates.size() < finals.size())
    res.notes.push_back(std::string("spencer: fitted and reported, not chosen: no --check records to show that it "
                                    "generalizes") +
                        (folds.empty() ? "" : " (auto does not cross-validate it: a fit through its ODE per motion "
                                              "left out)"));
  res.chosen = candidates.front();
  if (candidates.size() > 1)
    for (const std::size_t i : candidates)
      if (better(i, res.chosen)) res.chosen = i;
  {
    const LawFit& c = res.fits[res.chosen];
    const std::string given = options.law ? std::string("law given: ") + base_law_name(*options.law) : "";
    if (res.fits.size() == 1) {
      res.choice_reason = given;
    } else {
      std::string& why = res.choice_reason;
      why = (given.empty() ? "" : given + "; ") + baseline_form_name(c.baseline);
      if (!judged) {
        why += ": the form of lowest BIC";
      } else {
        why += ": of the forms each with the extras that generalized, the lowest RMS gap on " + judge + " (" +
               io::format_number("%.4f", check_gap(res.chosen));
        for (const std::size_t i : candidates)
          if (i != res.chosen)
            why += "; " + io::format_number("%.4f", check_gap(i)) + " for " + baseline_form_name(res.fits[i].baseline);
        why += ")";
      }
      why += " (BIC " + io::format_number("%.1f", c.bic);
      for (std::size_t i = 0; i < res.fits.size(); ++i) {
        if (i == res.chosen) continue;
        const LawFit& o = res.fits[i];
        why += "; " + io::format_number("%.1f", o.bic) + " for " + baseline_form_name(o.baseline) + ", delta " +
               io::format_number("%.1f", o.bic - c.bic);
      }
      why += ")";
    }
  }
  for (const LawFit& f : res.fits) {
    for (const ParamEstimate& q : f.params) {
      if (q.at_bound)
        res.notes.push_back(baseline_form_name(f.baseline) + ": " + q.name + " = " +
                            io::format_number("%.4g", q.value) +
                            " ended on its search bound (not identified by these records; its sigma is not "
                            "meaningful)");
    }
  }
  const ValidityRange fitted_range = validity_range(records, options.smoothing_half_window_s);
  if (!check.empty() && check_repeats_fitted_motions(records, check, options.smoothing_half_window_s))
    res.notes.push_back(
        "every check record repeats the amplitude and frequency of a fitted record: the extras and the form were "
        "chosen on motions like the fitted ones, which says little about other amplitudes or frequencies (check "
        "records of another amplitude and frequency test that; README, discrepancy section)");
  // The expected gap covers the records a form was judged on but not fitted
  // to: the check records, which the final fit meets as a later record; or
  // the motions left out, each fitted to the others, from three motions on.
  // With two, each fold is one motion's fit extrapolated to the other, far
  // worse than the fit to both on a third (laboratory damper, 2 mm and
  // 25 mm families: 41 % and 53 % at most left out, against 10–22 % of the
  // fit to both on the 5 mm family), and says little of that fit.
  const bool held_out_expected = !check.empty() || folds.size() >= kExpectedGapMinMotions;
  // The chosen form's gaps there, even where no comparison asked for them
  // (one form, no extra to judge); not Spencer's by cross-validation, a fit
  // through its ODE per motion (as for auto's choice above).
  if (held_out_expected && (folds.empty() || res.fits[res.chosen].baseline.law != BaseLaw::spencer))
    check_gap(res.chosen);
  for (auto& f : res.fits) {
    f.baseline.range = fitted_range;
    f.baseline.expected_gap = *std::max_element(f.record_gaps.begin(), f.record_gaps.end());
    f.baseline.expected_gap_basis = GapBasis::calibration_records;
    if (held_out_expected && !f.held_out_gaps.empty()) {
      f.baseline.expected_gap =
          std::max(f.baseline.expected_gap, *std::max_element(f.held_out_gaps.begin(), f.held_out_gaps.end()));
      f.baseline.expected_gap_basis = folds.empty() ? GapBasis::check_records : GapBasis::left_out_motions;
    }
  }
  return res;
}

}  // namespace mrd::discrepancy
