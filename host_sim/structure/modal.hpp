#pragma once
/// Modal properties of the building without the MR damper (thesis §6.1:
/// f_1 = 0.25 Hz; ζ = 4.97 %, 3.17 %, 5.07 % in modes 1-3; Fig. 6.3).
///
/// The damping of Fig. 6.2 is not proportional, so the modes are complex.
/// Natural frequencies and damping ratios come from the eigenvalues of the
/// 2N×2N state matrix A (building.hpp), which come in pairs
///
/// <pre>
///   λ = −ζ ω_n ± i ω_n √(1 − ζ²)   ⇒   ω_n = |λ|,  ζ = −Re λ / |λ|
/// </pre>
///
/// Undamped frequencies and real mode shapes come from K φ = ω² M φ as a
/// cross-check (they differ from ω_n only through the non-proportional part
/// of C).
///
/// With nonlinear isolators the modes are those of the linear part: K holds
/// their post-yield stiffness (lead-rubber) or pendulum stiffness W/R
/// (friction pendulum), the stiffness they have once they slide.

#include <string>
#include <vector>

#include "host_sim/structure/building.hpp"

namespace mrd::structure {

struct ModalResult {
  /// Natural frequencies ω_n/2π of the damped modes, Hz, ascending.
  std::vector<double> frequencies_hz;
  /// Damping ratios ζ of the same modes, fraction (0.05 = 5 %).
  std::vector<double> damping_ratios;
  /// Periods 1/f of the same modes, s.
  std::vector<double> periods_s;
  /// Undamped frequencies √(eig(K, M))/2π, Hz, ascending.
  std::vector<double> undamped_frequencies_hz;
  /// Undamped mode shapes, one per column in the order of
  /// undamped_frequencies_hz; row i is DOF i (0 = base). Each column is
  /// scaled so that its largest-magnitude entry is +1.
  Matrix mode_shapes;
  /// Names of the DOFs, DOF 0 first: "base", "floor_1", ... (fixed base:
  /// "floor_1", ...).
  std::vector<std::string> dof_names;
  /// With isolators: which of their stiffnesses K holds (the post-yield or
  /// pendulum stiffness); empty without isolators.
  std::string isolator_stiffness;
};

/// Modal analysis of the building. Throws std::invalid_argument for invalid
/// parameters and std::runtime_error if an eigen-solver fails or a mode is
/// critically or over-damped (real eigenvalues), which has no frequency in
/// the sense above.
ModalResult modal_analysis(const BuildingParams& params);

}  // namespace mrd::structure
