#include "host_sim/discrepancy/baseline_check.hpp"

#include <algorithm>
#include <cmath>

#include "host_sim/io/text.hpp"

namespace mrd::discrepancy {

using io::format_number;

BaselineCheck check_baseline(const Baseline& baseline, std::span<const double> measured_force_n,
                             std::span<const double> baseline_force_n, std::span<const double> settled_force_n,
                             std::span<const double> vel_m_s,
                             std::span<const double> current_cmd_a) {
  BaselineCheck c;
  double fm = 0.0;
  double bb = 0.0;
  double mm = 0.0;
  double sb = 0.0;
  for (std::size_t k = 0; k < measured_force_n.size(); ++k) {
    fm += measured_force_n[k] * baseline_force_n[k];
    sb += settled_force_n[k] * baseline_force_n[k];
    bb += baseline_force_n[k] * baseline_force_n[k];
    mm += measured_force_n[k] * measured_force_n[k];
  }
  const double n = static_cast<double>(std::max<std::size_t>(measured_force_n.size(), 1));
  const double rms_meas = std::sqrt(mm / n);
  const double rms_base = std::sqrt(bb / n);
  c.force_ratio = bb > 0.0 ? fm / bb : 0.0;
  c.min_force_ratio = kSettledRatioMargin * (bb > 0.0 ? sb / bb : 1.0);
  if (!(c.force_ratio >= c.min_force_ratio && c.force_ratio <= kMaxForceRatio)) {
    c.mismatch = true;
    c.force_scale_outside = true;
    c.reasons.push_back("force scale: the measured force is " + format_number("%.3g", c.force_ratio) +
                        " times the baseline's (least squares; RMS " + format_number("%.4g", rms_meas) + " N against " +
                        format_number("%.4g", rms_base) + " N), outside [" + format_number("%.3g", c.min_force_ratio) +
                        ", " + format_number("%g", kMaxForceRatio) +
                        "] (below: weaker than half a fully settled damper on this record)");
  }
  for (const double v : vel_m_s) c.velocity_max_m_s = std::max(c.velocity_max_m_s, std::fabs(v));
  const auto [lo, hi] = std::minmax_element(current_cmd_a.begin(), current_cmd_a.end());
  if (lo != current_cmd_a.end()) {
    c.current_min_a = *lo;
    c.current_max_a = *hi;
  }
  const ValidityRange& r = baseline.range;
  if (r.velocity_max_m_s > 0.0 && c.velocity_max_m_s > kVelocityRangeFactor * r.velocity_max_m_s) {
    c.mismatch = true;
    c.reasons.push_back("velocity: the record reaches " + format_number("%.4g", c.velocity_max_m_s) +
                        " m/s, the baseline covers up to " + format_number("%.4g", r.velocity_max_m_s) + " m/s");
  }
  // The current laws depend on |I| (Eq. 4.2–4.3): a back-driven current counts by its magnitude.
  const double i_abs = std::max(std::fabs(c.current_min_a), std::fabs(c.current_max_a));
  if (r.current_max_a > 0.0 && i_abs > kRangeFactor * r.current_max_a + kCurrentSlack_a) {
    c.mismatch = true;
    c.reasons.push_back("current: the record commands up to " + format_number("%.3g", i_abs) +
                        " A, the baseline covers up to " + format_number("%.3g", r.current_max_a) + " A");
  }
  return c;
}

CommandChanges command_changes(std::span<const double> current_cmd_a) {
  CommandChanges c;
  if (current_cmd_a.empty()) return c;
  const auto [lo, hi] = std::minmax_element(current_cmd_a.begin(), current_cmd_a.end());
  c.min_a = *lo;
  c.max_a = *hi;
  const double step = std::max(kCommandChangeShare * std::max(std::fabs(c.min_a), std::fabs(c.max_a)),
                               kCommandResolution_a);
  for (std::size_t k = 1; k < current_cmd_a.size(); ++k)
    if (std::fabs(current_cmd_a[k] - current_cmd_a[k - 1]) > step) ++c.steps;
  return c;
}

std::vector<std::string> coil_notes(const Baseline& baseline, std::span<const double> current_cmd_a,
                                    std::span<const double> current_meas_a) {
  const bool measured = !current_meas_a.empty();
  const CommandChanges c = command_changes(current_cmd_a);  // a measured current's noise is no change
  if (baseline.coil_identified || c.steps == 0) return {};
  const std::string changes = std::to_string(c.steps) + " steps between " + format_number("%.3g", c.min_a) +
                              " and " + format_number("%.3g", c.max_a) + " A";
  const std::string why = " identified: its calibration records held the current constant, so after each change "
                          "the model ";
  if (measured)
    return {"the record's current command changes (" + changes + "), but the baseline's field lag behind the "
            "measured coil current (Eq. 4.5's slow branch) was not" + why + "follows an assumed lag (time constant " +
            format_number("%.3g", baseline.coil.tau_slow_s) +
            " s), not this damper's; calibrating with a record whose current changes identifies it"};
  return {"the record's current command changes (" + changes +
          "), but the baseline's coil dynamics (Eq. 4.5) were not" + why + "follows an assumed coil (time constants " +
          format_number("%.3g", baseline.coil.tau_slow_s) + " and " + format_number("%.3g", baseline.coil.tau_fast_s) +
          " s), not this damper's; calibrating with a record whose current changes identifies them"};
}

std::vector<std::string> coverage_notes(const ValidityRange& range, double amplitude_m, double frequency_hz,
                                        double expected_gap) {
  std::vector<std::string> notes;
  std::string tail;
  if (expected_gap > 0.0)
    tail = "; its expected gap (" + format_number("%.3g", expected_gap) + ") was measured there only";
  const auto check = [&](const char* what, double value, double lo, double hi, double scale, const char* unit,
                         const char* fmt) {
    if (!(hi > 0.0) || !(value > 0.0)) return;
    const char* side = value > kCoverageFactor * hi ? "above" : (value < lo / kCoverageFactor ? "below" : nullptr);
    if (side == nullptr) return;
    const std::string from = format_number(fmt, lo * scale);
    const std::string to = format_number(fmt, hi * scale);
    notes.push_back(std::string("outside the calibrated coverage: the record's ") + what + " is " +
                    format_number(fmt, value * scale) + " " + unit + ", " + side + " the " +
                    (from == to ? to : from + "–" + to) + " " + unit + " the baseline was calibrated on" + tail);
  };
  check("displacement half range", amplitude_m, range.amplitude_min_m, range.amplitude_max_m, 1e3, "mm", "%.3g");
  check("dominant frequency", frequency_hz, range.frequency_min_hz, range.frequency_max_hz, 1.0, "Hz", "%.3g");
  return notes;
}

}  // namespace mrd::discrepancy
