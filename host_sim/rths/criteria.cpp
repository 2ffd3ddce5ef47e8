#include "host_sim/rths/criteria.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrd::rths {

namespace {
void same_length(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.empty()) throw std::invalid_argument("criteria: signals of different or zero length");
}
}  // namespace

double normalized_rms_error_pct(const std::vector<double>& a, const std::vector<double>& b) {
  same_length(a, b);
  double e2 = 0.0, b2 = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    e2 += (a[i] - b[i]) * (a[i] - b[i]);
    b2 += b[i] * b[i];
  }
  if (b2 == 0.0) return e2 == 0.0 ? 0.0 : HUGE_VAL;
  return 100.0 * std::sqrt(e2 / b2);
}

double normalized_peak_error_pct(const std::vector<double>& a, const std::vector<double>& b) {
  same_length(a, b);
  double e = 0.0, p = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    e = std::max(e, std::fabs(a[i] - b[i]));
    p = std::max(p, std::fabs(b[i]));
  }
  if (p == 0.0) return e == 0.0 ? 0.0 : HUGE_VAL;
  return 100.0 * e / p;
}

double cross_correlation_lag_s(const std::vector<double>& measured, const std::vector<double>& target, double dt_s,
                               int max_lag_steps) {
  same_length(measured, target);
  const long n = static_cast<long>(target.size());
  long best_lag = 0;
  double best = -HUGE_VAL;
  for (long lag = -max_lag_steps; lag <= max_lag_steps; ++lag) {
    double s = 0.0;
    for (long k = std::max(0L, -lag); k < n && k + lag < n; ++k) s += measured[static_cast<std::size_t>(k + lag)] * target[static_cast<std::size_t>(k)];
    if (s > best) {
      best = s;
      best_lag = lag;
    }
  }
  return static_cast<double>(best_lag) * dt_s;
}

Criteria evaluate_criteria(const std::vector<double>& measured_m, const std::vector<double>& target_m,
                           const std::vector<std::vector<double>>& floors_m,
                           const std::vector<std::vector<double>>& reference_floors_m, double dt_s) {
  Criteria c;
  c.j[0] = cross_correlation_lag_s(measured_m, target_m, dt_s, static_cast<int>(std::lround(0.05 / dt_s)));
  c.j[1] = normalized_rms_error_pct(measured_m, target_m);
  c.j[2] = normalized_peak_error_pct(measured_m, target_m);
  for (std::size_t f = 0; f < 3 && f < floors_m.size() && f < reference_floors_m.size(); ++f) {
    c.j[3 + 2 * f] = normalized_rms_error_pct(floors_m[f], reference_floors_m[f]);
    c.j[4 + 2 * f] = normalized_peak_error_pct(floors_m[f], reference_floors_m[f]);
  }
  return c;
}

}  // namespace mrd::rths
