#include "host_sim/drive/drive_file.hpp"

#include <cmath>

#include "host_sim/discrepancy/toml_fields.hpp"
#include "host_sim/drive/drive_ranges.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::drive {
namespace {

using discrepancy::TomlTable;
using discrepancy::toml_number;

std::string g(double v) { return io::format_number("%.4g", v); }

}  // namespace

DriveFile thesis_drive() { return DriveFile{}; }

DriveFile parse_drive_toml(const std::string& text, const std::string& origin) {
  const toml::table root = discrepancy::parse_toml(text, origin);
  discrepancy::no_unknown_tables(root, {"drive"}, origin);
  TomlTable t(discrepancy::required_table(root, "drive", origin), "drive", origin);
  DriveFile f;
  f.origin = origin;
  f.name = t.string("name");
  f.source = t.string("source");
  plant::PwmDriveParams& p = f.params;
  p.bus_v = t.in("bus_v", kBusVoltageRange);
  p.command_limit_v = t.in("command_range_v", kCommandRangeVoltageRange);
  p.volts_per_amp = t.in("volts_per_amp", kCommandScaleRange);
  p.continuous_current_a = t.in("continuous_current_a", kDriveCurrentRange);
  p.peak_current_a = t.in("peak_current_a", kDriveCurrentRange);
  p.peak_time_s = t.in("peak_time_s", kPeakTimeRange);
  p.loop_bandwidth_rad_s = t.in("loop_bandwidth_rad_s", kLoopBandwidthRange);
  p.substep_s = t.in("loop_period_s", kLoopPeriodRange);
  if (p.peak_current_a < p.continuous_current_a)
    t.refuse("peak_current_a", "expected at least continuous_current_a (" + toml_number(p.continuous_current_a) +
                                   " A): a drive's peak is what it gives above its continuous rating");
  f.loop_bandwidth_line = static_cast<std::size_t>(t.where("loop_bandwidth_rad_s").begin.line);
  t.no_unknown_keys();
  return f;
}

DriveFile read_drive_file(const std::filesystem::path& path) {
  return parse_drive_toml(io::read_regular_file(path, kMaxDriveFileBytes), io::file_label(path));
}

double command_limit_a(const plant::PwmDriveParams& d) noexcept { return d.command_limit_v / d.volts_per_amp; }

std::vector<std::string> check_drive_fit(const DriveFile& d, const plant::CoilParams& coil, double rated_current_a,
                                         double step_s) {
  const plant::PwmDriveParams& p = d.params;
  const plant::Coil c(coil);
  // K_p = L(1 A) ω_c (pwm_drive.cpp); the error shrinks by K_p T / L per period.
  const double loop_period_s = step_s / std::max(1.0, std::round(step_s / p.substep_s));
  const double gain = coil.inductance_1a_h * p.loop_bandwidth_rad_s * loop_period_s / coil.min_inductance_h;
  if (gain > kMaxLoopStepGain) {
    const std::string where = d.origin.empty() ? std::string("the thesis drive") : d.origin;
    const std::string line = d.loop_bandwidth_line > 0 ? ":" + std::to_string(d.loop_bandwidth_line) : "";
    throw io::UsageError(where + line + ": drive.loop_bandwidth_rad_s: expected at most " +
                         g(kMaxLoopStepGain * coil.min_inductance_h / (coil.inductance_1a_h * loop_period_s)) +
                         " rad/s with this coil: K_p = L(1 A) w_c = " + g(coil.inductance_1a_h * p.loop_bandwidth_rad_s) +
                         " V/A moves the current by K_p T / L = " + g(gain) + " of its error per loop period T = " +
                         g(loop_period_s) + " s at the coil's saturated inductance " + g(coil.min_inductance_h) +
                         " H, so the sampled loop overshoots and rings (a shorter loop_period_s also serves)");
  }
  std::vector<std::string> w;
  const double reach_a = p.bus_v / coil.resistance_ohm;
  if (reach_a < rated_current_a)
    w.push_back("drive: the " + g(p.bus_v) + " V bus drives at most " + g(reach_a) + " A through the coil's " +
                g(coil.resistance_ohm) + " ohm, below the damper's rated " + g(rated_current_a) + " A");
  const double n = step_s / p.substep_s;
  if (std::fabs(n - std::round(n)) > 1e-9 * std::max(1.0, n))
    w.push_back("drive: loop_period_s " + g(p.substep_s) + " s is not a whole fraction of the " + g(step_s) +
                " s step: the current loop runs at " + g(loop_period_s) + " s");
  return w;
}

}  // namespace mrd::drive
