#pragma once
/// The chapter-6 study: the four records of Table 6.2 at 0.1127 g (Table 6.3)
/// in every control mode, fully mixed against 2.5 years idle (Fig. 6.9–6.11),
/// the idle-time sweep (Fig. 6.12–6.20), and the chapter-5 checks it rests
/// on, written as a Markdown report with its plots.

#include <filesystem>
#include <string>
#include <vector>

#include "mrd/control/io.hpp"
#include "host_sim/run/closed_loop.hpp"

namespace mrd::run {

struct StudyOptions {
  double pga_g = 0.1127;
  double idle_years = 2.5;    ///< the idle case compared with fully mixed, years, as the report states it
  double step_s = 1.0e-3;
  bool with_sweep = true;
  unsigned threads = 0;
};

struct StudyRow {
  std::string motion;
  control::ControlMode mode = control::ControlMode::kPassiveOff;
  plant::PlantSummary fully_mixed;
  plant::PlantSummary idle;
};

struct StudyResult {
  std::vector<StudyRow> rows;
  bool synthetic_motions = false;
  std::vector<std::string> plot_problems;
};

/// Runs the study and writes `dir/report.md`, `dir/summary.json`, the
/// comparison plots and (with_sweep) the sweep outputs under `dir/sweep/`.
StudyResult run_study(const StudyOptions& options, const std::filesystem::path& dir);

}  // namespace mrd::run
