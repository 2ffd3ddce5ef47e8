#pragma once
/// The chapter-6 study: the four records of Table 6.2 at 0.1127 g (Table 6.3)
/// in every control mode, fully mixed against 2.5 years idle (Fig. 6.9–6.11),
/// the idle-time sweep (Fig. 6.12–6.20), and the chapter-5 checks it rests
/// on. run_study computes it; write_study_outputs writes it as a Markdown
/// report with its plots.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mrd/control/io.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/sine_cases.hpp"
#include "host_sim/run/sweep.hpp"
#include "host_sim/structure/modal.hpp"

namespace mrd::run {

struct StudyOptions {
  double pga_g = 0.1127;
  double idle_years = 2.5;    ///< the idle case compared with fully mixed, years, as the report states it
  double step_s = 1.0e-3;
  bool with_sweep = true;
  unsigned threads = 0;
  structure::BuildingParams building{};  ///< the thesis building unless a building file is given
  physics::MrDamperParams damper{};      ///< the thesis damper unless a damper file is given
  physics::SettlingParams settling{};    ///< the thesis fluid in the thesis damper unless files are given
  std::string damper_name;               ///< the damper file's damper ("": the thesis damper, no file)
  std::string fluid_name;                ///< the fluid file's fluid ("": the thesis's model fluid, no file)
};

/// One record in one control mode, fully mixed and after the idle time.
struct StudyRow {
  std::string motion;         ///< the motion's name, e.g. "hachinohe_ns"
  std::string label;          ///< the motion's label, e.g. "Case a: Hachinohe"
  control::ControlMode mode = control::ControlMode::kPassiveOff;
  plant::PlantSummary fully_mixed;
  plant::PlantSummary idle;
  ClosedLoopRecord fully_mixed_record;  ///< time series, for the comparison plot
  ClosedLoopRecord idle_record;
};

/// The idle-time sweep of the study, 0 to 1 year every 0.05 year.
struct StudySweep {
  SweepSpec spec;
  std::vector<SweepRow> rows;
  double wall_s = 0.0;        ///< wall-clock time the sweep took
};

struct StudyResult {
  StudyOptions options;
  bool synthetic_motions = false;        ///< the shared records were absent
  structure::ModalResult modal;          ///< §6.1
  double max_settling_time_years = 0.0;  ///< Eq. 5.4
  std::vector<ThesisSineResult> sine_cases;  ///< Table 5.1 against Table 5.2
  std::vector<StudyRow> rows;            ///< motion-major, then mode
  std::optional<StudySweep> sweep;       ///< with_sweep only
};

/// Runs the study: modal analysis, the thesis sine cases, every record ×
/// mode fully mixed and idle, and (with_sweep) the idle-time sweep.
StudyResult run_study(const StudyOptions& options);

/// Where the study's runs (and its sweep's) leave the model's validity
/// (validity_warnings), as sentences.
std::vector<std::string> study_warnings(const StudyResult& result);

/// Writes `dir/report.md`, `dir/summary.json`, one comparison plot per
/// record and mode and (with a sweep) the sweep outputs under `dir/sweep/`.
/// `dir` must exist. Returns the reasons for plots that could not be drawn.
std::vector<std::string> write_study_outputs(const std::filesystem::path& dir, const StudyResult& result);

}  // namespace mrd::run
