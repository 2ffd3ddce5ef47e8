#include "host_sim/structure/modal.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mrd/units.hpp"

namespace mrd::structure {
namespace {

constexpr double kTwoPi = 2.0 * units::kPi;

struct DampedMode {
  double omega_rad_s;
  double zeta;
};

}  // namespace

ModalResult modal_analysis(const BuildingParams& params) {
  const ContinuousModel cm = continuous_model(params);
  ModalResult r;

  // Damped modes: one eigenvalue of each conjugate pair (Im λ > 0).
  // Dynamic sizes (one-time analysis; the fixed-size solvers unrolled into
  // half of this file's compile time).
  Eigen::EigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(cm.a), /*computeEigenvectors=*/false);
  if (es.info() != Eigen::Success) throw std::runtime_error("modal analysis: eigenvalues of A did not converge");
  const int dofs = params.dofs();
  std::vector<DampedMode> modes(static_cast<std::size_t>(dofs));
  int n = 0;
  for (int k = 0; k < 2 * dofs; ++k) {
    const std::complex<double> lambda = es.eigenvalues()(k);
    if (lambda.imag() <= 0.0) continue;
    if (n == dofs) break;
    const double w = std::abs(lambda);
    modes[n++] = DampedMode{w, -lambda.real() / w};
  }
  if (n != dofs) {
    throw std::runtime_error("modal analysis: a mode is critically or over-damped (real eigenvalues of A)");
  }
  std::sort(modes.begin(), modes.end(),
            [](const DampedMode& a, const DampedMode& b) { return a.omega_rad_s < b.omega_rad_s; });
  for (int k = 0; k < dofs; ++k) {
    r.frequencies_hz.push_back(modes[k].omega_rad_s / kTwoPi);
    r.damping_ratios.push_back(modes[k].zeta);
    r.periods_s.push_back(1.0 / r.frequencies_hz.back());
  }

  // Undamped modes: K φ = ω² M φ; Eigen returns ω² ascending.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> gs(Eigen::MatrixXd(stiffness_matrix(params)),
                                                              Eigen::MatrixXd(mass_matrix(params)));
  if (gs.info() != Eigen::Success) throw std::runtime_error("modal analysis: K φ = ω² M φ did not converge");
  r.mode_shapes = Matrix::Zero(dofs, dofs);
  for (int k = 0; k < dofs; ++k) {
    r.undamped_frequencies_hz.push_back(std::sqrt(gs.eigenvalues()(k)) / kTwoPi);
    Vector phi = gs.eigenvectors().col(k);
    Eigen::Index imax = 0;
    phi.cwiseAbs().maxCoeff(&imax);
    phi /= phi(imax);
    r.mode_shapes.col(k) = phi;
  }
  const bool fixed = params.base == BaseKind::kFixed;
  for (int i = 0; i < dofs; ++i) {
    r.dof_names.push_back(i == 0 && !fixed ? std::string("base") : "floor_" + std::to_string(fixed ? i + 1 : i));
  }
  if (!params.isolators.empty()) {
    r.isolator_stiffness =
        "isolators at their post-yield stiffness (lead-rubber k_p) and pendulum stiffness (friction pendulum W/R)";
  }
  return r;
}

}  // namespace mrd::structure
