#pragma once
/// The virtual RTHS benchmark's evaluation criteria (Silva et al. 2020).
///
/// - J1: the time lag, s, at the peak of the cross-correlation of the
///   measured and the target displacement (positive: measured late);
/// - J2, J3: the normalized RMS and peak tracking errors, %:
///   100·rms(x_m − x_t)/rms(x_t), 100·max|x_m − x_t|/max|x_t|;
/// - J4, J5: the same for floor 1 of the RTHS against the all-numerical
///   reference; J6, J7 floor 2; J8, J9 floor 3.

#include <array>
#include <vector>

namespace mrd::rths {

/// 100·rms(a − b)/rms(b), %; 0 when b is all zero and a equals it.
double normalized_rms_error_pct(const std::vector<double>& a, const std::vector<double>& b);
/// 100·max|a − b|/max|b|, %.
double normalized_peak_error_pct(const std::vector<double>& a, const std::vector<double>& b);
/// The lag L·dt (|L| ≤ max_lag_steps; J1 searches ±50 ms) that maximizes Σ_k measured[k + L]·target[k], s.
double cross_correlation_lag_s(const std::vector<double>& measured, const std::vector<double>& target, double dt_s,
                               int max_lag_steps);

struct Criteria {
  std::array<double, 9> j{};  ///< J1 (s), J2..J9 (%)
};

/// J1–J9 from the tracking signals and up to three floors' displacements
/// of the RTHS and the reference (J for missing floors: 0).
Criteria evaluate_criteria(const std::vector<double>& measured_m, const std::vector<double>& target_m,
                           const std::vector<std::vector<double>>& floors_m,
                           const std::vector<std::vector<double>>& reference_floors_m, double dt_s);

}  // namespace mrd::rths
