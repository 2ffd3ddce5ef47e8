#include "host_sim/discrepancy/plausibility.hpp"

#include <algorithm>
#include <cmath>

#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/discrepancy/motion_timescale.hpp"
#include "host_sim/io/text.hpp"

namespace mrd::discrepancy {
namespace {

double largest_magnitude(const std::vector<double>& v) {
  double m = 0.0;
  for (const double x : v) m = std::max(m, std::fabs(x));
  return m;
}

std::string reach_number(double v) { return io::format_number("%.4g", v); }

/// "<file>: <what> up to <value> A, beyond any MR damper's coil ...".
std::string current_warning(const std::string& source, const char* what, double current_a) {
  return source + ": " + what + " up to " + reach_number(current_a) + " A, beyond any MR damper's coil (warned above " +
         reach_number(kPlausibleCurrent_a) + " A): milliamperes in an _A column?";
}

/// How far the peak forces of `hi` (the larger) and `lo` lie beyond what one
/// damper allows (their ratio over `bound`, the ratio of the currents times
/// that of the peak velocities, each at least 1); {0, 0} when the two cannot
/// be compared (one with field, one without).
struct Spread {
  double excess = 0.0;
  double bound = 0.0;
};

Spread spread_of(const RecordReach& hi, const RecordReach& lo) {
  const bool hi_field = hi.current_cmd_max_a >= kNoFieldCurrent_a;
  const bool lo_field = lo.current_cmd_max_a >= kNoFieldCurrent_a;
  if (hi_field != lo_field || !(lo.force_peak_n > 0.0)) return {};
  const double current_factor = hi_field ? std::max(1.0, hi.current_cmd_max_a / lo.current_cmd_max_a) : 1.0;
  const double velocity_factor =
      lo.velocity_max_m_s > 0.0 ? std::max(1.0, hi.velocity_max_m_s / lo.velocity_max_m_s) : 1.0;
  const double bound = current_factor * velocity_factor;
  return {hi.force_peak_n / lo.force_peak_n / bound, bound};
}

}  // namespace

RecordReach record_reach(const MeasuredData& data, double smoothing_half_window_s) {
  RecordReach r;
  r.source = data.source;
  const ModelInput in = model_input(data, smoothing_half_window_s);
  r.half_range_m = half_range_m(in.disp_m);
  r.velocity_max_m_s = largest_magnitude(in.vel_m_s);
  r.velocity_derived = in.velocity_derived;
  r.current_cmd_max_a = largest_magnitude(data.current_cmd_a);
  r.current_meas_max_a = largest_magnitude(data.current_a);
  r.force_peak_n = largest_magnitude(data.force_n);
  return r;
}

std::vector<std::string> unit_warnings(const RecordReach& r) {
  std::vector<std::string> w;
  const bool wide = r.half_range_m > kPlausibleHalfRange_m;
  if (wide)
    w.push_back(r.source + ": displacement half range " + reach_number(r.half_range_m) +
                " m, beyond any damper's half stroke (warned above " + reach_number(kPlausibleHalfRange_m) +
                " m): millimetres in a _m column?");
  if (r.velocity_max_m_s > kPlausibleVelocity_m_s && !(wide && r.velocity_derived))
    w.push_back(r.source + ": peak velocity " + reach_number(r.velocity_max_m_s) + " m/s" +
                (r.velocity_derived ? " (derived from the displacement)" : "") +
                ", beyond any damper (warned above " + reach_number(kPlausibleVelocity_m_s) +
                " m/s): a column in another unit?");
  if (r.current_cmd_max_a > kPlausibleCurrent_a)
    w.push_back(current_warning(r.source, "commanded current", r.current_cmd_max_a));
  if (r.current_meas_max_a > kPlausibleCurrent_a)
    w.push_back(current_warning(r.source, "measured coil current", r.current_meas_max_a));
  return w;
}

std::vector<std::string> force_scale_warnings(std::span<const RecordReach> records) {
  Spread worst;
  const RecordReach* worst_hi = nullptr;
  const RecordReach* worst_lo = nullptr;
  for (const RecordReach& a : records) {
    for (const RecordReach& b : records) {
      if (&a == &b || a.force_peak_n < b.force_peak_n) continue;
      const Spread s = spread_of(a, b);
      if (s.excess > worst.excess) {
        worst = s;
        worst_hi = &a;
        worst_lo = &b;
      }
    }
  }
  if (worst_hi == nullptr || !(worst.excess > kForceScaleSpread)) return {};
  const RecordReach& hi = *worst_hi;
  const RecordReach& lo = *worst_lo;
  const auto n = [](double v) { return reach_number(v); };
  return {"records " + hi.source + " and " + lo.source + ": peak forces " + n(hi.force_peak_n) + " N and " +
          n(lo.force_peak_n) + " N, " + n(hi.force_peak_n / lo.force_peak_n) + " times apart, where their currents (" +
          n(hi.current_cmd_max_a) + " A and " + n(lo.current_cmd_max_a) + " A) and peak velocities (" +
          n(hi.velocity_max_m_s) + " and " + n(lo.velocity_max_m_s) + " m/s) allow one damper a ratio of at most " +
          n(worst.bound) + " (warned above " + n(kForceScaleSpread) +
          " times that): records of two dampers, or a force column in another unit?"};
}

std::vector<std::string> plausibility_warnings(std::span<const RecordReach> records) {
  std::vector<std::string> w;
  for (const RecordReach& r : records)
    for (std::string& s : unit_warnings(r)) w.push_back(std::move(s));
  for (std::string& s : force_scale_warnings(records)) w.push_back(std::move(s));
  return w;
}

std::vector<std::string> plausibility_warnings(std::span<const MeasuredData> records, double smoothing_half_window_s) {
  std::vector<RecordReach> reach;
  for (const MeasuredData& d : records) reach.push_back(record_reach(d, smoothing_half_window_s));
  return plausibility_warnings(reach);
}

}  // namespace mrd::discrepancy
