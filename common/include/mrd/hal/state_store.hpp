#pragma once
/// Where the board keeps the idle-time estimator's state across reboots: one
/// fixed-size record of bytes (layout and CRC in firmware/core/state_store.hpp).
/// Implementations: a file on Linux (firmware/platform/linux/file_state_store),
/// RAM for tests and the simulator (firmware/platform/sim/memory_state_store);
/// a flash page on a microcontroller.

#include <array>
#include <cstddef>
#include <cstdint>

namespace mrd::hal {

inline constexpr std::size_t kStateRecordSize = 64;

/// One persisted record, as bytes.
using StateRecord = std::array<std::uint8_t, kStateRecordSize>;

/// What a StateStore reports.
enum class StoreStatus : std::uint8_t {
  kOk = 0,
  kMissing,    ///< nothing stored yet
  kWrongSize,  ///< a record is there but has the wrong length (e.g. truncated)
  kIoError,    ///< the medium failed (read, write, sync or rename)
};

constexpr const char* store_status_name(StoreStatus s) noexcept {
  switch (s) {
    case StoreStatus::kOk: return "ok";
    case StoreStatus::kMissing: return "missing";
    case StoreStatus::kWrongSize: return "wrong-size";
    case StoreStatus::kIoError: return "io-error";
  }
  return "unknown";
}

/// `save` must be atomic with respect to power loss: after a crash, `load`
/// returns the previous record or the new one, never a mix (the record's CRC
/// catches what the medium does not). Both calls may block on the medium:
/// never call them from the control step. Neither allocates nor throws.
///
/// The destructor is protected and not virtual, so that the interface needs
/// no operator delete in a freestanding build; nothing deletes a store
/// through this type.
class StateStore {
 public:
  virtual StoreStatus load(StateRecord& out) noexcept = 0;
  virtual StoreStatus save(const StateRecord& record) noexcept = 0;

 protected:
  StateStore() = default;
  StateStore(const StateStore&) = default;
  StateStore& operator=(const StateStore&) = default;
  ~StateStore() = default;
};

}  // namespace mrd::hal
