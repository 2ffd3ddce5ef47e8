#include "host_sim/rths/benchmark.hpp"

#include <stdexcept>

#include "host_sim/excitation/ground_motion.hpp"
#include "host_sim/structure/building.hpp"

namespace mrd::rths {

const std::vector<double> kBenchmarkStiffness_n_m{
    26054883.88,  -23133938.88, 5937035.46,    //
    -23133938.88, 32560774.19,  -14419970.78,  //
    5937035.46,   -14419970.78, 9267275.51,
};

structure::BuildingParams benchmark_structure(int case_number) {
  struct Case {
    double mass_kg, ratio;
  };
  static constexpr Case kCases[] = {{1000.0, 0.05}, {1100.0, 0.04}, {1300.0, 0.03}, {1000.0, 0.03}};
  if (case_number < 1 || case_number > 4) throw std::invalid_argument("benchmark_structure: case must be 1..4");
  const Case c = kCases[case_number - 1];
  structure::BuildingParams b;
  b.name = "silva-2020-3dof-case" + std::to_string(case_number);
  b.base = structure::BaseKind::kFixed;
  b.mass_kg.assign(3, c.mass_kg);
  b.stiffness_matrix_n_m = kBenchmarkStiffness_n_m;
  // The chain seen from the matrix (building_params.hpp).
  b.story_stiffness_n_m = {kBenchmarkStiffness_n_m[0] + kBenchmarkStiffness_n_m[3], -kBenchmarkStiffness_n_m[3],
                           -kBenchmarkStiffness_n_m[7]};
  b.story_damping_n_s_m.assign(3, 0.0);
  b.rayleigh = structure::RayleighDamping{c.ratio, 1, 2};
  b.dampers = {structure::DamperPlacement{0, 1}};
  return b;
}

StructureMatrices structure_matrices(const structure::BuildingParams& b) {
  structure::validate(b);
  return {structure::mass_matrix(b), structure::damping_matrix(b), structure::stiffness_matrix(b)};
}

std::vector<double> benchmark_record(const std::filesystem::path& file, double scale, double rate_hz) {
  excitation::GroundMotion g = excitation::read_ground_motion(file);
  for (double& a : g.accel_m_s2) a *= scale;
  return excitation::resample_linear(g, 1.0 / rate_hz);
}

}  // namespace mrd::rths
