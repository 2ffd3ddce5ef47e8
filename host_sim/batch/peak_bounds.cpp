#include "host_sim/batch/peak_bounds.hpp"

#include <algorithm>
#include <cmath>

namespace mrd::batch {
namespace {

/// ‖(a, b)‖₂.
double norm2(double a, double b) noexcept { return std::hypot(a, b); }

}  // namespace

double block_norm(double a, double b, double c, double d) noexcept {
  return 0.5 * (std::hypot(a + d, b - c) + std::hypot(a - d, b + c));
}

// A row c of the accelerations (displacements) in the modal coordinates q,
// summed in floating point over its 12 terms, is within 12 u Σ_k |c_k| |q_k|
// of c·q (u = 2⁻⁵³), and Σ_k |c_k| |q_k| ≤ Σ_j ‖c^(j)‖₂ ρ_j (c^(j) =
// (c_2j, c_2j+1), ρ_j = ‖(q_2j, q_2j+1)‖₂, Cauchy–Schwarz). A drift
// x_i − x_{i−1} of two such sums is within their roundings of
// (c_i − c_{i−1})·q, so its weight adds them: 16 u (‖c_i^(j)‖ + ‖c_{i−1}^(j)‖).
// A group's weight of mode j is the largest over its rows (floors 1–5,
// stories 1–5). A mode's computed step is within 5 u (‖B_j‖_F ρ_j +
// ‖γ_j^a‖ |a_g| + ‖γ_j^F‖ |F|) of the exact B_j q^(j) + γ_j^a a_g + γ_j^F F
// (four terms a component; ‖B_j‖_F ≤ √2 ‖B_j‖₂): with ‖B_j‖₂ (1 + 64 u) ≤ 1
// the amplitude grows by at most the inputs' terms, and the step changes
// q^(j) by at most (‖B_j − I‖₂ + 16 u) ρ_j plus those terms. Every weight is
// widened by kWiden, which covers these roundings, those of the bounds' own
// sums and of ρ_j's square root many times over.
void set_peak_bounds(SharedModel& m) noexcept {
  constexpr double u = 0x1p-53;
  constexpr double kWiden = 1.0 + 1e-12;
  bool contracts = true;
  double change[kBlockModes];
  for (int j = 0; j < kBlockModes; ++j) {
    const double* b0 = m.blocks[2 * j];
    const double* b1 = m.blocks[2 * j + 1];
    const double n = block_norm(b0[0], b0[1], b1[0], b1[1]);
    contracts = contracts && std::isfinite(n) && n * (1.0 + 64.0 * u) <= 1.0;
    change[j] = block_norm(b0[0] - 1.0, b0[1], b1[0], b1[1] - 1.0) + 16.0 * u;
  }
  m.peak_bounds = contracts;
  const auto set = [&](PeakBoundModel& g, auto row_weight) {
    g = PeakBoundModel{};
    for (int j = 0; j < kBlockModes; ++j) {
      double w = 0.0;
      for (int i = 1; i < kBlockDofs; ++i) w = std::max(w, row_weight(i, j));
      g.weight[j] = w * kWiden;
      g.rate_weight[j] = w * change[j] * kWiden;
      const double ga = norm2(m.gamma[2 * j][0], m.gamma[2 * j + 1][0]);
      const double gf = norm2(m.gamma[2 * j][1], m.gamma[2 * j + 1][1]);
      g.per_ag += g.weight[j] * ga;
      g.per_force += g.weight[j] * gf;
      g.rate_per_ag += g.rate_weight[j] * ga;
      g.rate_per_force += g.rate_weight[j] * gf;
    }
    g.per_ag *= kWiden;
    g.per_force *= kWiden;
    g.rate_per_ag *= kWiden;
    g.rate_per_force *= kWiden;
  };
  set(m.floor_bound, [&](int i, int j) { return norm2(m.accel_rows[i][2 * j], m.accel_rows[i][2 * j + 1]); });
  set(m.drift_bound, [&](int i, int j) {
    const double* c = m.disp_rows[i];
    const double* below = m.disp_rows[i - 1];
    return norm2(c[2 * j] - below[2 * j], c[2 * j + 1] - below[2 * j + 1]) +
           16.0 * u * (norm2(c[2 * j], c[2 * j + 1]) + norm2(below[2 * j], below[2 * j + 1]));
  });
}

}  // namespace mrd::batch
