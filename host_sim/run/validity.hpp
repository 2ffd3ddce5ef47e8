#pragma once
/// Where a run leaves the model's validity: the damper's stroke and velocity
/// (Table 3.1), the coil current the model was fitted over (Table 4.1) and
/// the damper's 200 kN capacity. Results beyond them are extrapolations; the
/// summaries carry these sentences as `warnings` and the CLI prints them.

#include <string>
#include <vector>

#include "host_sim/plant/plant.hpp"

namespace mrd::run {

/// Half-stroke of the damper's actuator LVDT, ±0.2921 m (Table 3.1).
inline constexpr double kDamperHalfStroke_m = 0.2921;
/// Highest velocity of the characterisation tests, m/s (Table 3.1).
inline constexpr double kMaxModelVelocity_m_s = 0.2491;
/// Highest coil current of the fitted model, A (0–2.5 A, Table 4.1).
inline constexpr double kMaxFittedCurrent_a = 2.5;
/// The damper's force capacity, N (200 kN).
inline constexpr double kDamperCapacity_n = 200.0e3;

/// Peaks of one run, absolute values, SI.
struct ValidityPeaks {
  double stroke_m = 0.0;
  double velocity_m_s = 0.0;
  double current_a = 0.0;
  double force_n = 0.0;
};

/// The peaks of a closed-loop run.
ValidityPeaks validity_peaks(const plant::PlantSummary& s);

/// One sentence per limit the run exceeds, naming the peak and the limit;
/// empty when the run stays within the model. The limits are `rating`'s (a
/// damper file's [rating]); the thesis damper's rating is the constants above,
/// with the sentences naming their tables.
std::vector<std::string> validity_warnings(const ValidityPeaks& p, const physics::DamperRating& rating = {});

/// For many runs: one sentence per limit any run exceeds, saying in how many
/// of the runs and the largest peak.
std::vector<std::string> validity_warnings(const std::vector<ValidityPeaks>& runs,
                                           const physics::DamperRating& rating = {});

/// The runs' peak base (isolator) displacements, m, against the bearings'
/// displacement capacity (the smallest a building file's bearings state):
/// one sentence when a peak exceeds it, "peak isolator displacement X m
/// exceeds ..." for one run, "in k of n runs: ..." with the largest peak for
/// several; empty when the bearings state no capacity or no peak exceeds it.
std::vector<std::string> bearing_capacity_warnings(const std::vector<double>& peak_base_displacement_m,
                                                   const structure::BuildingParams& building);

}  // namespace mrd::run
