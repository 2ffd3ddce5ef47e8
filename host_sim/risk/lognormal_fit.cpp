#include "host_sim/risk/lognormal_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

namespace mrd::risk {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// ln Φ(u); the asymptotic series below u = −30, where erfc underflows.
double log_cdf(double u) noexcept {
  if (u > -30.0) return std::log(0.5 * std::erfc(-u / std::numbers::sqrt2));
  return -0.5 * u * u - std::log(-u) - 0.5 * std::log(2.0 * std::numbers::pi);
}

/// Inverse Mills ratio φ(u)/Φ(u); its asymptote −u − 1/u below u = −30.
double mills(double u) noexcept {
  if (u > -30.0) {
    const double pdf = std::exp(-0.5 * u * u) / std::sqrt(2.0 * std::numbers::pi);
    return pdf / (0.5 * std::erfc(-u / std::numbers::sqrt2));
  }
  return -u - 1.0 / u;
}

/// The probit form u_j = a + b ln x_j, a = −ln θ/β, b = 1/β.
double probit_ll(const std::vector<LevelCounts>& levels, double a, double b) noexcept {
  double ll = 0.0;
  for (const auto& l : levels) {
    const double u = a + b * std::log(l.im);
    if (l.exceed) ll += l.exceed * log_cdf(u);
    if (l.runs > l.exceed) ll += (l.runs - l.exceed) * log_cdf(-u);
  }
  return ll;
}

struct Derivatives {
  double ga = 0.0, gb = 0.0, haa = 0.0, hab = 0.0, hbb = 0.0;
};

Derivatives probit_derivatives(const std::vector<LevelCounts>& levels, double a, double b) noexcept {
  Derivatives d;
  for (const auto& l : levels) {
    const double x = std::log(l.im);
    const double u = a + b * x;
    const double z = l.exceed, m = l.runs - l.exceed;
    const double lp = mills(u), lm = mills(-u);
    const double g = z * lp - m * lm;
    const double h = -z * lp * (u + lp) - m * lm * (-u + lm);
    d.ga += g;
    d.gb += g * x;
    d.haa += h;
    d.hab += h * x;
    d.hbb += h * x * x;
  }
  return d;
}

}  // namespace

double normal_cdf(double z) noexcept { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

const char* fit_status_name(FitStatus s) noexcept {
  switch (s) {
    case FitStatus::kFitted:
      return "fitted";
    case FitStatus::kNoneExceeded:
      return "none_exceeded";
    case FitStatus::kAllExceeded:
      return "all_exceeded";
  }
  return "unknown";
}

double LognormalFit::probability(double im) const noexcept {
  switch (status) {
    case FitStatus::kNoneExceeded:
      return 0.0;
    case FitStatus::kAllExceeded:
      return 1.0;
    case FitStatus::kFitted:
      break;
  }
  if (!(im > 0.0)) return 0.0;
  return normal_cdf(std::log(im / median_im) / beta);
}

double log_likelihood(const std::vector<LevelCounts>& levels, double median_im, double beta) noexcept {
  return probit_ll(levels, -std::log(median_im) / beta, 1.0 / beta);
}

LognormalFit fit_lognormal_mle(const std::vector<LevelCounts>& levels) {
  unsigned runs = 0, exceed = 0;
  double log_sum = 0.0;
  for (const auto& l : levels) {
    if (!(l.im > 0.0) || !std::isfinite(l.im)) throw std::invalid_argument("fit_lognormal_mle: intensity must be > 0");
    if (l.exceed > l.runs) throw std::invalid_argument("fit_lognormal_mle: more exceedances than runs");
    runs += l.runs;
    exceed += l.exceed;
    log_sum += l.runs * std::log(l.im);
  }
  LognormalFit fit;
  if (exceed == 0) {
    fit.status = FitStatus::kNoneExceeded;
    fit.median_im = kInf;
    return fit;
  }
  if (exceed == runs) {
    fit.status = FitStatus::kAllExceeded;
    return fit;
  }
  // Newton's method on the concave probit log-likelihood, with step halving;
  // b = 1/β held at a bound once a step leaves [1/kMaxBeta, 1/kMinBeta].
  const double b_min = 1.0 / kMaxBeta, b_max = 1.0 / kMinBeta;
  double b = 1.0 / 0.5;
  double a = -(log_sum / runs) * b;
  bool b_fixed = false;
  double ll = probit_ll(levels, a, b);
  for (int iter = 0; iter < 500; ++iter) {
    const Derivatives d = probit_derivatives(levels, a, b);
    double da = 0.0, db = 0.0;
    if (b_fixed) {
      da = -d.ga / d.haa;
    } else {
      const double det = d.haa * d.hbb - d.hab * d.hab;
      da = -(d.hbb * d.ga - d.hab * d.gb) / det;
      db = -(-d.hab * d.ga + d.haa * d.gb) / det;
      if (!std::isfinite(da) || !std::isfinite(db)) {
        da = d.ga;  // gradient step when the Hessian is singular
        db = d.gb;
      }
    }
    double t = 1.0;
    double a_new = a, b_new = b, ll_new = ll;
    for (int halving = 0; halving < 60; ++halving, t *= 0.5) {
      a_new = a + t * da;
      b_new = std::clamp(b + t * db, b_min, b_max);
      ll_new = probit_ll(levels, a_new, b_new);
      if (ll_new >= ll) break;
    }
    if (!(ll_new >= ll)) break;
    const double step = std::abs(a_new - a) + std::abs(b_new - b);
    if (!b_fixed && (b_new == b_max || b_new == b_min)) b_fixed = true;
    a = a_new;
    b = b_new;
    ll = ll_new;
    if (step < 1e-13 * (1.0 + std::abs(a) + std::abs(b))) break;
  }
  fit.beta = 1.0 / b;
  fit.median_im = std::exp(-a / b);
  return fit;
}

FragilityBand bootstrap_band(const std::vector<double>& levels_im, const ExceedanceTable& table,
                             const std::vector<double>& eval_im, unsigned resamples, std::uint64_t seed) {
  FragilityBand band;
  band.im = eval_im;
  band.p_low.assign(eval_im.size(), 0.0);
  band.p_high.assign(eval_im.size(), 0.0);
  if (table.empty() || table.front().empty() || resamples == 0) return band;
  const std::size_t records = table.front().size();
  std::mt19937_64 engine(seed);
  std::vector<std::vector<double>> p(eval_im.size());
  std::vector<double> medians, betas;
  std::vector<LevelCounts> levels(levels_im.size());
  std::vector<std::size_t> draw(records);
  for (unsigned s = 0; s < resamples; ++s) {
    // Index from the top 32 bits of a draw (a multiply-shift, the same on every platform).
    for (auto& d : draw) d = static_cast<std::size_t>(((engine() >> 32) * records) >> 32);
    for (std::size_t j = 0; j < levels_im.size(); ++j) {
      levels[j] = {levels_im[j], static_cast<unsigned>(records), 0};
      for (auto d : draw) levels[j].exceed += table[j][d];
    }
    const LognormalFit fit = fit_lognormal_mle(levels);
    medians.push_back(fit.median_im);
    if (fit.status == FitStatus::kFitted) betas.push_back(fit.beta);
    for (std::size_t k = 0; k < eval_im.size(); ++k) p[k].push_back(fit.probability(eval_im[k]));
  }
  const auto percentile = [](std::vector<double> v, double q) {
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(v.begin(), v.end());
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
    return v[std::max<std::size_t>(rank, 1) - 1];
  };
  for (std::size_t k = 0; k < eval_im.size(); ++k) {
    band.p_low[k] = percentile(p[k], 0.05);
    band.p_high[k] = percentile(p[k], 0.95);
  }
  band.median_low = percentile(medians, 0.05);
  band.median_high = percentile(medians, 0.95);
  band.beta_low = percentile(betas, 0.05);
  band.beta_high = percentile(betas, 0.95);
  return band;
}

}  // namespace mrd::risk
