#include "building_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ibuild {
namespace {

/// The symmetric tridiagonal A = M^(−½) K M^(−½) of the chain: diagonal
/// (k_i + k_{i+1}) / m_i, off-diagonal −k_{i+1} / √(m_i m_{i+1}).
struct Tridiagonal {
  std::vector<double> diag;
  std::vector<double> off;  ///< off[i] joins rows i and i+1
};

Tridiagonal chain_matrix(const Building& b) {
  const std::size_t n = b.mass_kg.size();
  Tridiagonal t;
  t.diag.resize(n);
  t.off.resize(n > 0 ? n - 1 : 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double above = i + 1 < n ? b.stiffness_n_m[i + 1] : 0.0;
    t.diag[i] = (b.stiffness_n_m[i] + above) / b.mass_kg[i];
    if (i + 1 < n) t.off[i] = -b.stiffness_n_m[i + 1] / std::sqrt(b.mass_kg[i] * b.mass_kg[i + 1]);
  }
  return t;
}

/// Number of eigenvalues of `t` below `x` (Sturm sequence count).
std::size_t eigenvalues_below(const Tridiagonal& t, double x) {
  std::size_t count = 0;
  double q = 1.0;
  for (std::size_t i = 0; i < t.diag.size(); ++i) {
    const double e2 = i == 0 ? 0.0 : t.off[i - 1] * t.off[i - 1];
    q = t.diag[i] - x - (i == 0 ? 0.0 : e2 / q);
    if (q == 0.0) q = -1e-300;  // x is an eigenvalue of the leading block: count it below
    if (q < 0.0) ++count;
  }
  return count;
}

}  // namespace

std::vector<double> undamped_frequencies_rad_s(const Building& b) {
  const Tridiagonal t = chain_matrix(b);
  const std::size_t n = t.diag.size();
  // Gershgorin bounds of the spectrum.
  double hi = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double left = i > 0 ? std::fabs(t.off[i - 1]) : 0.0;
    const double right = i + 1 < n ? std::fabs(t.off[i]) : 0.0;
    hi = std::max(hi, t.diag[i] + left + right);
  }
  std::vector<double> omegas(n);
  for (std::size_t k = 0; k < n; ++k) {
    double lo_k = 0.0;
    double hi_k = hi * (1.0 + 1e-12) + 1e-300;
    for (int it = 0; it < 200 && hi_k - lo_k > 1e-15 * hi_k; ++it) {
      const double mid = 0.5 * (lo_k + hi_k);
      if (eigenvalues_below(t, mid) > k) {
        hi_k = mid;
      } else {
        lo_k = mid;
      }
    }
    omegas[k] = std::sqrt(std::max(0.0, 0.5 * (lo_k + hi_k)));
  }
  return omegas;
}

std::vector<double> mode_shape(const Building& b, double omega_rad_s) {
  const std::size_t n = b.mass_kg.size();
  const double w2 = omega_rad_s * omega_rad_s;
  std::vector<double> phi(n, 0.0);
  if (n == 0) return phi;
  phi[0] = 1.0;
  // Row i: −k_i φ_{i−1} + (k_i + k_{i+1} − ω² m_i) φ_i − k_{i+1} φ_{i+1} = 0.
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double below = i > 0 ? b.stiffness_n_m[i] * phi[i - 1] : 0.0;
    phi[i + 1] = ((b.stiffness_n_m[i] + b.stiffness_n_m[i + 1] - w2 * b.mass_kg[i]) * phi[i] - below) /
                 b.stiffness_n_m[i + 1];
  }
  double largest = 0.0;
  for (double p : phi) largest = std::max(largest, std::fabs(p));
  for (double& p : phi) p /= largest;
  return phi;
}

RayleighCoefficients rayleigh_coefficients(const Building& b, const RayleighSpec& spec) {
  const std::vector<double> w = undamped_frequencies_rad_s(b);
  const auto at = [&](int mode) {
    if (mode < 1 || mode > static_cast<int>(w.size())) throw std::invalid_argument("Rayleigh mode out of range");
    return w[static_cast<std::size_t>(mode - 1)];
  };
  const double wa = at(spec.mode_a);
  const double wb = at(spec.mode_b);
  return RayleighCoefficients{2.0 * spec.ratio * wa * wb / (wa + wb), 2.0 * spec.ratio / (wa + wb)};
}

double total_weight_n(const Building& b) {
  double m = 0.0;
  for (double mi : b.mass_kg) m += mi;
  return m * kGravity_m_s2;
}

}  // namespace ibuild
