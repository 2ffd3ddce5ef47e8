#pragma once
/// The simulated peers as bus nodes: each wraps its behaviour (plant, drive
/// logic, actuator logic) and a hal::CanBus, and speaks the protocol through
/// the shared codec. The same classes run in the peer programs (SocketCAN,
/// any interface) and in the in-process `sim` board (in-memory bus).
///
/// Lockstep (deterministic, equal to the in-process simulation): the plant is
/// the master of time. Tick k, counter c = k mod 256:
/// <pre>
///   plant:      SimCoilState(c), DaqMotion(c), DaqAccel(c)        sensors at t_k
///   drive:      on SimCoilState(c) → DriveStatus(c)               measured i[k]
///   controller: when DaqMotion, DaqAccel, DriveStatus all carry c → step → CurrentCommand
///   drive:      on the command → SimCoilDrive(c)                  u[k]
///   plant:      on SimCoilDrive(c) → advance to t_{k+1}
/// </pre>
/// Free-running: each node ticks on its own monotonic clock; the drive and
/// the plant hold the latest value they received.

#include <cstdint>
#include <string>
#include <vector>

#include "mrd/hal/can_bus.hpp"
#include "host_sim/peers/actuator_logic.hpp"
#include "host_sim/peers/drive_logic.hpp"
#include "host_sim/plant/plant.hpp"

namespace mrd::peers {

/// DAQ + plant node: the plant (host_sim/plant/plant.hpp) with its sensors
/// sent as DAQ frames and its coil driven by the drive's SimCoilDrive.
class PlantNode {
 public:
  PlantNode(hal::CanBus& bus, const protocol::NodeIds& nodes, const plant::PlantSpec& spec);

  /// Lockstep: samples t_k for ground acceleration `ag` and sends the tick's frames.
  void begin_tick(double ground_accel_m_s2) noexcept;
  /// Lockstep: takes the SimCoilDrive of the pending tick if it arrived, and
  /// advances. True when the tick is complete.
  bool try_finish_tick() noexcept;
  /// Lockstep: completes the pending tick with the last coil drive received
  /// (the coil keeps its drive when a SimCoilDrive frame is lost).
  void force_finish_tick() noexcept;

  /// Free-running: one period: drain the drive's output, sample, send, advance.
  void free_tick(double ground_accel_m_s2) noexcept;

  const plant::Plant& model() const noexcept { return plant_; }
  std::uint64_t ticks() const noexcept { return tick_; }
  std::uint32_t rejected() const noexcept { return rejected_; }
  std::uint32_t encode_errors() const noexcept { return encode_errors_; }

 private:
  void send_sensors(const plant::PlantSensors& s, std::uint8_t counter) noexcept;
  void drain(bool lockstep) noexcept;

  hal::CanBus& bus_;
  protocol::NodeIds nodes_;
  plant::Plant plant_;
  protocol::CounterCheck drive_counter_{};
  std::uint64_t tick_ = 0;
  bool pending_ = false;
  bool got_drive_ = false;
  protocol::SimCoilDrive drive_{};
  std::uint32_t rejected_ = 0, encode_errors_ = 0;
};

/// PWM drive node.
class DriveNode {
 public:
  DriveNode(hal::CanBus& bus, const DriveConfig& config, double period_s);

  /// Lockstep: handles every received frame; sends DriveStatus on the plant's
  /// SimCoilState and SimCoilDrive once the tick's command arrived. Returns
  /// true when a tick was decided.
  bool poll() noexcept;
  /// Lockstep: decides the pending tick without a command (it did not come).
  void decide_without_command() noexcept;
  bool awaiting_command() const noexcept { return awaiting_; }

  /// Free-running: one drive period at `now_ns`: drain, decide, send status
  /// and coil drive.
  void free_tick(std::int64_t now_ns) noexcept;

  /// Injected drive fault (over-temperature, …) from now on.
  void set_fault(bool f) noexcept { fault_ = f; }
  const DriveLogic& logic() const noexcept { return logic_; }
  std::uint64_t ticks() const noexcept { return ticks_; }

 private:
  void decide(std::int64_t now_ns, std::uint8_t counter) noexcept;

  hal::CanBus& bus_;
  DriveConfig c_;
  DriveLogic logic_;
  std::int64_t period_ns_;
  bool fault_ = false;
  bool awaiting_ = false;
  std::uint8_t pending_counter_ = 0;
  std::uint8_t status_counter_ = 0;
  std::int64_t sim_now_ns_ = 0;
  std::uint64_t ticks_ = 0;
  float measured_a_ = 0.0f;
  protocol::CounterCheck coil_counter_{};
};

/// Mixing-actuator node (free-running; status every `status_period_ns`).
class ActuatorNode {
 public:
  ActuatorNode(hal::CanBus& bus, const ActuatorConfig& config, std::int64_t status_period_ns = 100'000'000);
  void free_tick(std::int64_t now_ns) noexcept;
  const ActuatorLogic& logic() const noexcept { return logic_; }

 private:
  hal::CanBus& bus_;
  ActuatorConfig c_;
  ActuatorLogic logic_;
  std::int64_t status_period_ns_;
  std::int64_t next_status_ns_ = 0;
  std::uint8_t counter_ = 0;
};

/// The DAQ of a building at rest while the mixing actuator strokes its
/// damper (a maintenance cycle, no earthquake): stroke = the actuator's
/// position, both accelerations zero, no force measured (sent as "not
/// available"). One DaqMotion and one DaqAccel per sample() (free-running).
class RestingDaqNode {
 public:
  RestingDaqNode(hal::CanBus& bus, const protocol::NodeIds& nodes) noexcept : bus_(bus), nodes_(nodes) {}
  void sample(double stroke_m) noexcept;
  std::uint64_t send_errors() const noexcept { return send_errors_; }

 private:
  hal::CanBus& bus_;
  protocol::NodeIds nodes_;
  std::uint8_t counter_ = 0;
  std::uint64_t send_errors_ = 0;
};

/// The CAN filters of each node (exact ids).
std::vector<hal::CanFilter> plant_filters(const protocol::NodeIds& n);
std::vector<hal::CanFilter> drive_filters(const protocol::NodeIds& n);
std::vector<hal::CanFilter> actuator_filters(const protocol::NodeIds& n);

}  // namespace mrd::peers
