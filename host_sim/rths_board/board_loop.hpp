#pragma once
/// The RTHS runtime on the board (`mrd-rths`): the numerical substructure
/// integrated at the loop rate, the actuator's command out over CAN, the
/// laboratory's measured displacement and force in. Each tick k:
///
/// <pre>
///   1. drain the bus: the measurement for tick k (counter k mod 256) is fresh; an older one is
///      used again and counted stale; the lab's "stopped" status ends the run
///   2. the substructure takes a_g[k] and f_m[k] → target x_t[k+1]   (rths::ChenRiclesIntegrator)
///   3. the compensator turns x_t[k+1] and x_m[k] into the command     (rths::make_compensator)
///   4. RthsCommand{command, target} out; the sample recorded in storage reserved before the run
/// </pre>
///
/// It is the loop of rths::run_rths with the laboratory on the far side of
/// the bus: with the lab answering within the tick, the same samples in the
/// same order. Free-running (run_periodic), the ticks are paced by
/// app::PeriodicSchedule on the board's monotonic clock, and its overruns and
/// worst lateness are kept with the longest tick's own run time.
///
/// The run ends: finished (every sample of the record), lab_stopped (the
/// laboratory's stop, with its reason), lab_silent (no fresh measurement for
/// lab_silent_ticks ticks in a row), command_out_of_range (a command or target
/// beyond the frame's ±83.9 mm, or not finite), interrupted (the stop flag).

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "host_sim/rths/compensators.hpp"
#include "host_sim/rths/criteria.hpp"
#include "host_sim/rths/lab_plant.hpp"
#include "host_sim/rths/substructure.hpp"
#include "host_sim/rths_board/rths_frames.hpp"
#include "mrd/hal/can_bus.hpp"
#include "mrd/hal/can_fd_bus.hpp"
#include "mrd/hal/clock.hpp"

namespace mrd::rths_board {

struct BoardLoopSpec {
  rths::StructureMatrices building;  ///< the whole structure (the reference)
  int specimen_dof = 0;              ///< 0-based
  rths::Specimen specimen;           ///< taken off the numerical substructure
  rths::LabPlantParams identified_plant;  ///< what the compensators were identified on
  rths::CompensatorSpec compensator;      ///< kind and windows; dt, plant and noise filled in
  double displacement_noise_power_m2_hz = 6.25e-14;  ///< for the compensators' excitation threshold
  double rate_hz = 1000.0;
  std::vector<double> ground_accel_m_s2;  ///< at the loop rate, scaled
  std::uint8_t runtime_node = 1;
  std::uint8_t lab_node = kDefaultLabNode;
  int lab_silent_ticks = 50;
  /// Command and measurement as CAN FD frames (rths_fd_frames.hpp); the bus must be a
  /// hal::CanFdBus with FD enabled. Status frames stay classic.
  bool can_fd = false;
};

enum class LoopEnd { kRunning, kFinished, kLabStopped, kLabSilent, kCommandOutOfRange, kInterrupted };
/// "running", "ok", the lab's stop reason for kLabStopped ("tracking_limit", …),
/// "lab_silent", "command_out_of_range", "interrupted".
std::string loop_end_status(LoopEnd e, LabStopReason lab_reason);

/// Timing of the free-running loop.
struct LoopTimingRecord {
  std::uint32_t overruns = 0;       ///< periods missed (app::PeriodicSchedule)
  std::int64_t worst_late_ns = 0;   ///< latest end of a tick past its deadline
  std::int64_t worst_tick_ns = 0;   ///< longest tick, start to command sent
  std::int64_t median_tick_ns = 0;  ///< of every tick's run time (after the loop)
  std::int64_t p99_tick_ns = 0;     ///< 99th percentile of the same
  std::int64_t period_ns = 0;
};

/// After a run: the median and 99th-percentile tick of `tick_ns` (each
/// tick's run time) into `timing`; nothing for an empty record.
void record_tick_percentiles(const std::vector<std::int64_t>& tick_ns, LoopTimingRecord& timing);

/// Tells the laboratory the run is over: three RthsRunStatus frames from
/// `node` with the end and the ticks run, `counter` advanced per frame.
/// Returns the frames the bus refused.
std::uint32_t send_run_status_frames(hal::CanBus& bus, std::uint8_t node, LoopEnd end, std::uint64_t ticks,
                                     std::uint8_t& counter) noexcept;

class BoardLoop {
 public:
  /// Reserves every record. Throws std::invalid_argument for an empty
  /// record, a rate outside 100..65535 Hz or matrices of different sizes.
  BoardLoop(hal::CanBus& bus, const BoardLoopSpec& spec);

  /// Drains the bus for the lab's beacon: true once a "waiting" status and
  /// measurement 0 have arrived. A lab at another rate is refused
  /// (rate_mismatch() then holds its rate).
  bool lab_ready() noexcept;
  std::uint16_t rate_mismatch() const noexcept { return lab_rate_mismatch_hz_; }

  /// One tick on what has arrived (see the file comment).
  LoopEnd tick() noexcept;
  /// Ticks on `clock` every `period_ns` with absolute deadlines until the run
  /// ends or `stop` is set; then sends the run status.
  LoopEnd run_periodic(hal::Clock& clock, std::int64_t period_ns, const std::atomic<bool>& stop) noexcept;
  /// Tells the laboratory the run is over (three frames).
  void send_run_status() noexcept;

  LoopEnd end() const noexcept { return end_; }
  LabStopReason lab_reason() const noexcept { return lab_reason_; }
  std::uint64_t ticks() const noexcept { return k_; }
  std::uint64_t steps() const noexcept { return spec_.ground_accel_m_s2.size(); }
  double dt_s() const noexcept { return dt_s_; }
  const LoopTimingRecord& timing() const noexcept { return timing_; }
  std::uint32_t stale_ticks() const noexcept { return stale_ticks_; }
  std::uint32_t rejected() const noexcept { return rejected_; }
  std::uint32_t tx_errors() const noexcept { return tx_errors_; }
  std::uint64_t frames_rx() const noexcept { return frames_rx_; }

  /// The records over ticks 0..ticks()-1.
  const std::vector<double>& target_m() const noexcept { return target_; }
  const std::vector<double>& measured_m() const noexcept { return measured_; }
  const std::vector<double>& command_m() const noexcept { return command_; }
  const std::vector<double>& force_n() const noexcept { return force_; }
  const std::vector<std::vector<double>>& floors_m() const noexcept { return floors_; }
  const std::vector<std::string>& coefficient_names() const noexcept { return coefficient_names_; }
  const std::vector<double>& coefficient_time_s() const noexcept { return coefficient_time_s_; }
  /// The compensator's coefficients at coefficient_time_s()[i]: coefficient_names().size() values.
  const double* coefficient_row(std::size_t i) const noexcept {
    return coefficient_values_.data() + i * coefficient_names_.size();
  }

  /// J1–J9 of the ticks run, against the all-numerical reference over the
  /// same samples (computed here, after the loop).
  rths::Criteria criteria() const;

 private:
  void drain() noexcept;

  void take_measurement(double displacement_m, double force_n, bool for_this_tick, bool first) noexcept;
  bool send_command(double command_m, double target_m) noexcept;

  hal::CanBus& bus_;
  hal::CanFdBus* fd_bus_ = nullptr;  ///< set with spec.can_fd
  BoardLoopSpec spec_;
  double dt_s_;
  rths::ChenRiclesIntegrator integrator_;
  std::unique_ptr<rths::Compensator> comp_;
  std::uint64_t k_ = 0;
  double target_now_ = 0.0;
  RthsMeasurement meas_{};
  bool fresh_ = false;
  bool have_meas0_ = false, lab_waiting_ = false;
  std::uint16_t lab_rate_mismatch_hz_ = 0;
  int silent_run_ = 0;
  LoopEnd end_ = LoopEnd::kRunning;
  LabStopReason lab_reason_ = LabStopReason::kNone;
  LoopTimingRecord timing_{};
  std::uint32_t stale_ticks_ = 0, rejected_ = 0, tx_errors_ = 0;
  std::uint64_t frames_rx_ = 0;
  std::uint8_t run_status_counter_ = 0;
  std::size_t coeff_every_ = 10;
  std::vector<double> target_, measured_, command_, force_;
  std::vector<std::vector<double>> floors_;
  std::vector<std::string> coefficient_names_;
  std::vector<double> coefficient_time_s_;
  std::vector<double> coefficient_values_;  ///< row after row, sized before the run
  std::vector<std::int64_t> tick_ns_;  ///< every tick's run time, free-running
};

}  // namespace mrd::rths_board
