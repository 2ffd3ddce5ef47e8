#pragma once
/// Lognormal fragility functions fitted by maximum likelihood to counts of
/// exceedance at a set of intensity levels (Baker 2015, "Efficient analytical
/// fragility function fitting using dynamic structural analysis data",
/// Earthquake Spectra 31(1), Eq. 1 and 11):
/// <pre>
///   P(LS | IM = x) = Φ( ln(x/θ) / β )
///   (θ̂, β̂) = argmax Σ_j [ z_j ln Φ(ln(x_j/θ)/β) + (n_j − z_j) ln(1 − Φ(ln(x_j/θ)/β)) ]
/// </pre>
/// n_j runs at level x_j, z_j of them exceeding the limit state (the binomial
/// coefficients of the likelihood do not depend on θ, β and are left out).
/// Confidence bands by a nonparametric bootstrap over the records (seeded).

#include <cstdint>
#include <vector>

namespace mrd::risk {

/// Standard normal cumulative distribution Φ(z).
double normal_cdf(double z) noexcept;

/// Counts at one intensity level.
struct LevelCounts {
  double im = 0.0;      ///< intensity (PGA in g here), > 0
  unsigned runs = 0;    ///< n_j
  unsigned exceed = 0;  ///< z_j ≤ n_j
};

enum class FitStatus {
  kFitted,        ///< θ, β from the likelihood
  kNoneExceeded,  ///< no run exceeded: P ≡ 0 over the levels (θ = +∞)
  kAllExceeded,   ///< every run exceeded: P ≡ 1 over the levels (θ = 0)
};

/// "fitted" | "none_exceeded" | "all_exceeded".
const char* fit_status_name(FitStatus s) noexcept;

struct LognormalFit {
  FitStatus status = FitStatus::kFitted;
  double median_im = 0.0;  ///< θ, same unit as LevelCounts::im
  double beta = 0.0;       ///< β, log-standard deviation
  /// P(LS | IM = im): Φ(ln(im/θ)/β); 0 or 1 for the two degenerate statuses.
  double probability(double im) const noexcept;
};

/// β is searched in [kMinBeta, kMaxBeta]. A separated data set (no exceedance
/// below some level, all above it) has its supremum at β → 0: the search stops
/// where the likelihood no longer changes in double precision, at a β of about
/// 0.01–0.02 (never below kMinBeta), with θ between the two levels.
inline constexpr double kMinBeta = 0.01;
inline constexpr double kMaxBeta = 5.0;

/// Log-likelihood of (θ, β) for the counts (without binomial coefficients).
double log_likelihood(const std::vector<LevelCounts>& levels, double median_im, double beta) noexcept;

/// Maximum-likelihood θ, β: Newton's method with step halving in the probit
/// parameters (a, b) = (−ln θ/β, 1/β), in which the log-likelihood is concave,
/// so the maximum found is the global one. Throws std::invalid_argument for a
/// level with im ≤ 0 or exceed > runs.
LognormalFit fit_lognormal_mle(const std::vector<LevelCounts>& levels);

/// Exceedance of each run: exceed[level][record] (1 = exceeded), the same
/// records at every level.
using ExceedanceTable = std::vector<std::vector<std::uint8_t>>;

/// Percentile band of P(LS | IM) at given intensities.
struct FragilityBand {
  std::vector<double> im;
  std::vector<double> p_low;                   ///< 5th percentile
  std::vector<double> p_high;                  ///< 95th percentile
  double median_low = 0.0, median_high = 0.0;  ///< 5th/95th percentile of θ (+∞ when none exceeded)
  double beta_low = 0.0, beta_high = 0.0;      ///< of β over the fitted resamples
};

/// Nonparametric bootstrap: `resamples` draws of the records with
/// replacement (std::mt19937_64 seeded by `seed`, indices from the top bits,
/// identical on every platform), each refitted; percentiles by the
/// nearest-rank rule. `levels_im` gives the intensity of each row of `table`.
FragilityBand bootstrap_band(const std::vector<double>& levels_im, const ExceedanceTable& table,
                             const std::vector<double>& eval_im, unsigned resamples, std::uint64_t seed);

}  // namespace mrd::risk
