#pragma once
/// One closed-loop earthquake run as `mrd sim` makes it: a recorded or
/// synthetic motion at a PGA, the firmware control core in one mode and
/// numeric build, after an idle time.

#include <string>

#include "mrd/control/io.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/controller.hpp"
#include "host_sim/run/motions.hpp"

namespace mrd::run {

struct SimSpec {
  std::string record;           ///< CSV or PEER .AT2 file; empty: a synthetic motion
  double pga_g = kThesisPga_g;  ///< PGA the motion is scaled to, g
  control::ControlMode mode = control::ControlMode::kPassiveOff;
  NumericKind numeric = NumericKind::kFloat;
  double idle_years = 0.0;
  double duration_s = 0.0;      ///< 0: the record's length (40 s for a synthetic motion)
  double step_s = 1.0e-3;
  unsigned seed = 1;            ///< of the synthetic motion
  bool keep_record = false;     ///< keep the time series for the outputs
};

struct SimRun {
  SimSpec spec;
  StudyMotion motion;
  plant::PlantSummary summary;
  ClosedLoopRecord record;      ///< empty unless spec.keep_record
};

/// Synthetic motion length without a record and without a duration, s.
inline constexpr double kSyntheticSimDuration_s = 40.0;

/// Loads or synthesizes the motion and runs the loop with `controller`
/// (made for spec.mode, spec.numeric and spec.step_s). Throws io::UsageError
/// for a record that cannot be read.
SimRun run_sim(const SimSpec& spec, Controller& controller);

}  // namespace mrd::run
