#include "firmware/app/runtime_log.hpp"

#include <cstdio>

namespace mrd::app {

void format_summary(char (&out)[kLogLineSize], const char* name, const ControlTaskStatus& s, const LoopTiming& timing,
                    std::uint64_t enable_changes) noexcept {
  using protocol::DecodeError;
  std::snprintf(
      out, kLogLineSize,
      "%s: summary ticks=%llu overruns=%u worst_late_us=%.1f frames_rx=%llu accepted=%llu rejected=%u "
      "(checksum %u, length %u, range %u, field %u, repeated %u, stale %u) unexpected_ids=%u tx_errors=%u "
      "sensor_timeout_ticks=%u drive_fault_ticks=%u bus_error_ticks=%u gpio_errors=%u enable_changes=%llu "
      "last_command_a=%.3f drive_enable=%d bus=%s",
      name, static_cast<unsigned long long>(s.ticks), timing.overruns,
      static_cast<double>(timing.worst_late_ns) / 1e3, static_cast<unsigned long long>(s.frames_received),
      static_cast<unsigned long long>(s.frames_accepted), s.rejected_total(), s.rejected(DecodeError::kBadChecksum),
      s.rejected(DecodeError::kWrongLength), s.rejected(DecodeError::kOutOfRange), s.rejected(DecodeError::kBadField),
      s.repeated_counters, s.stale_counters, s.unexpected_ids, s.tx_errors, s.sensor_timeout_ticks,
      s.drive_fault_ticks, s.bus_error_ticks, s.gpio_errors, static_cast<unsigned long long>(enable_changes),
      static_cast<double>(s.last_output.current_command_a), s.last_output.drive_enable ? 1 : 0,
      hal::bus_state_name(s.bus_state));
}

}  // namespace mrd::app
