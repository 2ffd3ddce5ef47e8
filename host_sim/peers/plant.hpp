#pragma once
/// The simulated world on the far side of the CAN bus: the 6-DOF building
/// and the MR damper (with idle-time effects and coil dynamics), stepped in
/// exactly the order of run::run_closed_loop (host_sim/run/closed_loop.hpp):
///
/// <pre>
///   sense(a_g[n]):   x_b[n], v_b[n], F[n] = damper(v_b[n], i[n], PR[n]), accelerations, i[n]
///   advance(u[n]):   i[n+1], PR[n+1] from u[n], |v_b[n]|  (Eq. 4.5, 5.9)
///                    z[n+1] = Φ z[n] + Γ [a_g[n], F[n]]    (ZOH-exact)
/// </pre>
///
/// so that a run over CAN, where u[n] comes back from the controller through
/// the drive, reproduces the in-process run operation for operation. The
/// sensor values are the floats run_closed_loop hands its controller.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "mrd/physics/mr_damper.hpp"
#include "mrd/physics/settling.hpp"
#include "host_sim/structure/discrete_building.hpp"

namespace mrd::peers {

struct PlantSpec {
  double step_s = 1.0e-3;
  double idle_years = 0.0;
  structure::BuildingParams building{};
  physics::MrDamperParams damper{};
  physics::SettlingParams settling{};
};

/// The same peaks as run::ClosedLoopSummary, computed the same way.
struct PlantSummary {
  double peak_base_displacement_m = 0.0;
  double peak_damper_force_n = 0.0;
  double peak_superstructure_accel_m_s2 = 0.0;
  double peak_base_accel_m_s2 = 0.0;
  double peak_current_a = 0.0;
  double final_participant_ratio = 0.0;
  double sq = 0.0;
  double duration_s = 0.0;
  std::uint64_t ticks = 0;
};

/// One tick's sensor values, as floats (what the DAQ and the drive measure).
struct PlantSensors {
  float damper_disp_m = 0.0f;
  float damper_force_n = 0.0f;
  float ground_accel_m_s2 = 0.0f;
  float base_accel_m_s2 = 0.0f;
  float coil_current_a = 0.0f;
};

class PlantModel {
 public:
  /// Designs the building at spec.step_s and sets the damper's settling
  /// quotient from the idle time (Eq. 5.5). Throws std::invalid_argument for
  /// a bad step.
  void init(const PlantSpec& spec);

  /// Sensors at t_n for ground acceleration `ground_accel_m_s2` (held over the step).
  PlantSensors sense(double ground_accel_m_s2) noexcept;

  /// Advances to t_{n+1} with the coil drive `command_a` held over the step
  /// (0 when the drive's output is off).
  void advance(double command_a) noexcept;

  /// Peaks so far, including the state reached by the last advance().
  PlantSummary summary() const noexcept;

  double coil_current_a() const noexcept { return damper_.current_a(); }
  double base_disp_m() const noexcept { return building_.base_disp_m(); }
  double step_s() const noexcept { return spec_.step_s; }

 private:
  PlantSpec spec_{};
  structure::DiscreteBuilding building_{};
  physics::MrDamper damper_{};
  structure::Vector6 accel_{};
  PlantSummary s_{};
  // The tick in progress (set by sense(), used by advance()).
  double ag_ = 0.0, xb_ = 0.0, vb_ = 0.0, force_n_ = 0.0;
};

/// The ground motion as `mrd sim` loads it (run::load_study_motion): read the
/// record (CSV or PEER AT2), scale it to `pga_g`, resample it to `step_s`
/// over `duration_s` (> 0) or the whole record. Throws io::UsageError
/// naming the file, line and field for a bad record.
std::vector<double> load_ground_accel(const std::filesystem::path& record, double pga_g, double step_s,
                                      double duration_s);

}  // namespace mrd::peers
