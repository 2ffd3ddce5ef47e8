#include "host_sim/discrepancy/filter_check.hpp"

#include <algorithm>
#include <cmath>

namespace mrd::discrepancy {
namespace {

/// Low-pass time constants searched: a log grid, then golden-section refinement.
constexpr double kTauMin_s = 2e-4;
constexpr double kTauMax_s = 0.2;
constexpr int kTauGrid = 36;
constexpr int kGoldenSteps = 24;

double rss_over(std::span<const double> measured, std::span<const double> model, std::span<const std::size_t> index) {
  double s = 0.0;
  for (const std::size_t k : index) s += (measured[k] - model[k]) * (measured[k] - model[k]);
  return s;
}

}  // namespace

void first_order_lowpass(std::span<const double> time_s, std::span<const double> u, double tau_s,
                         std::vector<double>& y) {
  const std::size_t n = u.size();
  y.resize(n);
  if (n == 0) return;
  y[0] = u[0];
  for (std::size_t k = 1; k < n; ++k) {
    const double h = time_s[k] - time_s[k - 1];
    if (!(h > 0.0) || !(tau_s > 0.0)) {
      y[k] = u[k];
      continue;
    }
    // Ramp input u(t) = u0 + (u1 − u0) t/h over the step: y(h) = e y0 + (1 − e) u0 + (u1 − u0)(1 − τ(1 − e)/h).
    const double e = std::exp(-h / tau_s);
    y[k] = e * y[k - 1] + (1.0 - e) * u[k - 1] + (u[k] - u[k - 1]) * (1.0 - tau_s * (1.0 - e) / h);
  }
}

FilterCheck compare_delay_with_lowpass(const DamperModel& model, const EffectSet& set, std::span<const double> params,
                                       std::span<const double> measured_force_n,
                                       std::span<const std::size_t> fit_index,
                                       std::span<const std::size_t> held_index, double n_eff, double min_delta_bic) {
  FilterCheck out;
  const auto off = set.offset(Effect::time_delay);
  if (!off) return out;
  out.checked = true;
  out.delay_s = params[*off];
  ModelWorkspace ws;
  std::vector<double> with_delay;
  model.simulate(set, params, ws, with_delay);
  std::vector<double> no_delay_params(params.begin(), params.end());
  no_delay_params[*off] = 0.0;
  std::vector<double> undelayed;
  model.simulate(set, no_delay_params, ws, undelayed);
  const auto& t = model.input().time_s;

  std::vector<double> filtered;
  const auto rss_at = [&](double tau_s) {
    first_order_lowpass(t, undelayed, tau_s, filtered);
    return rss_over(measured_force_n, filtered, fit_index);
  };
  // Log grid, then golden section on ln τ between the best point's neighbours.
  const double l0 = std::log(kTauMin_s);
  const double step = (std::log(kTauMax_s) - l0) / (kTauGrid - 1);
  int best = 0;
  double best_rss = 0.0;
  for (int g = 0; g < kTauGrid; ++g) {
    const double r = rss_at(std::exp(l0 + step * g));
    if (g == 0 || r < best_rss) {
      best = g;
      best_rss = r;
    }
  }
  double a = l0 + step * std::max(best - 1, 0);
  double b = l0 + step * std::min(best + 1, kTauGrid - 1);
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - phi * (b - a);
  double d = a + phi * (b - a);
  double rc = rss_at(std::exp(c));
  double rd = rss_at(std::exp(d));
  for (int it = 0; it < kGoldenSteps; ++it) {
    if (rc < rd) {
      b = d;
      d = c;
      rd = rc;
      c = b - phi * (b - a);
      rc = rss_at(std::exp(c));
    } else {
      a = c;
      c = d;
      rc = rd;
      d = a + phi * (b - a);
      rd = rss_at(std::exp(d));
    }
  }
  double tau_s = std::exp(l0 + step * best);
  if (std::min(rc, rd) < best_rss) {
    tau_s = std::exp(rc < rd ? c : d);
    best_rss = std::min(rc, rd);
  }
  out.tau_s = tau_s;

  const double rss_delay = rss_over(measured_force_n, with_delay, fit_index);
  first_order_lowpass(t, undelayed, tau_s, filtered);
  const double held_delay = rss_over(measured_force_n, with_delay, held_index);
  const double held_lowpass = rss_over(measured_force_n, filtered, held_index);
  out.delta_bic = n_eff * std::log(std::max(rss_delay, 1e-300) / std::max(best_rss, 1e-300));
  out.held_out_reduction = held_delay > 0.0 ? 1.0 - held_lowpass / held_delay : 0.0;
  out.lowpass_better = out.delta_bic >= min_delta_bic && out.held_out_reduction > 0.0;
  return out;
}

}  // namespace mrd::discrepancy
