#pragma once
/// The RTHS runtime of the thesis's set-up on the board (`mrd-rths
/// --building`): any building numerical (its damper placement is the
/// physical part: the damper's force comes from the laboratory), the MR
/// damper in the laboratory behind a servo-hydraulic actuator
/// (`mrd-rths-lab --specimen damper`, damper_lab_node.hpp), and the board's
/// firmware control task (the same control core and task as `mrd-firmware`)
/// beside it, reading the DAQ and drive frames and commanding the drive as in
/// the closed loop. Each tick n:
///
/// <pre>
///   1. drain the bus: DaqMotion with counter n (the actuator's stroke and the damper's force at t_n)
///      is fresh; an older one is used again and counted stale; the lab's "stopped" status ends the run
///   2. the control task's tick (control_tick): it has DaqMotion(n), DriveStatus(n) from the laboratory
///      and DaqAccel(n) from this runtime → CurrentCommand(n) to the laboratory's drive
///   3. the compensator's specimen model steps with that current at the actuator model's stroke and rate
///   4. the building steps to t_{n+1} with count × the measured force on the damper's element
///   5. DaqAccel(n+1): a_g[n+1] and the building's absolute base acceleration at t_{n+1}, sent now,
///      a whole period before the control task needs it
///   6. RthsCommand(n){command, target x_t[n+1]}: the command is the model-based prediction over the
///      actuator's delay and lag (rths::DamperCommandPredictor), or the target when uncompensated; the
///      actuator model takes it
/// </pre>
///
/// The actuator model (rths::LookaheadServo with the identified delay and
/// lag, fed this runtime's commands) gives the stroke and rate the
/// compensator's specimen model is driven by. The run ends as BoardLoop's:
/// finished, lab_stopped, lab_silent, command_out_of_range, interrupted.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <optional>

#include "host_sim/rths/numerical_building.hpp"
#include "host_sim/rths/thesis_actuator.hpp"
#include "host_sim/rths_board/board_loop.hpp"
#include "host_sim/structure/building.hpp"
#include "mrd/control/io.hpp"
#include "mrd/hal/can_bus.hpp"
#include "mrd/hal/clock.hpp"
#include "mrd/physics/mr_damper.hpp"

namespace mrd::rths_board {

struct DamperLoopSpec {
  structure::BuildingParams building;  ///< one damper placement (isolators: their hysteresis in the closed loop's sub-steps)
  physics::MrDamperParams damper{};    ///< the compensator's model of the specimen
  double settling_quotient = 1.0;      ///< the model's idle state
  double delay_s = 0.015;              ///< the actuator's identified delay (≥ one step)
  double lag_s = 0.002;                ///< and lag
  bool compensate = true;
  double rate_hz = 1000.0;
  std::vector<double> ground_accel_m_s2;  ///< at the loop rate
  protocol::NodeIds nodes{};              ///< the runtime sends RthsCommand as `controller`, DaqAccel as `daq`
  std::uint8_t lab_node = kDefaultLabNode;
  int lab_silent_ticks = 50;
  /// The laboratory steps on its own clock (mrd-rths-lab --own-clock): a
  /// sample is fresh when it is newer than the last one taken, whatever its
  /// counter (its counter is the laboratory's step, not this tick).
  bool lab_own_clock = false;
};

class DamperLoop {
 public:
  /// The control task's tick: runs it on what has arrived, returns its output.
  using ControlTick = std::function<control::ControllerOutput()>;

  /// Reserves every record. Throws std::invalid_argument for an empty
  /// record, a rate outside 100..65535 Hz, a building without exactly one
  /// damper placement, or a delay under one step.
  DamperLoop(hal::CanBus& bus, const DamperLoopSpec& spec, ControlTick control_tick);

  /// Drains the bus for the lab's beacon: true once a "waiting" status and
  /// DaqMotion 0 have arrived (then DaqAccel 0 is sent). A lab at another
  /// rate is refused (rate_mismatch() holds its rate).
  bool lab_ready() noexcept;
  std::uint16_t rate_mismatch() const noexcept { return lab_rate_mismatch_hz_; }

  LoopEnd tick() noexcept;
  /// Free-running: each tick first waits on the bus for the laboratory's
  /// sample of that tick, at most `sample_wait_ns` past the tick's start (a
  /// blocking wait, so a laboratory on the same CPU gets to answer), then
  /// ticks on what has arrived; absolute deadlines every `period_ns`.
  LoopEnd run_periodic(hal::Clock& clock, std::int64_t period_ns, const std::atomic<bool>& stop,
                       std::int64_t sample_wait_ns) noexcept;
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

  /// Peak |x_0| of the numerical building over the run (the last state too), m.
  double peak_base_displacement_m() const noexcept { return peak_base_m_; }
  /// Records over ticks 0..ticks()-1: the target stroke, the measured stroke
  /// and force, the command, the coil current command stage, the base displacement.
  const std::vector<double>& target_m() const noexcept { return target_; }
  const std::vector<double>& measured_m() const noexcept { return measured_; }
  const std::vector<double>& force_n() const noexcept { return force_; }
  const std::vector<double>& command_m() const noexcept { return command_; }
  const std::vector<double>& current_a() const noexcept { return current_; }
  const std::vector<double>& base_displacement_m() const noexcept { return base_; }
  /// 100·rms(measured − target)/rms(target) over the ticks run.
  double rms_tracking_error_pct() const noexcept;

 private:
  void drain() noexcept;
  void await_sample(hal::Clock& clock, std::int64_t until_ns) noexcept;
  void send_accel(std::size_t n) noexcept;

  hal::CanBus& bus_;
  DamperLoopSpec spec_;
  double dt_s_;
  ControlTick control_tick_;
  rths::NumericalBuilding building_;  ///< stepped as the closed loop's plant steps it
  physics::MrDamper model_;
  rths::LookaheadServo actuator_model_;
  int element_ = 0;
  double count_ = 1.0;
  std::size_t slot_ = 0;
  std::optional<rths::DamperCommandPredictor> predictor_;           ///< without isolators
  std::optional<rths::IsolatedCommandPredictor> isolated_predictor_;  ///< with them (copies the building per tick)
  std::vector<double> forces_, accel_;
  std::uint64_t k_ = 0;
  protocol::DaqMotion meas_{};
  std::uint8_t taken_counter_ = 0;  ///< counter of the sample the last tick took (own clock)
  bool fresh_ = false, have_meas0_ = false, lab_waiting_ = false, sent_accel0_ = false;
  std::uint16_t lab_rate_mismatch_hz_ = 0;
  int silent_run_ = 0;
  LoopEnd end_ = LoopEnd::kRunning;
  LabStopReason lab_reason_ = LabStopReason::kNone;
  LoopTimingRecord timing_{};
  std::uint32_t stale_ticks_ = 0, rejected_ = 0, tx_errors_ = 0;
  std::uint8_t run_status_counter_ = 0;
  double peak_base_m_ = 0.0;
  std::vector<double> target_, measured_, force_, command_, current_, base_;
  std::vector<std::int64_t> tick_ns_;
};

}  // namespace mrd::rths_board
