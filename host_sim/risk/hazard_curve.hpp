#pragma once
/// Seismic hazard curves: the mean annual frequency λ(IM) with which the
/// intensity (PGA, g) is exceeded at a site, and the mean annual frequency
/// of exceeding a limit state,
/// <pre>
///   λ_LS = ∫ P(LS | IM = x) |dλ(x)|                              (1)
/// </pre>
/// integrated over the curve's range (log-log interpolation between its
/// points), plus the tail above its last point, P(LS | IM_max)·λ(IM_max).
///
/// File format (CSV): a header line `pga_g,annual_frequency`, then one row per
/// point, PGA in g (> 0, strictly increasing) and the annual frequency of
/// exceeding it, 1/year (> 0, strictly decreasing); at least two points.
/// Blank lines and lines starting with `#` are skipped, CRLF and a UTF-8 BOM
/// accepted. Errors: io::UsageError "<file>:<line>: field '<column>': ...".

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace mrd::risk {

struct HazardCurve {
  std::string source;                    ///< file, or the default site's description
  std::vector<double> pga_g;             ///< increasing, g
  std::vector<double> annual_frequency;  ///< λ at each point, 1/year

  /// λ(x) by log-log interpolation; beyond the ends, the end segments' power
  /// laws extended.
  double frequency_at(double pga_g_value) const;
};

/// The illustrative default site: the power law λ(x) = k0·x^−k with k = 2.5
/// and k0 set so that 0.3 g has a 10 % chance of exceedance in 50 years
/// (λ = −ln(0.9)/50 = 2.107e-3 per year), tabulated at 60 log-spaced points
/// from 0.01 g to 5 g. Not a real site: a hazard of the shape such curves have
/// over this range.
inline constexpr double kDefaultHazardSlope = 2.5;
inline constexpr double kDefaultHazardAnchorPga_g = 0.3;
inline constexpr double kDefaultHazardAnchorYears = 50.0;
inline constexpr double kDefaultHazardAnchorProbability = 0.10;
HazardCurve default_hazard_curve();

/// k0 of the default site, g^k/year.
double default_hazard_k0();

/// Parses the CSV format above; `file` names the source in messages.
HazardCurve parse_hazard_csv(std::string_view text, const std::string& file);

/// Reads the CSV format above from a regular file (at most 16 MiB).
HazardCurve read_hazard_csv(const std::filesystem::path& path);

/// Equation (1) for a probability of exceedance `p(pga_g)`: each segment of
/// the curve split in `subdivisions` log-spaced pieces, P taken at each
/// piece's geometric midpoint times the drop of λ across it (exact for the
/// log-log interpolated λ), plus the tail term. 1/year.
double limit_state_frequency(const HazardCurve& curve, const std::function<double(double)>& p, int subdivisions = 64);

}  // namespace mrd::risk
