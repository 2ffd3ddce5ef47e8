#pragma once
/// Formatting shared by the discrepancy and calibration reports: thinned
/// series for plots and the number formats of the Markdown tables.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "host_sim/io/text.hpp"

namespace mrd::discrepancy {

/// Every `stride`-th value of `v`, multiplied by `scale`.
inline std::vector<double> thin(std::span<const double> v, std::size_t stride, double scale = 1.0) {
  std::vector<double> out;
  out.reserve(v.size() / stride + 1);
  for (std::size_t k = 0; k < v.size(); k += stride) out.push_back(v[k] * scale);
  return out;
}

/// A fraction as a percentage with two decimals ("12.34 %").
inline std::string pct(double fraction) { return io::format_number("%.2f %%", 100.0 * fraction); }

/// Four significant digits.
inline std::string g4(double v) { return io::format_number("%.4g", v); }

}  // namespace mrd::discrepancy
