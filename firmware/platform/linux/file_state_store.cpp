#include "firmware/platform/linux/file_state_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <utility>

#include "firmware/platform/linux/regular_file.hpp"

namespace mrd::posix {
namespace {

std::string parent_dir(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

/// Writes all of `size` bytes, retrying after EINTR and short writes.
bool write_all(int fd, const std::uint8_t* data, std::size_t size) noexcept {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

FileStateStore::FileStateStore(std::string path)
    : path_(std::move(path)), temp_path_(path_ + ".new"), dir_(parent_dir(path_)) {}

hal::StoreStatus FileStateStore::load(hal::StateRecord& out) noexcept {
  // At most one record: a longer file is refused unread, as is a folder, a FIFO or a device.
  std::uint8_t buf[hal::kStateRecordSize];
  std::size_t got = 0;
  last_load_ = read_regular_file(path_.c_str(), buf, sizeof buf, got);
  last_errno_ = last_load_.err;
  switch (last_load_.problem) {
    case FileProblem::kNone: break;
    case FileProblem::kMissing: return hal::StoreStatus::kMissing;
    case FileProblem::kTooLarge: return hal::StoreStatus::kWrongSize;
    default: return hal::StoreStatus::kIoError;
  }
  if (got != hal::kStateRecordSize) return hal::StoreStatus::kWrongSize;
  for (std::size_t i = 0; i < hal::kStateRecordSize; ++i) out[i] = buf[i];
  return hal::StoreStatus::kOk;
}

hal::StoreStatus FileStateStore::save(const hal::StateRecord& record) noexcept {
  // The rename below would replace whatever `<path>` names: never a folder, a FIFO or a device.
  if (const FileCheck target = check_regular_file(path_.c_str(), SIZE_MAX); is_non_regular(target.problem)) {
    last_errno_ = 0;
    return hal::StoreStatus::kIoError;
  }
  const int fd = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    last_errno_ = errno;
    return hal::StoreStatus::kIoError;
  }
  const bool written = write_all(fd, record.data(), record.size()) && ::fsync(fd) == 0;
  const int write_errno = errno;
  if (::close(fd) != 0 || !written) {
    last_errno_ = written ? errno : write_errno;
    ::unlink(temp_path_.c_str());
    return hal::StoreStatus::kIoError;
  }
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    last_errno_ = errno;
    ::unlink(temp_path_.c_str());
    return hal::StoreStatus::kIoError;
  }
  // Make the rename durable: sync the folder that holds the entry.
  const int dfd = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd < 0) {
    last_errno_ = errno;
    return hal::StoreStatus::kIoError;
  }
  const bool synced = ::fsync(dfd) == 0;
  last_errno_ = synced ? 0 : errno;
  ::close(dfd);
  return synced ? hal::StoreStatus::kOk : hal::StoreStatus::kIoError;
}

}  // namespace mrd::posix
