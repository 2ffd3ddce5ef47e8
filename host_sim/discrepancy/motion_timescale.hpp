#pragma once
/// How fast a record moves, from its displacement alone: the crossings of
/// its mean, the dominant frequency, and the smoothing window that follows
/// the fastest motion in it.

#include <span>
#include <vector>

namespace mrd::discrepancy {

/// Times at which the displacement crosses its mean, s: a crossing counts
/// once the signal has gone from beyond −10 % to beyond +10 % of its half
/// range (or back), so that noise about the mean adds none. The time of a
/// crossing is that of the first sample beyond the band.
[[nodiscard]] std::vector<double> mean_crossings_s(std::span<const double> time_s,
                                                   std::span<const double> displacement_m);

/// Central difference of `y` over `time_s` at every sample (one-sided at the
/// ends; 0 where the time does not advance), in y's unit per second.
[[nodiscard]] std::vector<double> central_difference(std::span<const double> time_s, std::span<const double> y);

/// Half the range of a displacement record (max − min)/2, m; 0 when empty.
[[nodiscard]] double half_range_m(std::span<const double> displacement_m);

/// Dominant frequency of a displacement record, Hz: crossings of its mean
/// are half a period apart; the half periods between the first and the last
/// crossing over their time. 0 with fewer than two crossings.
[[nodiscard]] double dominant_frequency_hz(std::span<const double> time_s, std::span<const double> displacement_m);

/// Half window of the quartic smoothing (smooth_motion, measured_data.hpp)
/// as a share of the shortest period in the record.
///
/// The local quartic fit over ±h passes a sine of frequency f with a
/// velocity gain of 0.9997 at h·f = 0.1, 0.996 at h·f = 0.19 and 0.50 at
/// h·f = 0.75 (least-squares fit of a sine sampled at 1 kHz, worked out
/// outside this code; tests/unit/discrepancy_timescale_test.cpp checks the
/// first against the analytic derivative). A fixed ±75 ms is h·f = 0.375 on a
/// 5 Hz test and 1.5 on a 20 Hz chirp, where the derived velocity would be 6 %
/// and 94 % low.
inline constexpr double kSmoothingPeriodShare = 0.1;

/// Quantile of the intervals between mean crossings taken as the record's
/// shortest half period. On an irregular motion (several sines, random
/// steps) the single shortest interval is where the displacement grazes the
/// band around its mean, far shorter than the periods it moves at: a window
/// sized to it smooths a sensor's noise on the whole record hardly at all
/// (on the independent generator's random multisines of 0.1–3 Hz, ±15 ms
/// where the 3 Hz part allows ±33 ms). A tenth of the intervals
/// are shorter: on a linear sweep from f0 ≪ f1 that is the half period at
/// about 0.95 f1 (a share (f1² − f²)/(f1² − f0²) of the crossings lies above
/// f; h·f1 = 0.105), on a sine any of its equal half periods.
inline constexpr double kShortHalfPeriodQuantile = 0.1;

/// The smoothing half window for a record: `cap_s` (the ±75 ms chosen for
/// noise at low frequency), or kSmoothingPeriodShare of the shortest period
/// the record moves at, twice the kShortHalfPeriodQuantile of the intervals
/// between mean crossings, when that is less. `cap_s` when the record has
/// fewer than two crossings.
[[nodiscard]] double smoothing_half_window_for(std::span<const double> time_s,
                                               std::span<const double> displacement_m, double cap_s);

}  // namespace mrd::discrepancy
