#include "host_sim/discrepancy/filter_check.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mrd::discrepancy {
namespace {

/// Low-pass time constants searched: a log grid, then golden-section refinement.
constexpr double kTauMin_s = 2e-4;
constexpr double kTauMax_s = 0.2;
constexpr int kTauGrid = 36;
constexpr int kGoldenSteps = 24;
/// Shortest anti-alias filter tried behind the delay, s.
constexpr double kAntiAliasMin_s = 1e-5;
/// Longest, in sample periods: a first-order filter with its corner at a
/// quarter of the sample rate, τ = 1 / (2π f_s / 4) = 2 / (π f_s).
constexpr double kAntiAliasMaxPerSample = 2.0 / 3.14159265358979323846;

double rss_over(std::span<const double> measured, std::span<const double> model, std::span<const std::size_t> index) {
  double s = 0.0;
  for (const std::size_t k : index) s += (measured[k] - model[k]) * (measured[k] - model[k]);
  return s;
}

/// Minimizes f(ln p) over [lo, hi] (ln p): a log grid of `grid` points, then
/// golden-section refinement between the best point's neighbours. Returns
/// the best p and its value.
template <class F>
std::pair<double, double> minimize_log(F&& f, double lo, double hi, int grid, int steps) {
  const double l0 = std::log(lo);
  const double step = (std::log(hi) - l0) / (grid - 1);
  int best = 0;
  double best_v = 0.0;
  for (int g = 0; g < grid; ++g) {
    const double r = f(std::exp(l0 + step * g));
    if (g == 0 || r < best_v) {
      best = g;
      best_v = r;
    }
  }
  double a = l0 + step * std::max(best - 1, 0);
  double b = l0 + step * std::min(best + 1, grid - 1);
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - phi * (b - a);
  double d = a + phi * (b - a);
  double rc = f(std::exp(c));
  double rd = f(std::exp(d));
  for (int it = 0; it < steps; ++it) {
    if (rc < rd) {
      b = d;
      d = c;
      rd = rc;
      c = b - phi * (b - a);
      rc = f(std::exp(c));
    } else {
      a = c;
      c = d;
      rc = rd;
      d = a + phi * (b - a);
      rd = f(std::exp(d));
    }
  }
  double p = std::exp(l0 + step * best);
  if (std::min(rc, rd) < best_v) {
    p = std::exp(rc < rd ? c : d);
    best_v = std::min(rc, rd);
  }
  return {p, best_v};
}

/// Series compliances searched, as the spring's deflection at the
/// baseline's force scale: 0.1 µm to 50 mm.
constexpr double kDeflectionMin_m = 1e-7;
constexpr double kDeflectionMax_m = 0.05;

}  // namespace

void series_compliance_force(const DamperModel& model, double compliance_m_per_n, std::vector<double>& force_n) {
  const ModelInput& in = model.input();
  const Baseline& b = model.baseline();
  const std::vector<double>& current = model.baseline_current_a();
  const std::size_t n = in.time_s.size();
  std::vector<double> raw(n, 0.0);
  const double c = std::max(compliance_m_per_n, 0.0);
  const double v_tf = b.v_tf_m_s;
  // The record starts in a steady state: the spring carries the force the
  // damper gives at the actuator's velocity (starting it unloaded leaves a
  // transient that lasts until the damper first yields).
  if (n > 0)
    raw[0] = bingham_force_n(in.vel_m_s[0], b.yield_n.at(current[0]), b.viscous_ns_m.at(current[0]), v_tf);
  double y = n > 0 ? in.disp_m[0] - c * raw[0] : 0.0;
  for (std::size_t k = 1; k < n; ++k) {
    const double dt = in.time_s[k] - in.time_s[k - 1];
    const double fy = b.yield_n.at(current[k]);
    const double cv = b.viscous_ns_m.at(current[k]);
    const double x = in.disp_m[k];
    // Implicit Euler: F = law((x − cF − y)/dt), the law Eq. 4.1–4.4 at the
    // damper's velocity. h(F) = F − law(...) rises with F, so the root lies
    // between 0 and the law at F = 0: bisection.
    const auto law_at_force = [&](double f) { return bingham_force_n((x - c * f - y) / dt, fy, cv, v_tf); };
    double lo = 0.0;
    double hi = law_at_force(0.0);
    if (hi < lo) std::swap(lo, hi);
    for (int it = 0; it < 60 && hi - lo > 1e-9 * (1.0 + std::fabs(hi)); ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid - law_at_force(mid) > 0.0) {
        hi = mid;
      } else {
        lo = mid;
      }
    }
    const double f = 0.5 * (lo + hi);
    raw[k] = f;
    y = x - c * f;
  }
  std::vector<std::size_t> all(n);
  for (std::size_t k = 0; k < n; ++k) all[k] = k;
  force_n.resize(n);
  delay_force(in.time_s, raw, std::max(b.force_delay_s, 0.0), all, force_n);
}

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
  const auto [tau_s, best_rss] = minimize_log(rss_at, kTauMin_s, kTauMax_s, kTauGrid, kGoldenSteps);
  out.tau_s = tau_s;

  // The delay hypothesis is the force channel's own: a transport delay behind
  // the acquisition's anti-alias filter, whose corner is at or above a
  // quarter of the sample rate (it passes the band the record resolves), so
  // its time constant is at most 4 / (2π f_s) = 0.64 sample periods. The
  // delay is shortened by the filter's, so the pair keeps the fitted mean delay.
  const double sample_s = t.size() > 1 ? (t.back() - t.front()) / static_cast<double>(t.size() - 1) : 0.0;
  const double anti_alias_max_s = kAntiAliasMaxPerSample * sample_s;
  std::vector<double> behind_filter;
  std::vector<double> shortened(params.begin(), params.end());
  const auto rss_behind = [&](double tau_aa_s) {
    shortened[*off] = std::max(out.delay_s - tau_aa_s, 0.0);
    model.simulate(set, shortened, ws, behind_filter);
    first_order_lowpass(t, std::vector<double>(behind_filter), tau_aa_s, behind_filter);
    return rss_over(measured_force_n, behind_filter, fit_index);
  };
  double rss_delay = rss_over(measured_force_n, with_delay, fit_index);
  if (anti_alias_max_s > kAntiAliasMin_s) {
    const auto [tau_aa_s, rss_aa] =
        minimize_log(rss_behind, kAntiAliasMin_s, anti_alias_max_s, kTauGrid / 3, kGoldenSteps / 2);
    if (rss_aa < rss_delay) {
      rss_delay = rss_aa;
      out.anti_alias_s = tau_aa_s;
      shortened[*off] = std::max(out.delay_s - tau_aa_s, 0.0);
      model.simulate(set, shortened, ws, behind_filter);
      first_order_lowpass(t, std::vector<double>(behind_filter), tau_aa_s, with_delay);
    }
  }
  first_order_lowpass(t, undelayed, tau_s, filtered);
  const double held_delay = rss_over(measured_force_n, with_delay, held_index);
  const double held_lowpass = rss_over(measured_force_n, filtered, held_index);
  out.delta_bic = n_eff * std::log(std::max(rss_delay, 1e-300) / std::max(best_rss, 1e-300));
  out.held_out_reduction = held_delay > 0.0 ? 1.0 - held_lowpass / held_delay : 0.0;
  out.lowpass_better = out.delta_bic >= min_delta_bic && out.held_out_reduction > 0.0;
  return out;
}

void compare_with_compliance(const DamperModel& model, const EffectSet& set, std::span<const double> params,
                             std::span<const double> measured_force_n, std::span<const std::size_t> fit_index,
                             std::span<const std::size_t> held_index, double n_eff, double min_delta_bic,
                             FilterCheck& out) {
  const Baseline& base = model.baseline();
  if (!(set.contains(Effect::time_delay) || set.contains(Effect::preyield_hysteresis))) return;
  // Only the plain Eq. 4.4 form (series_compliance_force solves no other).
  if (base.law != BaseLaw::bingham || base.has_lost_motion() || base.has_transition_time() ||
      base.has_tanh_transition())
    return;
  if (!(base.force_scale_n() > 0.0)) return;
  if (const auto off = set.offset(Effect::time_delay)) out.delay_s = params[*off];
  ModelWorkspace ws;
  std::vector<double> selected;
  model.simulate(set, params, ws, selected);
  const double rss_sel = rss_over(measured_force_n, selected, fit_index);
  const double held_sel = rss_over(measured_force_n, selected, held_index);
  out.compliance_checked = true;
  std::vector<double> compliant;
  const auto rss_c = [&](double comp) {
    series_compliance_force(model, comp, compliant);
    return rss_over(measured_force_n, compliant, fit_index);
  };
  const double scale = base.force_scale_n();
  const auto [comp, rss_comp] = minimize_log(rss_c, kDeflectionMin_m / scale, kDeflectionMax_m / scale, 24, 16);
  out.compliance_m_per_n = comp;
  series_compliance_force(model, comp, compliant);
  const double held_comp = rss_over(measured_force_n, compliant, held_index);
  out.compliance_delta_bic = n_eff * std::log(std::max(rss_sel, 1e-300) / std::max(rss_comp, 1e-300));
  out.compliance_held_out_reduction = held_sel > 0.0 ? 1.0 - held_comp / held_sel : 0.0;
  out.compliance_better = out.compliance_delta_bic >= min_delta_bic && out.compliance_held_out_reduction > 0.0;
}

}  // namespace mrd::discrepancy
