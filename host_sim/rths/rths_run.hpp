#pragma once
/// One real-time hybrid simulation, emulated: the numerical substructure
/// (CR integration), a compensator, the laboratory (plant, converters,
/// sensors, stop), and the all-numerical reference beside it, at one loop
/// rate. Each tick k:
///
/// 1. the laboratory's sensors are read (x_m[k], f_m[k]);
/// 2. the substructure takes a_g[k] and f_m[k] and gives the target
///    x_t[k+1] at the specimen's DOF;
/// 3. the compensator turns x_t[k+1] (and x_m[k]) into the command;
/// 4. the laboratory holds the command over the step (ZOH) and advances.
///
/// The reference integrates the whole building (the specimen numerical) by
/// the exact zero-order hold of its state-space form at the same step.

#include <memory>
#include <string>
#include <vector>

#include "host_sim/rths/compensators.hpp"
#include "host_sim/rths/criteria.hpp"
#include "host_sim/rths/lab_plant.hpp"
#include "host_sim/rths/laboratory.hpp"
#include "host_sim/rths/substructure.hpp"

namespace mrd::rths {

struct RthsSpec {
  StructureMatrices building;       ///< the whole reference structure
  int specimen_dof = 0;             ///< DOF 1 of the benchmark (0-based 0)
  LabPlantParams plant;             ///< the laboratory's true plant
  LabPlantParams identified_plant;  ///< the plant the compensators were identified on
  LaboratorySpec lab;
  CompensatorSpec compensator;      ///< kind, window, ...; dt, plant and noise are filled in
  double rate_hz = 4096.0;
  std::vector<double> ground_accel_m_s2;  ///< at the loop rate, already scaled
  /// Keep every n-th sample of the time series (1: all).
  int keep_every = 1;
};

struct RthsResult {
  std::string status = "ok";  ///< "ok", the laboratory's stop ("force_limit", ...), or "unstable"
  Criteria criteria;
  double peak_force_n = 0.0;
  double dt_s = 0.0;
  /// Time series (every keep_every-th tick).
  std::vector<double> time_s, target_m, measured_m, command_m, force_n;
  std::vector<std::vector<double>> floors_m, reference_floors_m;  ///< [DOF][sample]
  std::vector<std::string> coefficient_names;
  std::vector<double> coefficient_time_s;
  std::vector<std::vector<double>> coefficients;  ///< [sample][coefficient], every 10 ms
};

/// Runs it. Throws std::invalid_argument for an empty record, a rate
/// outside 100 Hz–100 kHz or matrices of different sizes.
RthsResult run_rths(const RthsSpec& spec);

/// The whole building's displacements (every DOF) under the record, exact ZOH.
std::vector<std::vector<double>> reference_response(const StructureMatrices& b,
                                                    const std::vector<double>& ground_accel_m_s2, double dt_s);

}  // namespace mrd::rths
