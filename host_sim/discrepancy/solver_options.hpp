#pragma once
/// The Ceres settings every fit of the discrepancy workflow uses: bounded
/// Levenberg–Marquardt on a dense problem, quiet, one thread per fit (the
/// workflow runs fits in parallel itself).

#include <ceres/ceres.h>

namespace mrd::discrepancy {

[[nodiscard]] inline ceres::Solver::Options lm_solver_options(int max_iterations) {
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = max_iterations;
  so.function_tolerance = 1e-10;
  so.gradient_tolerance = 1e-12;
  so.parameter_tolerance = 1e-9;
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  return so;
}

}  // namespace mrd::discrepancy
