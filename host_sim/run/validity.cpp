#include "host_sim/run/validity.hpp"

#include "host_sim/io/text.hpp"
#include "host_sim/structure/isolators.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdio>

namespace mrd::run {
namespace {

/// Tolerance on the current limit, 2 % of the rating: the controller holds
/// the command to 2.5 A and the coil overshoots it by ~0.02 A. At 2.55 A the
/// laws of Eq. 4.2–4.3 differ from 2.5 A by e^{−1.75}(1 − e^{−0.035}) = 0.6 %
/// of their span (f_c: 1.0 kN of 141 kN), no extrapolation worth a warning.
constexpr double kCurrentTolerance_a = 0.05;

struct Limit {
  double ValidityPeaks::*peak;
  double physics::DamperRating::*limit;
  const char* thesis_format;  ///< printf with the peak, then the limit: the thesis damper's rating
  const char* rated_format;   ///< the same for another damper's rating
};

constexpr Limit kLimits[] = {
    {&ValidityPeaks::stroke_m, &physics::DamperRating::stroke_m,
     "peak stroke %.4g m exceeds the damper's +-%.4g m (Table 3.1): the damper and isolators would reach their "
     "stops, which the model does not have",
     "peak stroke %.4g m exceeds the damper's rated +-%.4g m: the damper would reach its stops, which the model "
     "does not have"},
    {&ValidityPeaks::velocity_m_s, &physics::DamperRating::velocity_m_s,
     "peak damper velocity %.4g m/s exceeds the %.4g m/s of the tests the model was fitted to (Table 3.1): the force "
     "is extrapolated",
     "peak damper velocity %.4g m/s exceeds the damper's rated %.4g m/s: the force is extrapolated"},
    {&ValidityPeaks::current_a, &physics::DamperRating::current_a,
     "peak coil current %.4g A exceeds the fitted range 0 to %.4g A (Table 4.1): the force is extrapolated",
     "peak coil current %.4g A exceeds the damper's rated %.4g A: the force is extrapolated"},
    {&ValidityPeaks::force_n, &physics::DamperRating::force_n,
     "peak damper force %.4g N exceeds the damper's %.4g N capacity",
     "peak damper force %.4g N exceeds the damper's %.4g N capacity"},
};

bool is_thesis_rating(const physics::DamperRating& r) {
  return r.current_a == kMaxFittedCurrent_a && r.force_n == kDamperCapacity_n && r.stroke_m == kDamperHalfStroke_m &&
         r.velocity_m_s == kMaxModelVelocity_m_s;
}

/// The current's tolerance: kCurrentTolerance_a for the thesis's 2.5 A, the
/// same 2 % of another rating.
double tolerance(const Limit& l, const physics::DamperRating& r) {
  if (l.limit != &physics::DamperRating::current_a) return 0.0;
  return is_thesis_rating(r) ? kCurrentTolerance_a : 0.02 * r.current_a;
}

std::string sentence(const Limit& l, const physics::DamperRating& r, double peak) {
  char buf[256];
  std::snprintf(buf, sizeof buf, is_thesis_rating(r) ? l.thesis_format : l.rated_format, peak, r.*l.limit);
  return buf;
}

}  // namespace

ValidityPeaks validity_peaks(const plant::PlantSummary& s) {
  return {s.peak_damper_stroke_m, s.peak_base_velocity_m_s, s.peak_current_a, s.peak_damper_force_n};
}

std::vector<std::string> validity_warnings(const ValidityPeaks& p, const physics::DamperRating& rating) {
  std::vector<std::string> out;
  for (const Limit& l : kLimits) {
    const double peak = p.*l.peak;
    if (!(peak <= rating.*l.limit + tolerance(l, rating))) out.push_back(sentence(l, rating, peak));
  }
  return out;
}

std::vector<std::string> bearing_capacity_warnings(const std::vector<double>& peak_base_displacement_m,
                                                   const structure::BuildingParams& building) {
  structure::IsolatorBank bank;
  bank.init(building);
  const double capacity_m = bank.displacement_capacity_m();
  if (!(capacity_m > 0.0)) return {};
  std::size_t over = 0;
  double worst_m = 0.0;
  for (const double x : peak_base_displacement_m) {
    if (x > capacity_m) {
      ++over;
      worst_m = std::max(worst_m, x);
    }
  }
  if (over == 0) return {};
  const std::string capacity = "the bearings' displacement capacity " + io::format_number("%.4g", capacity_m) +
                               " m (building file)";
  if (peak_base_displacement_m.size() == 1)
    return {"peak isolator displacement " + io::format_number("%.4g", worst_m) + " m exceeds " + capacity};
  return {"in " + std::to_string(over) + " of " + std::to_string(peak_base_displacement_m.size()) +
          " runs: peak isolator displacement up to " + io::format_number("%.4g", worst_m) + " m exceeds " + capacity};
}

std::vector<std::string> validity_warnings(const std::vector<ValidityPeaks>& runs,
                                           const physics::DamperRating& rating) {
  std::vector<std::string> out;
  for (const Limit& l : kLimits) {
    std::size_t over = 0;
    double worst = 0.0;
    for (const ValidityPeaks& p : runs) {
      const double peak = p.*l.peak;
      if (!(peak <= rating.*l.limit + tolerance(l, rating))) {
        ++over;
        worst = std::max(worst, peak);
      }
    }
    if (over == 0) continue;
    out.push_back("in " + std::to_string(over) + " of " + std::to_string(runs.size()) +
                  " runs: " + sentence(l, rating, worst));
  }
  return out;
}

}  // namespace mrd::run
