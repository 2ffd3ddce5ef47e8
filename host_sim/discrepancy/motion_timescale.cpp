#include "host_sim/discrepancy/motion_timescale.hpp"

#include <algorithm>

namespace mrd::discrepancy {

std::vector<double> mean_crossings_s(std::span<const double> time_s, std::span<const double> displacement_m) {
  std::vector<double> out;
  const std::size_t n = displacement_m.size();
  if (n < 3 || time_s.size() != n) return out;
  double mean = 0.0;
  for (const double x : displacement_m) mean += x;
  mean /= static_cast<double>(n);
  const auto [lo, hi] = std::minmax_element(displacement_m.begin(), displacement_m.end());
  const double band = 0.1 * 0.5 * (*hi - *lo);
  if (!(band > 0.0)) return out;
  int state = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double y = displacement_m[k] - mean;
    const int s = y > band ? 1 : (y < -band ? -1 : 0);
    if (s != 0 && s != state) {
      if (state != 0) out.push_back(time_s[k]);
      state = s;
    }
  }
  return out;
}

std::vector<double> central_difference(std::span<const double> time_s, std::span<const double> y) {
  const std::size_t n = std::min(time_s.size(), y.size());
  std::vector<double> d(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k > 0 ? k - 1 : 0;
    const std::size_t b = k + 1 < n ? k + 1 : n - 1;
    if (b > a && time_s[b] > time_s[a]) d[k] = (y[b] - y[a]) / (time_s[b] - time_s[a]);
  }
  return d;
}

double half_range_m(std::span<const double> displacement_m) {
  if (displacement_m.empty()) return 0.0;
  const auto [lo, hi] = std::minmax_element(displacement_m.begin(), displacement_m.end());
  return 0.5 * (*hi - *lo);
}

double dominant_frequency_hz(std::span<const double> time_s, std::span<const double> displacement_m) {
  const std::vector<double> c = mean_crossings_s(time_s, displacement_m);
  // Crossings are half a period apart: (crossings − 1) half periods between the first and the last.
  return c.size() >= 2 && c.back() > c.front() ? static_cast<double>(c.size() - 1) / (2.0 * (c.back() - c.front()))
                                               : 0.0;
}

double smoothing_half_window_for(std::span<const double> time_s, std::span<const double> displacement_m,
                                 double cap_s) {
  const std::vector<double> c = mean_crossings_s(time_s, displacement_m);
  std::vector<double> half_periods_s;
  for (std::size_t k = 1; k < c.size(); ++k) {
    const double d = c[k] - c[k - 1];
    if (d > 0.0) half_periods_s.push_back(d);
  }
  if (half_periods_s.empty()) return cap_s;
  // The kShortHalfPeriodQuantile of the half periods: the single shortest
  // of an irregular motion is a graze of the mean band, not its bandwidth.
  const auto q = static_cast<std::size_t>(kShortHalfPeriodQuantile * static_cast<double>(half_periods_s.size()));
  std::nth_element(half_periods_s.begin(), half_periods_s.begin() + static_cast<std::ptrdiff_t>(q),
                   half_periods_s.end());
  return std::min(cap_s, kSmoothingPeriodShare * 2.0 * half_periods_s[q]);
}

}  // namespace mrd::discrepancy
