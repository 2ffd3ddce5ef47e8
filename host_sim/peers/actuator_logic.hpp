#pragma once
/// The optional mixing actuator's behaviour on the bus: runs a sinusoidal
/// mixing cycle x(t) = A sin(2π f t) for the requested duration when the
/// controller asks (thesis §5: ±76.2 mm at 0.2 Hz), refuses requests beyond
/// its stroke or velocity, and aborts when the controller stops asking
/// (500 ms without a MixingCommand) or says stop. Pure; time comes in as ns.

#include <cstdint>

#include "mrd/hal/can_bus.hpp"
#include "mrd/protocol/codec.hpp"

namespace mrd::peers {

struct ActuatorConfig {
  protocol::NodeIds nodes{};
  float stroke_limit_m = 0.1f;                    ///< |A| it can drive
  float velocity_limit_m_s = 0.2f;                ///< 2π f A it can reach
  std::int64_t command_timeout_ns = 500'000'000;  ///< 500 ms (CAN_PROTOCOL.md)
};

class ActuatorLogic {
 public:
  explicit ActuatorLogic(const ActuatorConfig& c = {}) noexcept : c_(c) {}

  /// Offers one received frame; true when it was a valid MixingCommand.
  bool on_frame(const hal::CanFrame& f, std::int64_t now_ns) noexcept;
  /// Advances the cycle to `now_ns`; returns the status to publish.
  protocol::MixingStatus tick(std::int64_t now_ns) noexcept;
  /// Actuator displacement at `now_ns`, m (0 unless running).
  double position_m(std::int64_t now_ns) const noexcept;

  protocol::MixingState state() const noexcept { return state_; }
  std::uint32_t rejected() const noexcept { return rejected_; }

 private:
  ActuatorConfig c_;
  protocol::CounterCheck counter_{};
  protocol::MixingCommand cmd_{};
  protocol::MixingState state_ = protocol::MixingState::kIdle;
  std::uint8_t faults_ = 0;
  std::int64_t start_ns_ = 0, last_cmd_ns_ = 0, now_ns_ = 0;
  bool have_cmd_ = false;
  std::uint32_t rejected_ = 0;
};

}  // namespace mrd::peers
