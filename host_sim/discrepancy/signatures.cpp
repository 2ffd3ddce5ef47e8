#include "host_sim/discrepancy/signatures.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string_view>

#include "host_sim/discrepancy/motion_timescale.hpp"

namespace mrd::discrepancy {
namespace {

struct Signature {
  const char* name;
  const char* looks_like;
};

constexpr Signature kSignatures[] = {
    {"offset", "a constant force (a zero offset)"},
    {"drift", "a slow drift over the record"},
    {"stiffness", "a force proportional to displacement (a spring)"},
    {"lag", "a lag: the measured force follows the model late or early"},
    {"force_scale", "a force-scale error: the model too strong or too weak"},
    {"asymmetry", "an asymmetry: extension and compression differ"},
    {"low_velocity_loop", "a loop at low velocity: force kept through reversals (pre-yield hysteresis)"},
    {"transition_shape", "the force rising with velocity near zero otherwise than Eq. 4.4"},
    {"current_law", "the force depending on the current otherwise than the current law"},
    {"inertia", "a force in phase with acceleration (inertia or fluid compressibility)"},
    {"filter_shape", "a filter rather than a delay: the error follows the model force's curvature"},
    {"current_lag_short", "the force following current changes late by about 0.1 s (a slower coil)"},
    {"current_lag_long", "the force following current changes late by about 1 s (a much slower coil)"},
    {"volume_recovery_short",
     "a force deficit recovering over the first ~3 cm of rod travel (settled fluid remixing quickly)"},
    {"volume_recovery_long", "a force deficit recovering over ~30 cm of rod travel (settled fluid remixing)"},
    {"heating", "a force change growing with the energy dissipated so far (the fluid heating)"},
};
constexpr std::size_t kCount = std::size(kSignatures);

/// Time constants of the current-lag signatures, s: Eq. 4.5's fast and slow lags are 0.03 and 0.7 s.
constexpr double kCurrentLagShort_s = 0.1;
constexpr double kCurrentLagLong_s = 1.0;
/// Rod travel over which the volume-recovery signatures decay, m (0.3 and 3 L through the
/// thesis damper's 0.01062 m² flow area).
constexpr double kRecoveryTravelShort_m = 0.03;
constexpr double kRecoveryTravelLong_m = 0.3;

/// What the history-dependent signatures are built from, per sample: the
/// current through two further first-order lags, the rod travel ∫|v| dt and
/// the dissipated energy ∫|F v| dt since the record's start.
struct Histories {
  std::vector<double> current_short_a, current_long_a, travel_m, energy_j;
};

Histories histories(const SignatureInput& in) {
  const std::size_t n = in.time_s.size();
  Histories h;
  h.current_short_a.resize(n);
  h.current_long_a.resize(n);
  h.travel_m.resize(n);
  h.energy_j.resize(n);
  double is = in.current_a[0], il = in.current_a[0], s = 0.0, e = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) {
      // Exact for a current held over the step.
      const double dt = std::max(in.time_s[k] - in.time_s[k - 1], 0.0);
      is += (1.0 - std::exp(-dt / kCurrentLagShort_s)) * (in.current_a[k - 1] - is);
      il += (1.0 - std::exp(-dt / kCurrentLagLong_s)) * (in.current_a[k - 1] - il);
      s += std::fabs(in.vel_m_s[k - 1]) * dt;
      e += std::fabs(in.model_force_n[k - 1] * in.vel_m_s[k - 1]) * dt;
    }
    h.current_short_a[k] = is;
    h.current_long_a[k] = il;
    h.travel_m[k] = s;
    h.energy_j[k] = e;
  }
  return h;
}

/// Signal `j` at sample k.
Eigen::MatrixXd signals(const SignatureInput& in, std::span<const std::size_t> index, std::span<const double> dfdt,
                        std::span<const double> d2fdt2, std::span<const double> acc, const Histories& hist) {
  const std::size_t n = in.time_s.size();
  const double t0 = in.time_s.front();
  const double span_s = std::max(in.time_s.back() - t0, 1e-9);
  double i_max = 0.0;
  for (const double i : in.current_a) i_max = std::max(i_max, std::fabs(i));
  const double band = 3.0 * std::max(in.low_velocity_band_m_s, 1e-6);
  const double e_total = hist.energy_j.back();
  Eigen::MatrixXd m(static_cast<Eigen::Index>(index.size()), static_cast<Eigen::Index>(kCount));
  for (std::size_t r = 0; r < index.size(); ++r) {
    const std::size_t k = std::min(index[r], n - 1);
    const double v = in.vel_m_s[k];
    const double f = in.model_force_n[k];
    const double w = std::max(0.0, 1.0 - std::fabs(v) / band);
    const double sa = acc[k] > 0.0 ? 1.0 : (acc[k] < 0.0 ? -1.0 : 0.0);
    const double sv = v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0);
    const auto row = static_cast<Eigen::Index>(r);
    m(row, 0) = 1.0;
    m(row, 1) = (in.time_s[k] - t0) / span_s - 0.5;
    m(row, 2) = in.disp_m[k];
    m(row, 3) = dfdt[k];
    m(row, 4) = f;
    m(row, 5) = v > 0.0 ? f : 0.0;
    m(row, 6) = -sa * w;
    m(row, 7) = sv * w;
    m(row, 8) = i_max > 0.0 ? f * std::fabs(in.current_a[k]) / i_max : 0.0;
    m(row, 9) = acc[k];
    m(row, 10) = d2fdt2[k];
    // A slower coil: ∂F/∂i times the current's extra lag, ∂F/∂i ∝ F (the current laws).
    m(row, 11) = i_max > 0.0 ? f * (hist.current_short_a[k] - in.current_a[k]) / i_max : 0.0;
    m(row, 12) = i_max > 0.0 ? f * (hist.current_long_a[k] - in.current_a[k]) / i_max : 0.0;
    // Settling: a force-scale deficit shrinking with displaced volume (rod travel).
    m(row, 13) = f * std::exp(-hist.travel_m[k] / kRecoveryTravelShort_m);
    m(row, 14) = f * std::exp(-hist.travel_m[k] / kRecoveryTravelLong_m);
    // Heating: a force-scale change in proportion to the energy dissipated so far.
    m(row, 15) = e_total > 0.0 ? f * hist.energy_j[k] / e_total : 0.0;
  }
  return m;
}

Eigen::VectorXd residual_at(const SignatureInput& in, std::span<const std::size_t> index) {
  Eigen::VectorXd r(static_cast<Eigen::Index>(index.size()));
  for (std::size_t j = 0; j < index.size(); ++j) r(static_cast<Eigen::Index>(j)) = in.residual_n[index[j]];
  return r;
}

/// Least squares on the columns `cols` of `a_train`; share of the held-out
/// power removed, and the coefficients. Columns that do not vary are dropped.
double held_out_share(const Eigen::MatrixXd& a_train, const Eigen::VectorXd& r_train, const Eigen::MatrixXd& a_test,
                      const Eigen::VectorXd& r_test, const std::vector<Eigen::Index>& cols, Eigen::VectorXd& coef) {
  std::vector<Eigen::Index> used;
  for (const Eigen::Index c : cols) {
    if (a_train.col(c).norm() > 0.0) used.push_back(c);
  }
  coef = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(cols.size()));
  const double power = r_test.squaredNorm();
  if (used.empty() || power <= 0.0) return 0.0;
  Eigen::MatrixXd at(a_train.rows(), static_cast<Eigen::Index>(used.size()));
  Eigen::MatrixXd ae(a_test.rows(), static_cast<Eigen::Index>(used.size()));
  for (std::size_t j = 0; j < used.size(); ++j) {
    // Columns scaled to unit RMS on the training samples: the solve is then well conditioned.
    const double s = a_train.col(used[j]).norm() / std::sqrt(static_cast<double>(a_train.rows()));
    at.col(static_cast<Eigen::Index>(j)) = a_train.col(used[j]) / s;
    ae.col(static_cast<Eigen::Index>(j)) = a_test.col(used[j]) / s;
  }
  const Eigen::VectorXd beta = at.colPivHouseholderQr().solve(r_train);
  const double after = (r_test - ae * beta).squaredNorm();
  for (std::size_t j = 0; j < used.size(); ++j) {
    const auto it = std::find(cols.begin(), cols.end(), used[j]);
    const double s = a_train.col(used[j]).norm() / std::sqrt(static_cast<double>(a_train.rows()));
    coef(it - cols.begin()) = beta(static_cast<Eigen::Index>(j)) / s;
  }
  return 1.0 - after / power;
}

/// Index of the quantile bin of `x` among `edges` (ascending).
std::size_t bin_of(double x, const std::vector<double>& edges) {
  return static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), x) - edges.begin());
}

/// `count − 1` inner quantile edges of `values` at the samples `index`.
std::vector<double> quantile_edges(std::span<const double> values, std::span<const std::size_t> index,
                                   std::size_t count) {
  std::vector<double> v;
  v.reserve(index.size());
  for (const std::size_t k : index) v.push_back(values[k]);
  std::sort(v.begin(), v.end());
  std::vector<double> edges;
  for (std::size_t b = 1; b < count && !v.empty(); ++b) edges.push_back(v[b * v.size() / count]);
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

constexpr std::size_t kVelocityBins = 12;
constexpr std::size_t kDisplacementBins = 4;
constexpr std::size_t kCurrentBins = 3;

/// The state map's held-out share (see signatures.hpp).
double state_map_share(const SignatureInput& in, std::span<const double> acc, std::span<const std::size_t> train,
                       std::span<const std::size_t> held_out) {
  const auto ev = quantile_edges(in.vel_m_s, train, kVelocityBins);
  const auto ex = quantile_edges(in.disp_m, train, kDisplacementBins);
  const auto ei = quantile_edges(in.current_a, train, kCurrentBins);
  const auto cell = [&](std::size_t k) {
    const std::size_t a = acc[k] >= 0.0 ? 1 : 0;
    return ((bin_of(in.vel_m_s[k], ev) * (kDisplacementBins + 1) + bin_of(in.disp_m[k], ex)) * 2 + a) *
               (kCurrentBins + 1) +
           bin_of(in.current_a[k], ei);
  };
  const std::size_t cells = (kVelocityBins + 1) * (kDisplacementBins + 1) * 2 * (kCurrentBins + 1);
  std::vector<double> sum(cells, 0.0);
  std::vector<double> count(cells, 0.0);
  for (const std::size_t k : train) {
    sum[cell(k)] += in.residual_n[k];
    count[cell(k)] += 1.0;
  }
  double power = 0.0;
  double after = 0.0;
  for (const std::size_t k : held_out) {
    const std::size_t c = cell(k);
    const double mean = count[c] > 0.0 ? sum[c] / count[c] : 0.0;
    power += in.residual_n[k] * in.residual_n[k];
    after += (in.residual_n[k] - mean) * (in.residual_n[k] - mean);
  }
  return power > 0.0 ? 1.0 - after / power : 0.0;
}

}  // namespace

SignatureAnalysis analyse_residual(const SignatureInput& in, std::span<const std::size_t> train,
                                   std::span<const std::size_t> held_out) {
  SignatureAnalysis out;
  if (in.time_s.size() < 3 || train.empty() || held_out.empty()) return out;
  const std::vector<double> dfdt = central_difference(in.time_s, in.model_force_n);
  const std::vector<double> d2fdt2 = central_difference(in.time_s, dfdt);
  const std::vector<double> acc = central_difference(in.time_s, in.vel_m_s);
  const Histories hist = histories(in);
  const Eigen::MatrixXd a_train = signals(in, train, dfdt, d2fdt2, acc, hist);
  const Eigen::MatrixXd a_test = signals(in, held_out, dfdt, d2fdt2, acc, hist);
  const Eigen::VectorXd r_train = residual_at(in, train);
  const Eigen::VectorXd r_test = residual_at(in, held_out);
  Eigen::VectorXd coef;
  std::vector<Eigen::Index> all;
  const auto counted = [&](std::size_t j) {
    const std::string_view name = kSignatures[j].name;
    if (in.model_has_coil_lag && name.starts_with("current_lag")) return false;
    if (in.model_has_settling && name.starts_with("volume_recovery")) return false;
    if (in.model_has_fade && name == "heating") return false;
    if (in.offset_wanders && name == "offset") return false;
    return true;
  };
  std::vector<double> counted_shares;
  for (std::size_t j = 0; j < kCount; ++j) {
    if (counted(j)) all.push_back(static_cast<Eigen::Index>(j));
    SignatureStat s;
    s.name = kSignatures[j].name;
    s.looks_like = kSignatures[j].looks_like;
    s.held_out_share = held_out_share(a_train, r_train, a_test, r_test, {static_cast<Eigen::Index>(j)}, coef);
    s.coefficient = coef(0);
    if (counted(j)) counted_shares.push_back(s.held_out_share);
    out.signatures.push_back(std::move(s));
  }
  // All together, or the best single one: a joint fit of many columns can do worse on the held-out
  // blocks than one of them alone (columns alike on the training blocks, such as F, F·E/E_end and
  // F·exp(−S/0.3 m), take large opposite coefficients), and each single share is itself judged there.
  out.structured_share = held_out_share(a_train, r_train, a_test, r_test, all, coef);
  for (const double share : counted_shares) out.structured_share = std::max(out.structured_share, share);
  SignatureStat map;
  map.name = "state_map";
  map.looks_like = "an error that repeats with the damper's state (velocity, displacement, direction, current)";
  map.held_out_share = state_map_share(in, acc, train, held_out);
  out.structured_share = std::max(out.structured_share, map.held_out_share);
  out.signatures.push_back(std::move(map));
  std::stable_sort(out.signatures.begin(), out.signatures.end(),
                   [](const SignatureStat& a, const SignatureStat& b) { return a.held_out_share > b.held_out_share; });
  return out;
}

}  // namespace mrd::discrepancy
