#include "ground_record.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include "building_model.hpp"

namespace ibuild {
namespace {

[[noreturn]] void bad_record(const std::filesystem::path& file, int line, const std::string& what) {
  throw std::runtime_error(file.string() + ":" + std::to_string(line) + ": " + what);
}

double parse_number(const std::string& text, const std::filesystem::path& file, int line) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(v)) bad_record(file, line, "expected a number, got '" + text + "'");
  return v;
}

}  // namespace

double GroundRecord::at(double t_s) const {
  if (accel_m_s2.empty() || t_s < 0.0) return 0.0;
  const double pos = t_s / step_s;
  const auto k = static_cast<std::size_t>(pos);
  if (k + 1 >= accel_m_s2.size()) return k + 1 == accel_m_s2.size() && pos == static_cast<double>(k) ? accel_m_s2[k] : 0.0;
  const double frac = pos - static_cast<double>(k);
  return accel_m_s2[k] + frac * (accel_m_s2[k + 1] - accel_m_s2[k]);
}

GroundRecord read_ground_record(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot open");
  std::string text;
  std::getline(in, text);  // header
  GroundRecord r;
  std::vector<double> times;
  int line = 1;
  while (std::getline(in, text)) {
    ++line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.empty()) continue;
    const auto comma = text.find(',');
    if (comma == std::string::npos) bad_record(file, line, "expected time_s,accel_m_s2");
    times.push_back(parse_number(text.substr(0, comma), file, line));
    r.accel_m_s2.push_back(parse_number(text.substr(comma + 1), file, line));
  }
  if (times.size() < 2) bad_record(file, line, "fewer than two samples");
  r.step_s = (times.back() - times.front()) / static_cast<double>(times.size() - 1);
  if (!(r.step_s > 0.0) || times.front() != 0.0) bad_record(file, 2, "time must start at 0 and increase");
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (std::fabs(times[k] - r.step_s * static_cast<double>(k)) > 1e-6 * r.step_s + 1e-9)
      bad_record(file, static_cast<int>(k) + 2, "the time step is not uniform");
  }
  return r;
}

GroundRecord scaled_to_pga(GroundRecord r, double pga_g) {
  double peak = 0.0;
  for (double a : r.accel_m_s2) peak = std::max(peak, std::fabs(a));
  if (!(peak > 0.0)) throw std::runtime_error("the record is all zeros: it cannot be scaled to a PGA");
  const double factor = pga_g * kGravity_m_s2 / peak;
  for (double& a : r.accel_m_s2) a *= factor;
  return r;
}

}  // namespace ibuild
