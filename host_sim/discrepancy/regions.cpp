#include "host_sim/discrepancy/regions.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

namespace mrd::discrepancy {
namespace {

/// Duration each sample stands for: half the steps on either side.
std::vector<double> sample_weights(std::span<const double> t) {
  const std::size_t n = t.size();
  std::vector<double> w(n, 0.0);
  if (n < 2) {
    std::fill(w.begin(), w.end(), 1.0);
    return w;
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double left = k > 0 ? t[k] - t[k - 1] : t[1] - t[0];
    const double right = k + 1 < n ? t[k + 1] - t[k] : t[n - 1] - t[n - 2];
    w[k] = 0.5 * (left + right);
  }
  return w;
}

/// Samples within ±window of a genuine velocity reversal: the velocity passes
/// zero between excursions beyond ±v_tf of opposite sign (noise that dithers
/// around zero is not a reversal).
std::vector<char> reversal_mask(std::span<const double> t, std::span<const double> v, double v_tf, double window_s) {
  const std::size_t n = t.size();
  std::vector<double> times;
  int armed = 0;           // sign of the last excursion beyond v_tf
  double last_zero = t.empty() ? 0.0 : t[0];
  for (std::size_t k = 1; k < n; ++k) {
    if ((v[k - 1] > 0.0) != (v[k] > 0.0)) last_zero = t[k];
    const int s = v[k] > v_tf ? 1 : (v[k] < -v_tf ? -1 : 0);
    if (s != 0 && s != armed) {
      if (armed != 0) times.push_back(last_zero);
      armed = s;
    }
  }
  std::vector<char> mask(n, 0);
  std::size_t j = 0;
  for (std::size_t k = 0; k < n; ++k) {
    while (j < times.size() && times[j] < t[k] - window_s) ++j;
    if (j < times.size() && std::fabs(times[j] - t[k]) <= window_s) mask[k] = 1;
  }
  return mask;
}

/// Weighted sums over the whole record: time and the squared residuals
/// before and after.
struct GapTotals {
  double weight = 0.0;
  double before = 0.0;
  double after = 0.0;
};

GapTotals gap_totals(const ResidualTraces& tr, const std::vector<double>& w) {
  GapTotals t;
  for (std::size_t k = 0; k < w.size(); ++k) {
    const double rb = tr.measured_force_n[k] - tr.baseline_force_n[k];
    const double ra = tr.measured_force_n[k] - tr.updated_force_n[k];
    t.weight += w[k];
    t.before += w[k] * rb * rb;
    t.after += w[k] * ra * ra;
  }
  return t;
}

/// The statistics of the samples where `in` holds; nullopt when they carry
/// no weight.
std::optional<RegionStat> region_stat(const char* name, const std::string& description,
                                      const std::function<bool(std::size_t)>& in, const ResidualTraces& tr,
                                      const std::vector<double>& w, const GapTotals& totals) {
  double rw = 0.0, sb = 0.0, sa = 0.0, bias = 0.0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    if (!in(k)) continue;
    const double rb = tr.measured_force_n[k] - tr.baseline_force_n[k];
    const double ra = tr.measured_force_n[k] - tr.updated_force_n[k];
    const double fb = tr.baseline_force_n[k];
    rw += w[k];
    sb += w[k] * rb * rb;
    sa += w[k] * ra * ra;
    bias += w[k] * rb * (fb > 0.0 ? 1.0 : (fb < 0.0 ? -1.0 : 0.0));
  }
  if (!(rw > 0.0)) return std::nullopt;
  RegionStat s;
  s.name = name;
  s.description = description;
  s.fraction_of_time = rw / totals.weight;
  s.share_of_gap_before = totals.before > 0.0 ? sb / totals.before : 0.0;
  s.share_of_gap_after = totals.after > 0.0 ? sa / totals.after : 0.0;
  s.concentration_before = s.fraction_of_time > 0.0 ? s.share_of_gap_before / s.fraction_of_time : 0.0;
  s.rms_before_n = std::sqrt(sb / rw);
  s.rms_after_n = std::sqrt(sa / rw);
  s.magnitude_bias_before_n = bias / rw;
  s.concentrated = s.concentration_before >= 1.5 && s.share_of_gap_before >= 0.1;
  return s;
}

}  // namespace

std::vector<RegionStat> localize_regions(const ResidualTraces& tr, double v_tf_m_s) {
  const std::size_t n = tr.time_s.size();
  std::vector<RegionStat> out;
  if (n == 0) return out;
  const std::vector<double> w = sample_weights(tr.time_s);
  const GapTotals totals = gap_totals(tr, w);
  double vmax = 0.0;
  double xmin = tr.disp_m[0], xmax = tr.disp_m[0];
  for (std::size_t k = 0; k < n; ++k) {
    vmax = std::max(vmax, std::fabs(tr.vel_m_s[k]));
    xmin = std::min(xmin, tr.disp_m[k]);
    xmax = std::max(xmax, tr.disp_m[k]);
  }
  const double xmid = 0.5 * (xmin + xmax);
  const double xhalf = 0.5 * (xmax - xmin);
  const double t0 = tr.time_s[0];
  const double dur = tr.time_s[n - 1] - t0;
  constexpr double kReversalWindow_s = 0.025;
  const std::vector<char> rev = reversal_mask(tr.time_s, tr.vel_m_s, v_tf_m_s, kReversalWindow_s);

  struct Def {
    const char* name;
    std::string description;
    std::function<bool(std::size_t)> in;
  };
  const std::vector<Def> defs{
      {"velocity_reversal", "within 25 ms of a velocity reversal", [&](std::size_t k) { return rev[k] != 0; }},
      {"near_zero_velocity", "|v| below the transition velocity of Eq. 4.4 (10 mm/s)",
       [&](std::size_t k) { return std::fabs(tr.vel_m_s[k]) < v_tf_m_s; }},
      {"high_velocity", "|v| at least half the record's largest |v|",
       [&](std::size_t k) { return std::fabs(tr.vel_m_s[k]) >= 0.5 * vmax; }},
      {"positive_velocity", "v > 10 mm/s", [&](std::size_t k) { return tr.vel_m_s[k] > v_tf_m_s; }},
      {"negative_velocity", "v < -10 mm/s", [&](std::size_t k) { return tr.vel_m_s[k] < -v_tf_m_s; }},
      {"current_low", "coil current below 0.5 A", [&](std::size_t k) { return std::fabs(tr.coil_current_a[k]) < 0.5; }},
      {"current_mid", "coil current 0.5 to 1.5 A",
       [&](std::size_t k) {
         const double i = std::fabs(tr.coil_current_a[k]);
         return i >= 0.5 && i < 1.5;
       }},
      {"current_high", "coil current 1.5 A and above",
       [&](std::size_t k) { return std::fabs(tr.coil_current_a[k]) >= 1.5; }},
      {"current_transient", "coil current (Eq. 4.5) more than 0.05 A from the command",
       [&](std::size_t k) { return std::fabs(tr.coil_current_a[k] - tr.current_cmd_a[k]) > 0.05; }},
      {"early", "first 20 % of the record", [&](std::size_t k) { return tr.time_s[k] - t0 <= 0.2 * dur; }},
      {"late", "last 20 % of the record", [&](std::size_t k) { return tr.time_s[k] - t0 >= 0.8 * dur; }},
      {"displacement_extremes", "displacement in the outer 20 % of its range",
       [&](std::size_t k) { return xhalf > 0.0 && std::fabs(tr.disp_m[k] - xmid) >= 0.8 * xhalf; }},
  };
  for (const auto& d : defs) {
    if (auto s = region_stat(d.name, d.description, d.in, tr, w, totals)) out.push_back(std::move(*s));
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const RegionStat& a, const RegionStat& b) { return a.concentration_before > b.concentration_before; });
  return out;
}

std::vector<TimeWindowStat> localize_time(const ResidualTraces& tr, std::size_t count) {
  const std::size_t n = tr.time_s.size();
  std::vector<TimeWindowStat> out;
  if (n < 2 || count == 0) return out;
  const std::vector<double> w = sample_weights(tr.time_s);
  const double t0 = tr.time_s[0];
  const double dur = tr.time_s[n - 1] - t0;
  std::vector<double> ww(count, 0.0), sb(count, 0.0), sa(count, 0.0);
  double total_b = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    auto b = static_cast<std::size_t>((tr.time_s[k] - t0) / dur * static_cast<double>(count));
    b = std::min(b, count - 1);
    const double rb = tr.measured_force_n[k] - tr.baseline_force_n[k];
    const double ra = tr.measured_force_n[k] - tr.updated_force_n[k];
    ww[b] += w[k];
    sb[b] += w[k] * rb * rb;
    sa[b] += w[k] * ra * ra;
    total_b += w[k] * rb * rb;
  }
  for (std::size_t b = 0; b < count; ++b) {
    TimeWindowStat s;
    s.start_s = t0 + dur * static_cast<double>(b) / static_cast<double>(count);
    s.end_s = t0 + dur * static_cast<double>(b + 1) / static_cast<double>(count);
    if (ww[b] > 0.0) {
      s.rms_before_n = std::sqrt(sb[b] / ww[b]);
      s.rms_after_n = std::sqrt(sa[b] / ww[b]);
    }
    s.share_of_gap_before = total_b > 0.0 ? sb[b] / total_b : 0.0;
    out.push_back(s);
  }
  return out;
}

}  // namespace mrd::discrepancy
