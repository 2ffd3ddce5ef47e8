#pragma once
/// Inputs of the independent generator as functions of continuous time: the
/// actuator's displacement (a sum of sines plus a constant-velocity ramp) and
/// the commanded coil current (piecewise constant, steps at any instant), and
/// a portable random source.

#include <cstdint>
#include <random>
#include <vector>

namespace indep {

/// Random numbers from std::mt19937_64 (its sequence is fixed by the C++
/// standard) with uniform and normal draws written here, so a seed gives the
/// same record with every standard library.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  /// Uniform in [0, 1).
  double uniform();
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// exp(uniform(ln lo, ln hi)); lo, hi > 0.
  double log_uniform(double lo, double hi);
  /// Standard normal (Box–Muller).
  double normal();
  bool chance(double p) { return uniform() < p; }

 private:
  std::mt19937_64 engine_;
};

/// One sine component of the displacement.
struct SineComponent {
  double amplitude_m;
  double frequency_hz;
  double phase_rad;
};

/// A linear sweep A sin(2π (f₀ t + ½ r t²)), r the sweep rate (f₁ − f₀)/T; amplitude 0 = none.
struct Chirp {
  double amplitude_m = 0.0;
  double start_hz = 0.0;
  double rate_hz_per_s = 0.0;

  [[nodiscard]] double phase_rad(double t_s) const;
  [[nodiscard]] double frequency_hz(double t_s) const { return start_hz + rate_hz_per_s * t_s; }
};

/// x(t) = offset + ramp·t + Σ A sin(2π f t + φ) + chirp(t), m.
struct Motion {
  double offset_m = 0.0;
  double ramp_m_s = 0.0;
  std::vector<SineComponent> sines;
  Chirp chirp;

  [[nodiscard]] double displacement_m(double t_s) const;
  [[nodiscard]] double velocity_m_s(double t_s) const;
  [[nodiscard]] double acceleration_m_s2(double t_s) const;
};

/// Commanded current, A: `levels_a[j]` from `start_s[j]` on (start_s[0] = −∞ in effect).
struct CurrentProgram {
  std::vector<double> start_s{0.0};
  std::vector<double> levels_a{0.0};

  [[nodiscard]] double at(double t_s) const;
};

}  // namespace indep
