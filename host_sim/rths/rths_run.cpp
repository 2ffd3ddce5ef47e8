#include "host_sim/rths/rths_run.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrd::rths {

std::vector<std::vector<double>> reference_response(const StructureMatrices& b,
                                                    const std::vector<double>& ground_accel_m_s2, double dt_s) {
  const Eigen::Index n = b.m.rows();
  const Matrix m_inv = b.m.inverse();
  ContinuousSystem s;
  s.a = Matrix::Zero(2 * n, 2 * n);
  s.a.topRightCorner(n, n).setIdentity();
  s.a.bottomLeftCorner(n, n) = -m_inv * b.k;
  s.a.bottomRightCorner(n, n) = -m_inv * b.c;
  s.b = Matrix::Zero(2 * n, 1);
  s.b.bottomRows(n) = -Vector::Ones(n);  // M⁻¹·(−M·1)
  s.c = Matrix::Identity(2 * n, 2 * n).topRows(n);
  s.d = Matrix::Zero(n, 1);
  const DiscreteSystem d = zero_order_hold(s, dt_s);
  std::vector<std::vector<double>> out(static_cast<std::size_t>(n),
                                       std::vector<double>(ground_accel_m_s2.size(), 0.0));
  Vector z = Vector::Zero(2 * n);
  Vector next = Vector::Zero(2 * n);
  for (std::size_t k = 0; k < ground_accel_m_s2.size(); ++k) {
    for (Eigen::Index i = 0; i < n; ++i) out[static_cast<std::size_t>(i)][k] = z(i);
    next.noalias() = d.phi * z;
    next += d.gamma.col(0) * ground_accel_m_s2[k];
    z.swap(next);
  }
  return out;
}

RthsResult run_rths(const RthsSpec& spec) {
  if (spec.ground_accel_m_s2.empty()) throw std::invalid_argument("run_rths: empty record");
  if (!(spec.rate_hz >= 100.0 && spec.rate_hz <= 1e5)) throw std::invalid_argument("run_rths: rate out of range");
  const Eigen::Index n = spec.building.m.rows();
  if (spec.building.k.rows() != n || spec.building.c.rows() != n)
    throw std::invalid_argument("run_rths: M, C, K of different sizes");
  const double dt = 1.0 / spec.rate_hz;
  const std::size_t keep = static_cast<std::size_t>(std::max(1, spec.keep_every));

  const StructureMatrices numerical = without_specimen(spec.building, spec.plant.specimen, spec.specimen_dof);
  ChenRiclesIntegrator integrator(spec.building, numerical, spec.specimen_dof, dt);
  Laboratory lab(spec.plant, spec.lab, dt);
  CompensatorSpec cs = spec.compensator;
  cs.dt_s = dt;
  cs.plant = inverse_expansion(lab_plant_model(spec.identified_plant), 0);
  cs.noise_m = std::sqrt(spec.lab.displacement_noise_power_m2_hz / dt);
  const std::unique_ptr<Compensator> comp = make_compensator(cs);

  RthsResult r;
  r.dt_s = dt;
  r.coefficient_names = comp->coefficient_names();
  const std::size_t steps = spec.ground_accel_m_s2.size();
  std::vector<double> all_target(steps), all_measured(steps);
  std::vector<std::vector<double>> all_floors(static_cast<std::size_t>(n), std::vector<double>(steps));
  const std::size_t coeff_every = static_cast<std::size_t>(std::max(1L, std::lround(0.01 / dt)));
  double target_now = 0.0;  // x_t[k]: the substructure starts at rest
  double peak_target = 0.0;
  for (std::size_t k = 0; k < steps; ++k) {
    const LabMeasurement meas = lab.measure();
    all_target[k] = target_now;
    all_measured[k] = meas.displacement_m;
    for (Eigen::Index i = 0; i < n; ++i) all_floors[static_cast<std::size_t>(i)][k] = integrator.displacement_m()(i);
    const double target_next = integrator.step(spec.ground_accel_m_s2[k], meas.force_n);
    const double command = comp->command(target_next, meas.displacement_m);
    if (k % keep == 0) {
      r.time_s.push_back(static_cast<double>(k) * dt);
      r.target_m.push_back(target_now);
      r.measured_m.push_back(meas.displacement_m);
      r.command_m.push_back(command);
      r.force_n.push_back(meas.force_n);
    }
    if (k % coeff_every == 0 && !r.coefficient_names.empty()) {
      r.coefficient_time_s.push_back(static_cast<double>(k) * dt);
      r.coefficients.push_back(comp->coefficients());
    }
    lab.step(command, target_next);
    peak_target = std::max(peak_target, std::fabs(target_next));
    target_now = target_next;
    if (lab.stopped() != LabStop::kNone && r.status == "ok") r.status = lab_stop_name(lab.stopped());
    if (!std::isfinite(target_next) && r.status == "ok") r.status = "unstable";
  }
  r.peak_force_n = lab.peak_force_n();

  const std::vector<std::vector<double>> ref = reference_response(spec.building, spec.ground_accel_m_s2, dt);
  r.criteria = evaluate_criteria(all_measured, all_target, all_floors, ref, dt);
  // A run whose response grows well past the reference's is unstable even
  // if the laboratory did not stop it.
  double peak_ref = 0.0;
  for (double v : ref[static_cast<std::size_t>(spec.specimen_dof)]) peak_ref = std::max(peak_ref, std::fabs(v));
  if (r.status == "ok" && peak_target > 2.0 * peak_ref) r.status = "unstable";
  for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
    std::vector<double> f, g;
    for (std::size_t k = 0; k < steps; k += keep) {
      f.push_back(all_floors[i][k]);
      g.push_back(ref[i][k]);
    }
    r.floors_m.push_back(std::move(f));
    r.reference_floors_m.push_back(std::move(g));
  }
  return r;
}

}  // namespace mrd::rths
