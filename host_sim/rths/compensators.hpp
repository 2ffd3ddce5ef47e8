#pragma once
/// Delay and lag compensators of an RTHS: each turns the target displacement
/// the actuator must reach at the next step into the command sent now.
///
/// - none: command = target.
/// - sample (the benchmark's sample controller): the phase lead
///   (50.8316 s + 8570.397)/(s + 8570.397) on the target (exact ZOH of its
///   state-space form), plus a PI with K_p = 2, K_i = 95 1/s on the tracking
///   error (lead output − measured).
/// - polynomial (Horiuchi et al. 1999): the target extrapolated τ ahead by
///   the third-order polynomial through its last four samples, τ the
///   identified plant's delay.
/// - adaptive (adaptive time series, Chae, Kazemibidokhti and Ricles 2013):
///   command = a0·x_t + a1·ẋ_t + a2·ẍ_t (derivatives by backward differences
///   of the target), the coefficients fitted by least squares over a sliding
///   window to the relation command ≈ a0·x_m + a1·ẋ_m + a2·ẍ_m of the past
///   commands and measurements (both through one low-pass filter, which the
///   relation commutes with, so the filter's own lag cancels), updated only
///   when the window's motion is well above the sensor noise, each update
///   rate-limited and the coefficients bounded.
/// - model (model-based feedforward): command = Σ c_i·dⁱx_t/dtⁱ, i = 0..3,
///   the c_i initially the low-frequency expansion 1/Ĝ(s) ≈ c0 + c1 s + c2 s²
///   + c3 s³ of the identified plant Ĝ, then c0..c2 adapted by a normalized
///   gradient step on the same filtered relation as `adaptive`, bounded.

#include <array>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "host_sim/rths/state_space.hpp"

namespace mrd::rths {

enum class CompensatorKind { kNone, kSample, kPolynomial, kAdaptive, kModel };

/// "none", "sample", "polynomial", "adaptive", "model".
const char* compensator_name(CompensatorKind k);
/// Parses a name above; false when unknown.
bool compensator_from_name(const std::string& name, CompensatorKind& out);

/// The identified plant as the compensators use it: 1/Ĝ(s) ≈ c0 + c1 s +
/// c2 s² + c3 s³ near s = 0 (c1/c0 the plant's delay, s).
struct InverseExpansion {
  std::array<double, 4> c{1.0, 0.0, 0.0, 0.0};
};

/// The expansion of 1/G for a single-input single-output output `out` of a
/// stable continuous system: from the moments G(s) = g0 + g1 s + g2 s² + g3 s³
/// + …, g_i = −C·A^{−(i+1)}·B (i ≥ 1; g0 = −C A⁻¹ B + D), inverted as a power series.
InverseExpansion inverse_expansion(const ContinuousSystem& g, int out = 0);

class Compensator {
 public:
  virtual ~Compensator() = default;
  /// The command for the next step from the target for it and the
  /// displacement measured now.
  virtual double command(double target_m, double measured_m) = 0;
  /// Names and current values of the compensator's coefficients (may be none).
  virtual std::vector<std::string> coefficient_names() const { return {}; }
  virtual std::vector<double> coefficients() const { return {}; }
  /// The same values into out[0 .. coefficient_names().size()), without
  /// allocating (a loop's record of them).
  virtual void write_coefficients(double* out) const noexcept { (void)out; }
};

struct CompensatorSpec {
  CompensatorKind kind = CompensatorKind::kNone;
  double dt_s = 1.0 / 4096.0;
  InverseExpansion plant;  ///< the identified plant (polynomial, adaptive, model)
  double window_s = 1.0;   ///< adaptive: least-squares window
  double update_s = 0.01;  ///< adaptive / model: time between coefficient updates
  double filter_hz = 10.0; ///< adaptive / model: the shared low-pass filter's corner
  double noise_m = 16e-6;  ///< the displacement sensor's noise σ (excitation threshold)
};

std::unique_ptr<Compensator> make_compensator(const CompensatorSpec& spec);

}  // namespace mrd::rths
