#pragma once
/// Lanes of closed-loop runs on any building (lane_block_any.hpp): builds
/// the shared model from a plant spec, owns the lanes' arrays, and reads
/// each lane's sensed values, time-series samples and summary back as the
/// scalar plant (plant::Plant) gives them.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "host_sim/batch/lane_block_any.hpp"
#include "host_sim/batch/lane_stepper.hpp"
#include "host_sim/plant/plant.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "mrd/physics/lost_motion_play.hpp"
#include "mrd/physics/mr_damper.hpp"

namespace mrd::batch {

class AnyLanes {
 public:
  /// Throws std::invalid_argument for a hardware plant or an invalid building.
  AnyLanes(const plant::PlantSpec& spec, const LaneKernel& kernel);
  AnyLanes(const AnyLanes&) = delete;
  AnyLanes& operator=(const AnyLanes&) = delete;

  int lanes() const noexcept { return kernel_.any_lanes; }
  const LaneKernel& kernel() const noexcept { return kernel_; }
  /// Lane l at rest (Plant::init) with settling quotient `sq`, reading 0 m/s².
  void rest(int l, double sq);
  /// Lane l reads a_g[n] = scale · ground[n].
  void start(int l, const double* ground, double scale) noexcept;
  void set_command(int l, double current_a) noexcept { block_.command_a[l] = current_a; }

  void run(std::size_t ticks) { kernel_.any_run(model_, block_, ticks); }
  void sense() { kernel_.any_sense(model_, block_); }
  void advance() { kernel_.any_advance(model_, block_); }

  LaneSensed sensed(int l) const noexcept;
  /// run::run_closed_loop's record layout for this building.
  void start_record(run::ClosedLoopRecord& rec, std::size_t n) const;
  /// Appends what advance() reached (roof and floor accelerations, isolator force, drifts).
  void record_after(int l, run::ClosedLoopRecord& rec) const;
  /// Plant::summary() of lane l after `ticks` ticks.
  plant::PlantSummary summary(int l, std::size_t ticks, double sq) const;

 private:
  const plant::PlantSpec& spec_;
  const LaneKernel& kernel_;
  AnyModel model_{};
  AnyBlock block_{};
  // What model_ points into.
  std::vector<double> blocks_, phi_, gamma_, t_rows_, accel_rows_, inv_mass_;
  std::vector<int> element_of_, damper_element_, damper_slot_;
  std::vector<unsigned> damper_count_;
  std::vector<std::uint8_t> first_on_slot_;
  std::vector<AnyIsolatorGroup> groups_;
  std::vector<physics::LostMotionPlay> plays_;  ///< a lost motion's plays, [damper · kMaxLanes + lane]
  std::vector<physics::MrDamper> dampers_;      ///< a law the lanes do not vectorize, [damper · kMaxLanes + lane]
  // What block_ points into (64-byte aligned rows of kMaxLanes doubles).
  struct alignas(64) Row {
    double v[kMaxLanes];
  };
  std::vector<Row> rows_;

  double row_value(const double* rows, int k, int l) const noexcept { return rows[k * kMaxLanes + l]; }
  /// disp_m(i) of lane l, as DiscreteBuilding sums it.
  double disp_m(int l, int i) const noexcept;
};

}  // namespace mrd::batch
