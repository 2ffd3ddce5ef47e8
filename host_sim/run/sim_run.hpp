#pragma once
/// One closed-loop earthquake run as `mrd sim` makes it: a recorded or
/// synthetic motion at a PGA, the firmware control core in one mode and
/// numeric build, after an idle time.

#include <cstdint>
#include <string>

#include "mrd/control/io.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/motions.hpp"

namespace mrd::run {

/// `record` value for a run without ground motion (zero acceleration).
inline constexpr const char* kNoRecord = "none";

struct SimSpec {
  std::string record;           ///< CSV or PEER .AT2 file; kNoRecord: no ground motion; empty: a synthetic motion
  double pga_g = kThesisPga_g;  ///< PGA the motion is scaled to, g
  control::ControlMode mode = control::ControlMode::kPassiveOff;
  NumericKind numeric = NumericKind::kFloat;
  double idle_years = 0.0;
  double duration_s = 0.0;      ///< 0: the record's length (40 s for a synthetic motion)
  double step_s = 1.0e-3;
  std::uint64_t seed = 1;       ///< of the synthetic motion
  bool keep_record = false;     ///< keep the time series for the outputs
  plant::PlantKind plant = plant::PlantKind::kThesis;
  std::uint64_t sensor_seed = 1;   ///< of the hardware plant's sensor noise
  double stroke_offset_m = 0.003;  ///< where the hardware plant's damper is parked off centre, m
  structure::BuildingParams building{};  ///< the thesis building unless a building file is given
  physics::MrDamperParams damper{};      ///< the thesis damper unless a damper file is given
  physics::SettlingParams settling{};    ///< the thesis fluid in the thesis damper unless files are given
  plant::PwmDriveParams hardware_drive{};  ///< the hardware plant's drive (§3.2 unless a drive file's)
  std::string hardware_drive_name = "thesis-pwm";  ///< its name (the drive file's [drive] name)
};

struct SimRun {
  SimSpec spec;
  StudyMotion motion;
  plant::PlantSummary summary;
  ClosedLoopRecord record;      ///< empty unless spec.keep_record
};

/// Synthetic motion length without a record and without a duration, s.
inline constexpr double kSyntheticSimDuration_s = 40.0;

/// Loads or synthesizes the motion (zero acceleration over spec.duration_s
/// for kNoRecord) and runs the loop on spec.plant with `controller` (made for
/// spec.mode, spec.numeric and spec.step_s). Throws io::UsageError for a
/// record that cannot be read, or kNoRecord without a duration.
SimRun run_sim(const SimSpec& spec, Controller& controller);

}  // namespace mrd::run
