#pragma once
/// The emulated laboratory as a node on the CAN bus (`mrd-rths-lab`): the
/// benchmark's servo-hydraulic actuator with its specimen, converters and
/// sensor noise (rths::Laboratory), stepped once per command from the RTHS
/// runtime, its measurement sent back for the runtime's next tick:
///
/// <pre>
///   before the run:  measurement 0 + status "waiting" (the beacon, sent by the program every 100 ms)
///   command k:       laboratory.step(command, target)  →  measurement for tick k + 1
///   a stop:          the actuator holds its last command (rths::Laboratory), status "stopped"
///                    with the reason after every command from then on
///   run status:      the runtime's end of run: the node is finished
/// </pre>
///
/// The stop is the laboratory's: |force| beyond the force limit or |measured
/// − target| beyond the tracking limit (LaboratorySpec), a command that is not
/// finite, or (stop_for_command_timeout, called by the program) no command for
/// too long once running. Nothing in serve() allocates except the laboratory's
/// own Eigen temporaries.

#include <cstdint>

#include "host_sim/rths/laboratory.hpp"
#include "host_sim/rths_board/rths_fd_frames.hpp"
#include "host_sim/rths_board/rths_frames.hpp"
#include "mrd/hal/can_bus.hpp"
#include "mrd/hal/can_fd_bus.hpp"

namespace mrd::rths_board {

struct LabNodeConfig {
  std::uint8_t runtime_node = 1;
  std::uint8_t lab_node = kDefaultLabNode;
  double rate_hz = 1000.0;  ///< one laboratory step per command, 1/rate_hz long
  rths::LabPlantParams plant;
  rths::LaboratorySpec spec;
  /// Commands and measurements as CAN FD frames (rths_fd_frames.hpp); the bus must be a
  /// hal::CanFdBus with FD enabled. Status frames stay classic.
  bool can_fd = false;
};

class LabNode {
 public:
  /// Throws std::invalid_argument for a rate outside 100 Hz..65535 Hz, or for
  /// `can_fd` on a bus that does not carry FD frames.
  LabNode(hal::CanBus& bus, const LabNodeConfig& config);

  /// Measurement 0 and the status (waiting before the first command).
  void send_beacon() noexcept;
  /// Every frame received: commands step the laboratory (one step each) and
  /// answer with the next measurement; the runtime's run status finishes the
  /// node. Returns the commands taken.
  int serve() noexcept;
  /// No command for too long while running: hold and report the stop.
  void stop_for_command_timeout() noexcept;

  bool finished() const noexcept { return finished_; }
  RunState run_state() const noexcept { return run_state_; }
  LabState state() const noexcept { return state_; }
  LabStopReason stop_reason() const noexcept { return stop_; }
  std::uint64_t steps() const noexcept { return steps_; }
  std::uint64_t stop_step() const noexcept { return stop_step_; }
  std::uint32_t rejected() const noexcept { return rejected_; }
  std::uint32_t sequence_gaps() const noexcept { return sequence_gaps_; }
  std::uint32_t tx_errors() const noexcept { return tx_errors_; }
  double peak_force_n() const noexcept { return lab_.peak_force_n(); }

 private:
  void take(double command_m, double target_m, bool in_sequence) noexcept;
  void send_measurement() noexcept;
  void send_status() noexcept;
  void send(const hal::CanFrame& f) noexcept;

  hal::CanBus& bus_;
  hal::CanFdBus* fd_bus_ = nullptr;  ///< set with config.can_fd
  LabNodeConfig config_;
  rths::Laboratory lab_;
  rths::LabMeasurement now_{};
  LabState state_ = LabState::kWaiting;
  LabStopReason stop_ = LabStopReason::kNone;
  RunState run_state_ = RunState::kFinished;
  bool finished_ = false;
  std::uint64_t steps_ = 0, stop_step_ = 0;
  std::uint32_t rejected_ = 0, sequence_gaps_ = 0, tx_errors_ = 0;
  std::uint8_t status_counter_ = 0;
};

}  // namespace mrd::rths_board
