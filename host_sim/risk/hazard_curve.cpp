#include "host_sim/risk/hazard_curve.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::risk {
namespace {

constexpr std::size_t kMaxHazardFileBytes = std::size_t{16} << 20;

double parse_field(std::string_view field, const std::string& prefix, const char* column) {
  double v = 0.0;
  const auto* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, v);
  if (field.empty() || ec != std::errc() || ptr != end || !std::isfinite(v)) {
    throw io::UsageError(prefix + "field '" + column + "': expected a number, got '" + io::excerpt(field, 40) + "'");
  }
  return v;
}

}  // namespace

double HazardCurve::frequency_at(double x) const {
  const std::size_t n = pga_g.size();
  std::size_t i = 0;
  while (i + 2 < n && x > pga_g[i + 1]) ++i;
  const double slope = std::log(annual_frequency[i + 1] / annual_frequency[i]) / std::log(pga_g[i + 1] / pga_g[i]);
  return annual_frequency[i] * std::pow(x / pga_g[i], slope);
}

double default_hazard_k0() {
  const double lambda = -std::log(1.0 - kDefaultHazardAnchorProbability) / kDefaultHazardAnchorYears;
  return lambda * std::pow(kDefaultHazardAnchorPga_g, kDefaultHazardSlope);
}

HazardCurve default_hazard_curve() {
  HazardCurve c;
  const double k0 = default_hazard_k0();
  char text[200];
  std::snprintf(
      text, sizeof text,
      "illustrative default site: lambda(PGA) = %.6g * PGA_g^-%.3g per year (%.3g g at %.0f %% in %.0f years)", k0,
      kDefaultHazardSlope, kDefaultHazardAnchorPga_g, kDefaultHazardAnchorProbability * 100.0,
      kDefaultHazardAnchorYears);
  c.source = text;
  constexpr int kPoints = 60;
  const double lo = std::log(0.01), hi = std::log(5.0);
  for (int i = 0; i < kPoints; ++i) {
    const double x = std::exp(lo + (hi - lo) * i / (kPoints - 1));
    c.pga_g.push_back(x);
    c.annual_frequency.push_back(k0 * std::pow(x, -kDefaultHazardSlope));
  }
  return c;
}

HazardCurve parse_hazard_csv(std::string_view text, const std::string& file) {
  text = io::strip_bom(text);
  HazardCurve c;
  c.source = file;
  std::size_t line_no = 0;
  bool header = false;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t eol = std::min(text.find('\n', pos), text.size());
    const std::string_view line = io::trim(text.substr(pos, eol - pos));
    pos = eol + 1;
    ++line_no;
    if (line.empty() || line.front() == '#') {
      if (eol == text.size()) break;
      continue;
    }
    const std::string prefix = io::line_prefix(file, line_no);
    const auto fields = io::split_commas(line);
    if (!header) {
      if (fields.size() != 2 || fields[0] != "pga_g" || fields[1] != "annual_frequency") {
        throw io::UsageError(prefix + "expected the header 'pga_g,annual_frequency', got '" + io::excerpt(line, 60) +
                             "'");
      }
      header = true;
    } else {
      if (fields.size() != 2) {
        throw io::UsageError(prefix + "expected 2 fields (pga_g,annual_frequency), got " +
                             std::to_string(fields.size()));
      }
      const double x = parse_field(fields[0], prefix, "pga_g");
      const double f = parse_field(fields[1], prefix, "annual_frequency");
      if (!(x > 0.0)) throw io::UsageError(prefix + "field 'pga_g': expected a PGA > 0 g");
      if (!c.pga_g.empty() && !(x > c.pga_g.back())) {
        throw io::UsageError(prefix + "field 'pga_g': expected PGAs that increase from row to row");
      }
      if (!(f > 0.0)) throw io::UsageError(prefix + "field 'annual_frequency': expected a frequency > 0 per year");
      if (!c.annual_frequency.empty() && !(f < c.annual_frequency.back())) {
        throw io::UsageError(prefix + "field 'annual_frequency': expected frequencies that decrease as the PGA grows");
      }
      c.pga_g.push_back(x);
      c.annual_frequency.push_back(f);
    }
    if (eol == text.size()) break;
  }
  if (!header) throw io::UsageError(file + ": no header 'pga_g,annual_frequency'");
  if (c.pga_g.size() < 2) throw io::UsageError(file + ": expected at least 2 points on the hazard curve");
  return c;
}

HazardCurve read_hazard_csv(const std::filesystem::path& path) {
  return parse_hazard_csv(io::read_regular_file(path, kMaxHazardFileBytes), io::file_label(path));
}

double limit_state_frequency(const HazardCurve& curve, const std::function<double(double)>& p, int subdivisions) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < curve.pga_g.size(); ++i) {
    const double x0 = curve.pga_g[i], x1 = curve.pga_g[i + 1];
    const double l0 = curve.annual_frequency[i], l1 = curve.annual_frequency[i + 1];
    const double slope = std::log(l1 / l0) / std::log(x1 / x0);
    for (int s = 0; s < subdivisions; ++s) {
      const double xa = x0 * std::pow(x1 / x0, static_cast<double>(s) / subdivisions);
      const double xb = x0 * std::pow(x1 / x0, static_cast<double>(s + 1) / subdivisions);
      const double drop = l0 * (std::pow(xa / x0, slope) - std::pow(xb / x0, slope));
      sum += p(std::sqrt(xa * xb)) * drop;
    }
  }
  sum += p(curve.pga_g.back()) * curve.annual_frequency.back();
  return sum;
}

}  // namespace mrd::risk
