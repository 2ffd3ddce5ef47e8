#pragma once
/// hal::StateStore on a Linux file system, crash-safe by write-new-then-rename:
/// the record goes to `<path>.new`, which is fsync'ed, renamed over `<path>`,
/// and the folder is fsync'ed so the rename itself survives a power loss.
/// A crash at any point leaves either the old record or the new one at
/// `<path>` (a stale `<path>.new` is overwritten by the next save). load()
/// reads `<path>` only and reports its size; the record's own CRC (see
/// firmware/core/state_store.hpp) catches a medium that returns damaged bytes.
///
/// Paths are fixed at construction (the only allocation); load() and save()
/// use plain POSIX calls, allocate nothing and throw nothing. They block on
/// the disk: call them from a low-priority context, never the control step.

#include <string>

#include "mrd/hal/state_store.hpp"

namespace mrd::posix {

class FileStateStore final : public hal::StateStore {
 public:
  explicit FileStateStore(std::string path);

  hal::StoreStatus load(hal::StateRecord& out) noexcept override;
  hal::StoreStatus save(const hal::StateRecord& record) noexcept override;

  const std::string& path() const noexcept { return path_; }
  const std::string& temp_path() const noexcept { return temp_path_; }
  /// errno of the last failed call (0 after a success).
  int last_errno() const noexcept { return last_errno_; }

 private:
  std::string path_;
  std::string temp_path_;
  std::string dir_;
  int last_errno_ = 0;
};

}  // namespace mrd::posix
