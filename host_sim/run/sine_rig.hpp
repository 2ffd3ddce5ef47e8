#pragma once
/// The sine characterization rig of thesis §5.2: the damper driven with a
/// displacement sine at constant current after an idle time, and the metrics
/// of Table 5.2.

#include <vector>

#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::run {

/// One sine test on the rig.
struct SineRigSpec {
  double amplitude_m = 0.0254;   ///< displacement amplitude, m
  double frequency_hz = 0.5;
  double current_a = 2.5;        ///< constant coil current, A
  double idle_time_s = 0.0;      ///< idle time before the test, s (sets SQ, Eq. 5.4–5.5)
  double duration_s = 60.0;
  double step_s = 1.0e-3;
};

/// Table 5.2 metrics. Definitions (as the table uses them):
/// - fully_mixed_force: the largest |F| of the same test on fully mixed
///   fluid (SQ = 0), i.e. the force the damper should give;
/// - max_force: the largest |F| over the whole test;
/// - initial_force: |F| at the first velocity peak, before any fluid has
///   been displaced (PR = a_PR). The displacement A sin(2π f t) starts at its
///   velocity peak, so this is the force at t = 0;
/// - rise_time_90 / rise_time_95: the first time |F| reaches 90 % / 95 % of
///   max_force ("Calc. 90 % of Experimental Force"), from the test's start.
struct SineMetrics {
  double fully_mixed_force_n = 0.0;
  double max_force_n = 0.0;
  double initial_force_n = 0.0;
  double rise_time_90_s = 0.0;
  double rise_time_95_s = 0.0;
  double sq = 0.0;
};

struct SineRecord {
  std::vector<double> time_s, disp_m, vel_m_s, force_n, current_a, pr;
};

/// Runs the rig. The coil current is steady at `current_a` from the start
/// (the thesis supplied a constant current); the displacement is
/// A sin(2π f t) with its exact velocity A ω cos(ω t).
SineMetrics run_sine_rig(const SineRigSpec& spec, const physics::MrDamperParams& damper = {},
                         const physics::SettlingParams& settling = {}, SineRecord* record = nullptr);

/// One row of Table 5.1 / 5.2: the test and what was measured.
struct ThesisSineCase {
  const char* name;
  SineRigSpec spec;
  double fully_mixed_force_kn;
  double max_force_kn;
  double initial_force_kn;
  double rise_time_90_s;
  double rise_time_95_s;
};

/// The three cases of Table 5.1 with the measurements of Table 5.2 (a).
const std::vector<ThesisSineCase>& thesis_sine_cases();

}  // namespace mrd::run
