#include "host_sim/rths/lab_plant.hpp"

#include <cmath>

namespace mrd::rths {

double Specimen::damping_n_s_m() const { return 2.0 * damping_ratio * std::sqrt(stiffness_n_m * mass_kg); }

ContinuousSystem lab_plant_model(const LabPlantParams& p) {
  const double m = p.specimen.mass_kg;
  const double k = p.specimen.stiffness_n_m;
  const double c = p.specimen.damping_n_s_m();
  enum { kQ, kQdot, kF, kX, kXdot };
  ContinuousSystem s;
  s.a = Matrix::Zero(5, 5);
  s.b = Matrix::Zero(5, 1);
  s.c = Matrix::Zero(2, 5);
  s.d = Matrix::Zero(2, 1);
  s.a(kQ, kQdot) = 1.0;
  s.a(kQdot, kQ) = -p.beta2;
  s.a(kQdot, kQdot) = -p.beta1;
  s.a(kQdot, kX) = -p.a1_beta0;
  s.b(kQdot, 0) = p.a1_beta0 * p.gain;
  s.a(kF, kF) = -p.a3;
  s.a(kF, kQ) = 1.0;
  s.a(kF, kXdot) = -p.a2;
  s.a(kX, kXdot) = 1.0;
  s.a(kXdot, kF) = 1.0 / m;
  s.a(kXdot, kX) = -k / m;
  s.a(kXdot, kXdot) = -c / m;
  s.c(0, kX) = 1.0;
  s.c(1, kF) = 1.0;
  return s;
}

LabPlantParams draw_lab_plant(const LabPlantParams& nominal, const LabPlantUncertainty& u, std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  LabPlantParams p = nominal;
  p.beta1 += u.beta1 * n(rng);
  p.beta2 += u.beta2 * n(rng);
  p.a3 += u.a3 * n(rng);
  p.specimen.stiffness_n_m += u.specimen_stiffness_n_m * n(rng);
  return p;
}

}  // namespace mrd::rths
