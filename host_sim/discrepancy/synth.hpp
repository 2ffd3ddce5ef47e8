#pragma once
/// Measured-like damper records made from the baseline model plus hidden
/// effects: random sine or broadband displacement, constant or stepped
/// current, sensor noise and quantization. The discrepancy workflow is
/// proven on these (it is not told what was added).

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "host_sim/discrepancy/baseline.hpp"
#include "host_sim/discrepancy/effects.hpp"
#include "host_sim/discrepancy/measured_data.hpp"

namespace mrd::discrepancy {

enum class SynthInput { random, sine, broadband };
enum class SynthCurrent { random, constant, steps };

struct SynthSpec {
  std::vector<Effect> effects;
  /// Parameters packed in `effects` order; empty = drawn from synth_range().
  std::vector<double> params;
  SynthInput input = SynthInput::random;
  SynthCurrent current = SynthCurrent::random;
  double duration_s = 20.0;
  double rate_hz = 1000.0;
  std::uint64_t seed = 1;
  /// Sample times t_k = (k + u_k·jitter) / rate, u_k uniform in [−½, ½]; < 1.
  double jitter = 0.0;
  bool velocity_column = false;
  /// Force-noise level; negative = drawn (white 0.2–1 kN plus a 20 ms
  /// correlated part of 0.1–0.5 kN). Displacement noise likewise (5–20 µm).
  double force_noise_n = -1.0;
  double disp_noise_m = -1.0;
  /// Each effect's contribution must reach this multiple of the force-noise
  /// RMS; parameters and input are drawn again (up to 50 times) until it does.
  double min_effect_to_noise = 4.0;
  /// The damper the record is made from: the thesis's 200 kN damper when
  /// absent, else this baseline (a damper.toml, any law). With a baseline the
  /// draws are put on its damper: motions inside its [validity] half ranges,
  /// dominant frequencies and velocity, currents up to its largest one, and
  /// the sensor noise, the 16-bit channels' ranges and the effects' forces
  /// and lengths scaled from the thesis damper's by its force scale
  /// (Baseline::force_scale_n) and by its largest half range over 40 mm.
  std::optional<Baseline> baseline;
};

struct SynthCase {
  MeasuredData data;
  std::vector<Effect> effects;
  std::vector<double> params;  ///< packed in `effects` order
  std::string input_description;
  std::string current_description;
  double force_noise_rms_n = 0.0;  ///< white + correlated
  double disp_noise_m = 0.0;
  /// RMS change of the force caused by each effect (with the others present), N.
  std::vector<double> effect_rms_n;
  /// Normalized RMS gap between the noise-free truth and the baseline.
  double true_gap = 0.0;
  int draws = 1;                   ///< how many draws the visibility rule took
};

/// Range the generator draws parameter `i` of `e` from (inside the physical
/// bounds, large enough to be seen in a 20 s record).
[[nodiscard]] std::pair<double, double> synth_range(Effect e, std::size_t i);

/// 0, 1 or 2 distinct effects drawn from `seed` (by a hash of its own, so
/// the record drawn for the same seed does not change).
[[nodiscard]] std::vector<Effect> random_effects(std::uint64_t seed);

/// Deterministic for a given spec (own PRNG: SplitMix64 + Box–Muller).
/// Throws std::invalid_argument for a spec out of range (duration < 2 s,
/// rate < 50 Hz, jitter ≥ 1, a params vector of the wrong size).
[[nodiscard]] SynthCase synthesize(const SynthSpec& spec);

}  // namespace mrd::discrepancy
