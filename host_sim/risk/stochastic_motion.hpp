#pragma once
/// Stochastic ground motions with an evolving spectrum for fragility studies
/// (`mrd fragility --synthetic N`): the time-modulated, filtered white noise of
/// Rezaeian & Der Kiureghian (2008, "A stochastic ground motion model with
/// separable temporal and spectral nonstationarities", Earthquake Engng
/// Struct. Dyn. 37), in discrete form:
/// <pre>
///   x(t_k) = q(t_k) · Σ_{i≤k} h(t_k − t_i; ω_i) s_i / √(Σ_{i≤k} h(t_k − t_i; ω_i)²)
///   h(τ; ω) = ω/√(1−ζ²) · e^{−ζωτ} sin(ω√(1−ζ²) τ)        (filter impulse response)
///   ω_i = 2π · max(f_min, f_mid + f'·(t_i − t_mid))        (the filter frequency drifts)
///   q(t) = (t/t_p)^(α−1) · e^{−(α−1)(t/t_p − 1)}           (gamma envelope, peak 1 at t_p)
/// </pre>
/// s_i independent standard normal. The normalization makes the filtered
/// process unit-variance at every instant, so q alone sets the intensity in
/// time and ω_i alone the frequency content (the two are separable). x is then
/// high-passed by a critically damped oscillator (corner f_c; ü + 2ω_c u̇ +
/// ω_c² u = x, the corrected motion is ü, Newmark average acceleration) so the
/// ground's velocity and displacement return to zero, and scaled to its PGA.
///
/// Cost: linear in the duration. The terms whose ω_i is the same (once the
/// drifting frequency is held at f_min, which is most of a long record) are
/// carried by three running sums, and a term is dropped once its impulse
/// response's envelope e^{−ζω_iτ} has fallen below 1e-12 (about 73 s for the
/// slowest filter of the default ranges, ζ = 0.2 at 0.3 Hz), which changes a
/// sample by about 1e-12 of the record's PGA and none of its statistics.
///
/// Per record the model parameters are drawn uniformly from ranges (below);
/// they span firm-soil records of moderate events. They are not the fitted
/// predictive relations of Rezaeian & Der Kiureghian (2010): the set is meant
/// to vary frequency content and envelope from record to record.
///
/// Determinism: std::mt19937_64 seeded per record, normal deviates by
/// excitation::StandardNormal (Box–Muller), uniform deviates from the top 53
/// bits; the same seed gives the same record on any IEEE-754 platform (up to
/// last-bit differences in exp/sin/cos of the platform's libm).

#include <cstdint>
#include <string>

#include "host_sim/excitation/ground_motion.hpp"

namespace mrd::risk {

struct StochasticMotionRanges {
  double dt_s = 0.01;                                     ///< generation step, s
  double duration_s = 30.0;                               ///< s
  double f_mid_lo_hz = 1.5, f_mid_hi_hz = 5.0;            ///< f_mid, Hz (at t_mid = t_p)
  double f_slope_lo_hz_s = -0.10, f_slope_hi_hz_s = 0.0;  ///< f', Hz/s
  double f_min_hz = 0.3;                                  ///< floor of the drifting frequency, Hz
  double zeta_lo = 0.2, zeta_hi = 0.6;                    ///< ζ of the filter
  double peak_time_lo_s = 3.0, peak_time_hi_s = 8.0;      ///< t_p, s
  double envelope_shape = 3.0;                            ///< α of the gamma envelope
  double high_pass_hz = 0.2;                              ///< f_c, Hz
};

/// The drawn parameters of one record.
struct StochasticMotionParams {
  double f_mid_hz = 0.0, f_slope_hz_s = 0.0, zeta = 0.0, peak_time_s = 0.0;
};

/// Seed of record `index` of a study seeded `study_seed` (SplitMix64 of both).
std::uint64_t record_seed(std::uint64_t study_seed, std::uint64_t index) noexcept;

/// Parameters drawn for `seed`.
StochasticMotionParams draw_stochastic_params(const StochasticMotionRanges& ranges, std::uint64_t seed);

/// A record's name, `stochastic-<index>`, and its source: the model, seed and
/// drawn parameters.
struct StochasticLabel {
  std::string name, source;
};
StochasticLabel stochastic_motion_label(const StochasticMotionRanges& ranges, std::uint64_t seed, std::uint64_t index);

/// What generating one record cost: filter-term updates, one per group of
/// terms sharing a frequency per step (see stochastic_motion.cpp). It grows
/// linearly with the duration: a term is dropped once its impulse response
/// has decayed below 1e-12 of its start, and the terms held at f_min share
/// one group.
struct StochasticMotionWork {
  std::size_t term_updates = 0;
};

/// One record, at ranges.dt_s, scaled to a PGA of 1 g, named
/// as stochastic_motion_label says; `work`, when given, receives its cost.
excitation::GroundMotion stochastic_motion(const StochasticMotionRanges& ranges, std::uint64_t seed,
                                           std::uint64_t index, StochasticMotionWork* work = nullptr);

}  // namespace mrd::risk
