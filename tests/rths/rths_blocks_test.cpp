// The RTHS blocks against hand calculations: the control plant's DC gain,
// the zero-order hold of a first-order lag, the inverse expansion of a lag,
// the polynomial extrapolation of a cubic, the converters' step, the noise
// variance from a noise power, the CR integrator's static deflection and
// period, the criteria on known signals, and the laboratory's stop.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "host_sim/rths/compensators.hpp"
#include "host_sim/rths/criteria.hpp"
#include "host_sim/rths/lab_plant.hpp"
#include "host_sim/rths/laboratory.hpp"
#include "host_sim/rths/state_space.hpp"
#include "host_sim/rths/substructure.hpp"

namespace mrd::rths {
namespace {

constexpr double kPiRthsBlocks = 3.14159265358979323846;

TEST(RthsPlant, DcGainIsTheLoopsByHand) {
  // At s = 0: G_s = a1β0/β2, G_0 = G_a·G_est/(1 + 0) = 1/(a3·k_e), so with
  // L = a1β0/(β2·a3·k_e) = 2.1283e13/(9.9976e4·3.3·1.19e6) = 54.21,
  // G(0) = gain·L/(1 + L) = 1.0261·0.98189 = 1.00752.
  const LabPlantParams p;
  const double l = 2.1283e13 / (9.9976e4 * 3.3 * 1190e3);
  const double expected = 1.0261 * l / (1.0 + l);
  EXPECT_NEAR(expected, 1.00752, 1e-5);
  EXPECT_NEAR(dc_gain(lab_plant_model(p))(0, 0), expected, 1e-9);
  // The force output at DC: the specimen's spring, F = k_e·x.
  EXPECT_NEAR(dc_gain(lab_plant_model(p))(1, 0), expected * 1190e3, 1e-6 * 1190e3);
}

TEST(RthsPlant, SpecimenDampingIsTwoZetaRootKm) {
  // 2·0.0097·√(1.19e6·29.13) = 0.0194·5887.7 = 114.22 N·s/m.
  EXPECT_NEAR(Specimen{}.damping_n_s_m(), 114.22, 0.01);
}

TEST(RthsStateSpace, ZeroOrderHoldOfAFirstOrderLag) {
  // ẋ = −a x + u: Φ = e^{−a·dt}, Γ = (1 − e^{−a·dt})/a.
  const double a = 30.0, dt = 1e-3;
  ContinuousSystem s{Matrix::Constant(1, 1, -a), Matrix::Constant(1, 1, 1.0), Matrix::Constant(1, 1, 1.0),
                     Matrix::Zero(1, 1)};
  const DiscreteSystem d = zero_order_hold(s, dt);
  EXPECT_NEAR(d.phi(0, 0), std::exp(-a * dt), 1e-14);
  EXPECT_NEAR(d.gamma(0, 0), (1.0 - std::exp(-a * dt)) / a, 1e-14);
}

TEST(RthsStateSpace, InverseExpansionOfALagIsOnePlusTauS) {
  // G = 1/(τ s + 1): 1/G = 1 + τ s exactly.
  const double tau = 0.02;
  ContinuousSystem s{Matrix::Constant(1, 1, -1.0 / tau), Matrix::Constant(1, 1, 1.0 / tau),
                     Matrix::Constant(1, 1, 1.0), Matrix::Zero(1, 1)};
  const InverseExpansion h = inverse_expansion(s);
  EXPECT_NEAR(h.c[0], 1.0, 1e-12);
  EXPECT_NEAR(h.c[1], tau, 1e-12);
  EXPECT_NEAR(h.c[2], 0.0, 1e-12);
  EXPECT_NEAR(h.c[3], 0.0, 1e-12);
}

TEST(RthsStateSpace, PlantDelayMatchesItsPhaseAtLowFrequency) {
  // c1/c0 of 1/G is −dφ/dω at ω → 0: the phase at 0.5 Hz is −ω·τ within
  // the curvature (−ω³ terms), 0.3 % at this frequency.
  const ContinuousSystem g = lab_plant_model(LabPlantParams{});
  const InverseExpansion h = inverse_expansion(g);
  const double w = 2.0 * kPiRthsBlocks * 0.5;
  EXPECT_NEAR(-std::arg(frequency_response(g, w)) / w, h.c[1] / h.c[0], 0.003 * h.c[1] / h.c[0]);
}

TEST(RthsCompensators, PolynomialExtrapolatesACubicExactly) {
  // A third-order polynomial through four samples of a cubic is the cubic:
  // the command is x(t + τ'), τ' = τ − Δt/2 (the hold's half-step lead).
  const double dt = 1.0 / 4096.0, tau = 0.012;
  CompensatorSpec spec;
  spec.kind = CompensatorKind::kPolynomial;
  spec.dt_s = dt;
  spec.plant.c = {1.0, tau, 0.0, 0.0};
  auto comp = make_compensator(spec);
  const auto cubic = [](double t) { return 0.3 + 2.0 * t - 5.0 * t * t + 7.0 * t * t * t; };
  double last = 0.0;
  double t = 0.0;
  for (int k = 0; k < 10; ++k) {
    t = k * dt;
    last = comp->command(cubic(t), 0.0);
  }
  EXPECT_NEAR(last, cubic(t + tau - 0.5 * dt), 1e-12);
}

TEST(RthsCompensators, NamesRoundTrip) {
  for (const char* n : {"none", "sample", "polynomial", "adaptive", "model"}) {
    CompensatorKind k{};
    ASSERT_TRUE(compensator_from_name(n, k)) << n;
    EXPECT_STREQ(compensator_name(k), n);
  }
  CompensatorKind k{};
  EXPECT_FALSE(compensator_from_name("smith", k));
}

TEST(RthsCompensators, SampleLeadHasUnitDcGain) {
  // (50.8316 s + 8570.397)/(s + 8570.397) at s = 0 is 1, at s → ∞ 50.8316.
  // A measurement that answers the previous command exactly keeps the PI's
  // error at 0 (by induction from rest), so the command is the lead's output:
  // 50.8316·x at the first step of a step input (the ZOH's D), x at the end.
  CompensatorSpec spec;
  spec.kind = CompensatorKind::kSample;
  auto comp = make_compensator(spec);
  double u = comp->command(0.002, 0.0);
  EXPECT_NEAR(u, 50.8316 * 0.002, 1e-12);
  for (int k = 0; k < 4096; ++k) u = comp->command(0.002, u);
  EXPECT_NEAR(u, 0.002, 1e-12);
}

TEST(RthsLaboratory, ConverterStepIsSpanOverTwoToTheBits) {
  // ±3.8 V, 18 bit: 7.6 V/262144 = 28.99 µV; on ±38 mm that is 0.29 µm.
  const double step_m = 2.0 * 0.038 / 262144.0;
  EXPECT_NEAR(Laboratory::quantize(0.3 * step_m, 0.038, 3.8, 18), 0.0, 1e-15);
  EXPECT_NEAR(Laboratory::quantize(0.7 * step_m, 0.038, 3.8, 18), step_m, 1e-15);
  EXPECT_NEAR(Laboratory::quantize(1.0, 0.038, 3.8, 18), 0.038, 1e-15);  // clipped at full scale
}

TEST(RthsLaboratory, NoiseVarianceIsPowerTimesSampleRate) {
  // P = 6.25e-14 m²/Hz at 4096 Hz: σ² = P·f_s = 2.56e-10 m², σ = 16.0 µm;
  // the force's 1.16e-3 N²/Hz: σ = √4.751 = 2.180 N. 40000 samples: the
  // sample σ within 2 % (its standard error is 1/√(2N) = 0.35 %).
  LaboratorySpec spec;
  Laboratory lab(LabPlantParams{}, spec, 1.0 / 4096.0);
  double sx = 0.0, sf = 0.0;
  const int n = 40000;
  for (int i = 0; i < n; ++i) {
    const LabMeasurement m = lab.measure();
    sx += m.displacement_m * m.displacement_m;
    sf += m.force_n * m.force_n;
  }
  EXPECT_NEAR(std::sqrt(sx / n), 16.0e-6, 0.02 * 16.0e-6);
  EXPECT_NEAR(std::sqrt(sf / n), 2.180, 0.02 * 2.180);
}

TEST(RthsLaboratory, StopsAtTheForceLimitAndHolds) {
  // A 10 mm command on the specimen asks k_e·10 mm = 11.9 kN > 8.9 kN.
  LaboratorySpec spec;
  spec.displacement_noise_power_m2_hz = 0.0;
  spec.force_noise_power_n2_hz = 0.0;
  Laboratory lab(LabPlantParams{}, spec, 1.0 / 4096.0);
  for (int k = 0; k < 4096 && lab.stopped() == LabStop::kNone; ++k) lab.step(0.010, lab.true_displacement_m());
  EXPECT_EQ(lab.stopped(), LabStop::kForceLimit);
  EXPECT_STREQ(lab_stop_name(lab.stopped()), "force_limit");
}

TEST(RthsSubstructure, StaticDeflectionAndPeriodOfASingleMass) {
  // One mass m = 1000 kg, k = 4e6 N/m, no damping, no specimen force, a
  // constant ground acceleration a = 1 m/s²: x oscillates about −m·a/k =
  // −0.25 mm between 0 and −0.5 mm, with CR's (trapezoidal) period
  // 2π/ω̃, ω̃ = (2/Δt)·atan(ω·Δt/2), ω = √(k/m) = 63.25 rad/s.
  const double m = 1000.0, k = 4e6, dt = 1e-3;
  StructureMatrices s{Matrix::Constant(1, 1, m), Matrix::Zero(1, 1), Matrix::Constant(1, 1, k)};
  ChenRiclesIntegrator cr(s, s, 0, dt);
  std::vector<double> x;
  for (int i = 0; i < 20000; ++i) x.push_back(cr.step(1.0, 0.0));
  double lo = 0.0, hi = -1.0;
  double mean = 0.0;
  for (double v : x) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    mean += v;
  }
  mean /= static_cast<double>(x.size());
  EXPECT_NEAR(mean, -m / k, 0.01 * m / k);
  EXPECT_NEAR(lo, -2.0 * m / k, 0.01 * m / k);
  EXPECT_NEAR(hi, 0.0, 0.01 * m / k);
  // Period from the upward crossings of the mean.
  std::vector<double> crossings;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i - 1] < mean && x[i] >= mean)
      crossings.push_back((static_cast<double>(i) - 1.0 + (mean - x[i - 1]) / (x[i] - x[i - 1])) * dt);
  ASSERT_GE(crossings.size(), 10u);
  const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double w = std::sqrt(k / m);
  EXPECT_NEAR(period, 2.0 * kPiRthsBlocks / ((2.0 / dt) * std::atan(w * dt / 2.0)), 1e-5);
}

TEST(RthsCriteria, KnownSignals) {
  // measured = 1.1·target: J2 = J3 = 10 %; measured = target delayed by 5
  // steps: J1 = 5·dt.
  const double dt = 1e-3;
  std::vector<double> t, m, d;
  for (int i = 0; i < 4000; ++i) {
    t.push_back(std::sin(2.0 * kPiRthsBlocks * 2.0 * i * dt));
    m.push_back(1.1 * t.back());
    d.push_back(std::sin(2.0 * kPiRthsBlocks * 2.0 * (i - 5) * dt));
  }
  EXPECT_NEAR(normalized_rms_error_pct(m, t), 10.0, 1e-9);
  EXPECT_NEAR(normalized_peak_error_pct(m, t), 10.0, 1e-9);
  EXPECT_NEAR(cross_correlation_lag_s(d, t, dt, 50), 5.0 * dt, 1e-12);
}

}  // namespace
}  // namespace mrd::rths
