#pragma once
/// hal::StateStore on a Linux file system, crash-safe by write-new-then-rename:
/// the record goes to `<path>.new`, which is fsync'ed, renamed over `<path>`,
/// and the folder is fsync'ed so the rename itself survives a power loss.
/// A crash at any point leaves either the old record or the new one at
/// `<path>` (a stale `<path>.new` is overwritten by the next save). load()
/// reads `<path>` only, under the reader policy (regular_file.hpp: a folder,
/// a FIFO or a device is refused unread, kIoError, and never blocks), and
/// reports its size; the record's own CRC (see firmware/core/state_store.hpp)
/// catches a medium that returns damaged bytes. save() never replaces a
/// folder, a FIFO or a device at `<path>` (kIoError, last_errno() 0).
///
/// Paths are fixed at construction (the only allocation); load() and save()
/// use plain POSIX calls, allocate nothing and throw nothing. They block on
/// the disk: call them from a low-priority context, never the control step.

#include <string>

#include "firmware/platform/linux/regular_file.hpp"
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
  /// What the reader policy said at the last load(): problem_text() says
  /// why it failed ("is a pipe (FIFO), expected a regular file", …). Only
  /// load() sets it, so the thread that loads may read it while another saves.
  const FileCheck& last_load() const noexcept { return last_load_; }

 private:
  std::string path_;
  std::string temp_path_;
  std::string dir_;
  int last_errno_ = 0;
  FileCheck last_load_{};
};

}  // namespace mrd::posix
