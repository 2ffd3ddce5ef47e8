#pragma once
/// What `mrd rths --specimen damper` writes into its folder:
///
/// - summary.json: status (ok, unstable), warnings, the set-up (building, damper, fluid, record, control
///   mode, idle time, loop rate, actuator delay and lag, compensation) and
///   the result: the peak base displacement of the RTHS and of the
///   all-numerical closed loop run beside it, the gap between them (%), the
///   tracking errors and the peak damper force of both;
/// - tracking.csv: time_s, target_m, actuator_m, actuator_velocity_m_s,
///   command_m, force_n, current_a, base_displacement_m,
///   closed_loop_base_displacement_m, closed_loop_force_n (every tick);
/// - tracking.png (target and actuator stroke, their difference) and
///   base.png (base displacement and damper force, RTHS against the closed
///   loop), drawn by gnuplot when present.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_sim/rths/damper_rths.hpp"
#include "host_sim/run/closed_loop.hpp"

namespace mrd::rths {

/// The set-up as the summary records it.
struct DamperRthsDescription {
  std::string building;  ///< its name
  int dofs = 0;
  std::string damper;    ///< the damper file, or "thesis-200kn"
  std::string fluid;     ///< the fluid file, or "thesis-model-fluid"
  std::string record;    ///< the file
  double pga_g = 0.0;
  double scale_factor = 0.0;
  std::string control;   ///< the mode's name
  double idle_years = 0.0;
  double duration_s = 0.0;
};

/// What the command computed: the RTHS and the closed loop beside it.
struct DamperRthsOutcome {
  DamperRthsResult rths;
  DamperRthsRecord record;
  plant::PlantSummary closed_loop;
  run::ClosedLoopRecord closed_loop_record;
  /// 100·(RTHS − closed loop)/closed loop of the peak base displacement.
  double gap_pct() const;
  /// "ok", or "unstable" when the RTHS diverged: its peak base displacement
  /// more than twice the closed loop's (the benchmark's rule, rths_run.hpp),
  /// or it, the peak force or the tracking error not a finite number.
  std::string status() const;
};

/// Largest |gap| of the peak base displacement, %, the summary calls close
/// to the closed loop (the 2 %); beyond it a warning says so.
inline constexpr double kDamperRthsGapWarning_pct = 2.0;

/// Sentences, one per finding the user should see: the run diverged; the
/// peak base displacement is more than kDamperRthsGapWarning_pct off the
/// closed loop's. Empty for a run within it.
std::vector<std::string> damper_rths_warnings(const DamperRthsSpec& spec, const DamperRthsOutcome& o);

nlohmann::json damper_rths_summary_json(const DamperRthsSpec& spec, const DamperRthsDescription& d,
                                        const DamperRthsOutcome& o);

/// Writes the files above; returns the plots that could not be drawn, one
/// line each.
std::vector<std::string> write_damper_rths_outputs(const std::filesystem::path& dir, const DamperRthsSpec& spec,
                                                   const DamperRthsDescription& d, const DamperRthsOutcome& o);

}  // namespace mrd::rths
