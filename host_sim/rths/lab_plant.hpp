#pragma once
/// The laboratory's control plant of the virtual RTHS benchmark (Silva et al.
/// 2020): a servo-hydraulic actuator under its own proportional loop, driving
/// the specimen (a single-degree-of-freedom mass-spring-damper).
///
/// <pre>
///   G = gain·feedback(G_s·G_0, 1),   G_s = a1β0 / (s² + β1 s + β2)
///   G_0 = feedback(G_a·G_est, a2·s), G_a = 1 / (s + a3),
///   G_est = 1 / (m_e s² + c_e s + k_e),  c_e = 2 ζ_e √(k_e m_e)
/// </pre>
///
/// realized with the physical states z = [q, q̇, F, x, ẋ]: q the servo-valve's
/// output, F the actuator force (N), x the specimen's displacement (m):
///
/// <pre>
///   q̈ = −β2 q − β1 q̇ + a1β0 (gain·r − x)   (G_s on the loop's error, r the command)
///   Ḟ = −a3 F + q − a2 ẋ                    (G_a with the velocity feedback a2·s)
///   m_e ẍ = F − c_e ẋ − k_e x               (G_est)
/// </pre>
///
/// Outputs: the specimen's displacement x (m) and the force F (N). G is
/// single-input single-output, so where its gain sits does not change G
/// (its DC gain, gain·G_sG_0(0)/(1 + G_sG_0(0)), is 1.0075); it is put on the
/// command (the command channel's calibration, which brings the inner loop's
/// DC error 1/(1 + G_sG_0(0)) = 1.8 % back to about 1): then the measured
/// displacement is the specimen's own, and the measured force answers it.
/// On the output instead, the sensor would read 2.6 % more than the specimen
/// moves and the specimen's force would be 2.5 % short of what its measured
/// displacement implies, an error no compensator could see.

#include <random>

#include "host_sim/rths/state_space.hpp"

namespace mrd::rths {

/// The specimen at DOF 1 of the benchmark (published values).
struct Specimen {
  double mass_kg = 29.13;
  double stiffness_n_m = 1190e3;
  double damping_ratio = 0.0097;
  /// c_e = 2 ζ_e √(k_e m_e), N·s/m.
  double damping_n_s_m() const;
};

/// The plant's published nominal parameters (SI: β1 1/s, β2 1/s², a3 1/s).
struct LabPlantParams {
  double gain = 1.0261;
  double a1_beta0 = 2.1283e13;
  double a2 = 4.2297e6;
  double beta1 = 425.0;
  double beta2 = 9.9976e4;
  double a3 = 3.3;
  Specimen specimen;
};

/// The published 1σ uncertainty (normal): β1 ±3.3, β2 ±3.3e3, a3 ±1.3,
/// k_e ±50 kN/m.
struct LabPlantUncertainty {
  double beta1 = 3.3;
  double beta2 = 3.3e3;
  double a3 = 1.3;
  double specimen_stiffness_n_m = 50e3;
};

/// The continuous model above: input r (m), outputs [gain·x (m), F (N)].
ContinuousSystem lab_plant_model(const LabPlantParams& p);

/// One plant drawn from the nominal values and the uncertainty (a normal draw
/// per parameter, in the order β1, β2, a3, k_e).
LabPlantParams draw_lab_plant(const LabPlantParams& nominal, const LabPlantUncertainty& u, std::mt19937_64& rng);

}  // namespace mrd::rths
