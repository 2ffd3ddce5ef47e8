#include "host_sim/rths_board/run_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace mrd::rths_board {
namespace fs = std::filesystem;
namespace {

constexpr const char* kRunFiles[] = {"summary.json", "tracking.csv", "coefficients.csv", "stop.json"};

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

std::string quoted(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      o += ' ';
      continue;
    }
    o += c;
  }
  return o + "\"";
}

/// "  \"timing\": {…},\n" of either loop.
template <class Loop>
std::string timing_json(const Loop& loop) {
  const LoopTimingRecord& t = loop.timing();
  return "  \"timing\": {\"period_ns\": " + std::to_string(t.period_ns) + ", \"overruns\": " +
         std::to_string(t.overruns) + ", \"worst_late_us\": " + num(static_cast<double>(t.worst_late_ns) / 1e3) +
         ", \"worst_tick_us\": " + num(static_cast<double>(t.worst_tick_ns) / 1e3) +
         ", \"median_tick_us\": " + num(static_cast<double>(t.median_tick_ns) / 1e3) +
         ", \"p99_tick_us\": " + num(static_cast<double>(t.p99_tick_ns) / 1e3) +
         ", \"stale_measurement_ticks\": " + std::to_string(loop.stale_ticks()) +
         ", \"rejected_frames\": " + std::to_string(loop.rejected()) +
         ", \"tx_errors\": " + std::to_string(loop.tx_errors()) + "},\n";
}

template <class Loop>
std::string timing_fields_of(const Loop& loop) {
  const LoopTimingRecord& t = loop.timing();
  char b[400];
  std::snprintf(b, sizeof b,
                "ticks=%llu overruns=%u worst_late_us=%.1f worst_tick_us=%.1f median_tick_us=%.1f p99_tick_us=%.1f "
                "stale_ticks=%u rejected=%u tx_errors=%u",
                static_cast<unsigned long long>(loop.ticks()), t.overruns, static_cast<double>(t.worst_late_ns) / 1e3,
                static_cast<double>(t.worst_tick_ns) / 1e3, static_cast<double>(t.median_tick_ns) / 1e3,
                static_cast<double>(t.p99_tick_ns) / 1e3, loop.stale_ticks(), loop.rejected(), loop.tx_errors());
  return b;
}

std::string setup_json(const RunDescription& d, const BoardLoop& loop) {
  std::string s;
  s += "  \"board\": " + quoted(d.board) + ",\n";
  s += "  \"record\": " + quoted(d.record) + ",\n";
  s += "  \"record_scale\": " + num(d.record_scale) + ",\n";
  s += "  \"structure\": " + quoted(d.structure) + ",\n";
  s += "  \"compensator\": " + quoted(d.compensator) + ",\n";
  s += "  \"rate_hz\": " + num(d.rate_hz) + ",\n";
  s += "  \"ticks\": " + std::to_string(loop.ticks()) + ",\n";
  s += "  \"record_ticks\": " + std::to_string(loop.steps()) + ",\n";
  return s + timing_json(loop);
}

std::string damper_setup_json(const DamperRunDescription& d, const DamperLoop& loop) {
  std::string s;
  s += "  \"specimen\": \"damper\",\n";
  s += "  \"board\": " + quoted(d.board) + ",\n";
  s += "  \"record\": " + quoted(d.record) + ",\n";
  s += "  \"pga_g\": " + num(d.pga_g) + ",\n";
  s += "  \"building\": " + quoted(d.building) + ",\n";
  s += "  \"control\": " + quoted(d.control) + ",\n";
  s += "  \"compensation\": " + quoted(d.compensation) + ",\n";
  s += "  \"delay_s\": " + num(d.delay_s) + ",\n";
  s += "  \"lag_s\": " + num(d.lag_s) + ",\n";
  s += "  \"rate_hz\": " + num(d.rate_hz) + ",\n";
  s += "  \"ticks\": " + std::to_string(loop.ticks()) + ",\n";
  s += "  \"record_ticks\": " + std::to_string(loop.steps()) + ",\n";
  return s + timing_json(loop);
}

}  // namespace

void prepare_out_dir(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw std::runtime_error(dir.string() + ": cannot create the output folder");
  for (const char* name : kRunFiles) {
    fs::remove(dir / name, ec);
    fs::remove(dir / (std::string(name) + ".tmp"), ec);
  }
}

void write_atomically(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path final_path = dir / name;
  const fs::path tmp = dir / (name + ".tmp");
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw std::runtime_error(tmp.string() + ": cannot write");
  }
  std::error_code ec;
  fs::rename(tmp, final_path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error(final_path.string() + ": cannot rename the written file into place");
  }
}

void write_finished_run(const fs::path& dir, const RunDescription& d, const BoardLoop& loop,
                        const rths::Criteria& c) {
  static constexpr const char* kNames[] = {"j1_lag_s",          "j2_tracking_rms_pct", "j3_tracking_peak_pct",
                                           "j4_floor1_rms_pct", "j5_floor1_peak_pct",  "j6_floor2_rms_pct",
                                           "j7_floor2_peak_pct", "j8_floor3_rms_pct",  "j9_floor3_peak_pct"};
  // The CSVs first: summary.json, written last, marks a complete run.
  std::string csv = "time_s,target_m,measured_m,command_m,force_n\n";
  csv.reserve(loop.ticks() * 72);
  for (std::size_t k = 0; k < loop.measured_m().size(); ++k) {
    for (const double v : {static_cast<double>(k) * loop.dt_s(), loop.target_m()[k], loop.measured_m()[k],
                           loop.command_m()[k], loop.force_n()[k]}) {
      csv += num(v);
      csv += ',';
    }
    csv.back() = '\n';
  }
  write_atomically(dir, "tracking.csv", csv);
  std::string co = "time_s";
  for (const auto& n : loop.coefficient_names()) {
    co += ',';
    co += n;
  }
  co += "\n";
  const std::size_t width = loop.coefficient_names().size();
  for (std::size_t i = 0; i < loop.coefficient_time_s().size(); ++i) {
    co += num(loop.coefficient_time_s()[i]);
    for (std::size_t j = 0; j < width; ++j) {
      co += ',';
      co += num(loop.coefficient_row(i)[j]);
    }
    co += "\n";
  }
  write_atomically(dir, "coefficients.csv", co);

  std::string s = "{\n  \"status\": \"ok\",\n" + setup_json(d, loop);
  s += "  \"criteria\": {";
  for (std::size_t i = 0; i < c.j.size(); ++i) s += std::string(i ? ", " : "") + quoted(kNames[i]) + ": " + num(c.j[i]);
  s += "},\n  \"coefficients_final\": {";
  if (!loop.coefficient_time_s().empty()) {
    const double* last = loop.coefficient_row(loop.coefficient_time_s().size() - 1);
    for (std::size_t i = 0; i < width; ++i)
      s += std::string(i ? ", " : "") + quoted(loop.coefficient_names()[i]) + ": " + num(last[i]);
  }
  s += "}\n}\n";
  write_atomically(dir, "summary.json", s);
}

void write_stopped_run(const fs::path& dir, const RunDescription& d, const BoardLoop& loop) {
  std::string s = "{\n  \"status\": " + quoted(loop_end_status(loop.end(), loop.lab_reason())) + ",\n";
  s += setup_json(d, loop);
  s += "  \"end_time_s\": " + num(static_cast<double>(loop.ticks()) * loop.dt_s()) + "\n}\n";
  write_atomically(dir, "stop.json", s);
}

std::string timing_fields(const BoardLoop& loop) { return timing_fields_of(loop); }
std::string timing_fields(const DamperLoop& loop) { return timing_fields_of(loop); }

void write_finished_damper_run(const fs::path& dir, const DamperRunDescription& d, const DamperLoop& loop) {
  std::string csv = "time_s,target_m,measured_m,command_m,force_n,current_a,base_displacement_m\n";
  csv.reserve(loop.ticks() * 110);
  for (std::size_t k = 0; k < loop.measured_m().size(); ++k) {
    for (const double v : {static_cast<double>(k) * loop.dt_s(), loop.target_m()[k], loop.measured_m()[k],
                           loop.command_m()[k], loop.force_n()[k], loop.current_a()[k],
                           loop.base_displacement_m()[k]}) {
      csv += num(v);
      csv += ',';
    }
    csv.back() = '\n';
  }
  write_atomically(dir, "tracking.csv", csv);
  double peak_force_n = 0.0;
  for (double f : loop.force_n()) peak_force_n = std::max(peak_force_n, std::fabs(f));
  std::string s = "{\n  \"status\": \"ok\",\n" + damper_setup_json(d, loop);
  s += "  \"peak_base_displacement_m\": " + num(loop.peak_base_displacement_m()) + ",\n";
  s += "  \"peak_damper_force_n\": " + num(peak_force_n) + ",\n";
  s += "  \"tracking_rms_error_pct\": " + num(loop.rms_tracking_error_pct()) + "\n}\n";
  write_atomically(dir, "summary.json", s);
}

void write_stopped_damper_run(const fs::path& dir, const DamperRunDescription& d, const DamperLoop& loop) {
  std::string s = "{\n  \"status\": " + quoted(loop_end_status(loop.end(), loop.lab_reason())) + ",\n";
  s += damper_setup_json(d, loop);
  s += "  \"end_time_s\": " + num(static_cast<double>(loop.ticks()) * loop.dt_s()) + "\n}\n";
  write_atomically(dir, "stop.json", s);
}

}  // namespace mrd::rths_board
