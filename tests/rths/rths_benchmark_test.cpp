// The virtual RTHS benchmark (Silva et al. 2020) on plants drawn from its
// published uncertainty (normal, 1σ on β1, β2, a3, k_e) and both records
// (El Centro, Kobe, scaled by 0.4), at 4096 Hz: the adaptive time series
// must give J2 ≤ 3 % and J4 ≤ 5 % in every run and never stop or diverge
// (the published acceptance, the "done when"); the sample controller
// and no compensation are run beside it and printed. CI runs the first two
// drawn plants; MRD_RTHS_STUDY=1 runs all 20 and every compensator.
//
// The actuator's 8.9 kN limit is reported, not enforced as a stop: Kobe at
// 0.4 asks the specimen for k_e·8.39 mm = 10.0 kN in the all-numerical
// reference itself (checked below), so a stop at 8.9 kN would end every
// Kobe run, whatever the compensator.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <map>
#include <string>

#include "host_sim/rths/benchmark.hpp"
#include "host_sim/rths/rths_run.hpp"

namespace mrd::rths {
namespace {

const std::filesystem::path kRecordsRthsBench = std::filesystem::path(MRD_SHARED_DIR) / "ground_motions";

struct StudyCell {
  double worst_j2 = 0.0, worst_j4 = 0.0, worst_force_n = 0.0;
  int runs = 0, not_ok = 0;
};

RthsResult run_benchmark_case(const StructureMatrices& building, const std::vector<double>& record,
                              const LabPlantParams& plant, CompensatorKind kind, std::uint64_t seed) {
  RthsSpec s;
  s.building = building;
  s.plant = plant;
  s.identified_plant = LabPlantParams{};
  s.lab.force_limit_n = HUGE_VAL;  // reported, see the file comment
  s.lab.noise_seed = seed;
  s.compensator.kind = kind;
  s.rate_hz = 4096.0;
  s.ground_accel_m_s2 = record;
  s.keep_every = 4096;  // the test needs the criteria only
  return run_rths(s);
}

TEST(RthsBenchmark, KobeAsksMoreThanTheActuatorsLimitInTheReference) {
  const StructureMatrices b = structure_matrices(benchmark_structure(1));
  const auto record = benchmark_record(kRecordsRthsBench / "kobe_jma_ns.csv", kBenchmarkRecordScale, 4096.0);
  const auto ref = reference_response(b, record, 1.0 / 4096.0);
  double peak = 0.0;
  for (double x : ref[0]) peak = std::max(peak, std::fabs(x));
  EXPECT_GT(peak * Specimen{}.stiffness_n_m, 8.9e3);
}

TEST(RthsBenchmark, DrawnPlantsBothRecords) {
  const bool full = std::getenv("MRD_RTHS_STUDY") != nullptr;
  const int plants = full ? 20 : 2;
  const StructureMatrices building = structure_matrices(benchmark_structure(1));
  std::vector<CompensatorKind> kinds{CompensatorKind::kAdaptive, CompensatorKind::kSample, CompensatorKind::kNone};
  if (full) kinds = {CompensatorKind::kAdaptive, CompensatorKind::kModel, CompensatorKind::kPolynomial,
                     CompensatorKind::kSample, CompensatorKind::kNone};
  std::map<std::string, StudyCell> cells;
  for (const char* file : {"elcentro_ns.csv", "kobe_jma_ns.csv"}) {
    const auto record = benchmark_record(kRecordsRthsBench / file, kBenchmarkRecordScale, 4096.0);
    std::mt19937_64 rng(20200939);
    for (int p = 0; p < plants; ++p) {
      const LabPlantParams plant = draw_lab_plant(LabPlantParams{}, LabPlantUncertainty{}, rng);
      for (const CompensatorKind kind : kinds) {
        // None and the sample controller: the first plant only in CI.
        if (!full && kind != CompensatorKind::kAdaptive && p > 0) continue;
        const RthsResult r = run_benchmark_case(building, record, plant, kind, 1000u + static_cast<unsigned>(p));
        StudyCell& c = cells[std::string(file) + " " + compensator_name(kind)];
        c.runs += 1;
        c.not_ok += r.status == "ok" ? 0 : 1;
        c.worst_j2 = std::max(c.worst_j2, r.criteria.j[1]);
        c.worst_j4 = std::max(c.worst_j4, r.criteria.j[3]);
        c.worst_force_n = std::max(c.worst_force_n, r.peak_force_n);
        if (kind == CompensatorKind::kAdaptive) {
          EXPECT_EQ(r.status, "ok") << file << " plant " << p;
          EXPECT_LE(r.criteria.j[1], 3.0) << file << " plant " << p;
          EXPECT_LE(r.criteria.j[3], 5.0) << file << " plant " << p;
        }
      }
    }
  }
  for (const auto& [name, c] : cells)
    std::printf("%-28s runs %2d  not ok %2d  worst J2 %8.2f %%  worst J4 %8.2f %%  peak force %7.0f N\n", name.c_str(),
                c.runs, c.not_ok, c.worst_j2, c.worst_j4, c.worst_force_n);
}

}  // namespace
}  // namespace mrd::rths
