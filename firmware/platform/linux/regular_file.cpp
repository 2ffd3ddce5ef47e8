#include "firmware/platform/linux/regular_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace mrd::posix {
namespace {

FileCheck failed(FileProblem problem, int err = 0) noexcept {
  FileCheck c;
  c.problem = problem;
  c.err = err;
  return c;
}

/// Refuses what is not a regular file of at most `max_bytes`.
FileCheck check_status(const struct stat& st, std::size_t max_bytes) noexcept {
  if (S_ISDIR(st.st_mode)) return failed(FileProblem::kFolder);
  if (S_ISFIFO(st.st_mode)) return failed(FileProblem::kPipe);
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return failed(FileProblem::kDevice);
  if (!S_ISREG(st.st_mode)) return failed(FileProblem::kNotRegular);
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) {
    FileCheck c = failed(FileProblem::kTooLarge);
    c.size_bytes = static_cast<std::uintmax_t>(st.st_size);
    return c;
  }
  return {};
}

FileCheck grew_past_limit() noexcept {
  FileCheck c = failed(FileProblem::kTooLarge);
  c.grew = true;
  return c;
}

/// A descriptor closed when it goes out of scope.
class Fd {
 public:
  explicit Fd(int fd) noexcept : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const noexcept { return fd_; }

 private:
  int fd_;
};

/// stat(), open() without blocking, fstat() on the descriptor: `fd` holds a
/// regular file of `size_bytes` ≤ `max_bytes` when the result is ok.
FileCheck open_checked(const char* path, std::size_t max_bytes, int& fd, std::size_t& size_bytes) noexcept {
  fd = -1;
  size_bytes = 0;
  if (const FileCheck c = check_regular_file(path, max_bytes); !c.ok()) return c;
  const int opened = ::open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (opened < 0) return errno == ENOENT ? failed(FileProblem::kMissing) : failed(FileProblem::kOpenFailed, errno);
  struct stat st {};
  if (::fstat(opened, &st) != 0) {
    const int err = errno;
    ::close(opened);
    return failed(FileProblem::kStatFailed, err);
  }
  // The path may name something else now than when stat() looked at it.
  if (const FileCheck c = check_status(st, max_bytes); !c.ok()) {
    ::close(opened);
    return c;
  }
  fd = opened;
  size_bytes = static_cast<std::size_t>(st.st_size);
  return {};
}

/// read() once, retrying after EINTR; the count, or −1 with errno set.
ssize_t read_some(int fd, void* into, std::size_t bytes) noexcept {
  for (;;) {
    const ssize_t n = ::read(fd, into, bytes);
    if (n >= 0 || errno != EINTR) return n;
  }
}

std::string size_text(std::size_t bytes) {
  if (bytes >= (std::size_t{1} << 20)) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

}  // namespace

FileCheck check_regular_file(const char* path, std::size_t max_bytes) noexcept {
  struct stat st {};
  if (::stat(path, &st) != 0) {
    return errno == ENOENT ? failed(FileProblem::kMissing) : failed(FileProblem::kStatFailed, errno);
  }
  return check_status(st, max_bytes);
}

FileCheck read_regular_file(const char* path, std::uint8_t* buffer, std::size_t capacity,
                            std::size_t& size) noexcept {
  size = 0;
  int raw = -1;
  std::size_t size_bytes = 0;
  if (const FileCheck c = open_checked(path, capacity, raw, size_bytes); !c.ok()) return c;
  const Fd fd(raw);
  for (;;) {
    if (size == capacity) {
      // Full: one more byte tells "exactly the limit" from "grew past it".
      std::uint8_t extra = 0;
      const ssize_t n = read_some(fd.get(), &extra, 1);
      if (n < 0) return failed(FileProblem::kReadFailed, errno);
      return n == 0 ? FileCheck{} : grew_past_limit();
    }
    const ssize_t n = read_some(fd.get(), buffer + size, capacity - size);
    if (n < 0) return failed(FileProblem::kReadFailed, errno);
    if (n == 0) return {};
    size += static_cast<std::size_t>(n);
  }
}

FileCheck read_regular_file(const char* path, std::size_t max_bytes, std::string& text) {
  text.clear();
  int raw = -1;
  std::size_t size_bytes = 0;
  if (const FileCheck c = open_checked(path, max_bytes, raw, size_bytes); !c.ok()) return c;
  const Fd fd(raw);
  text.reserve(size_bytes);
  char chunk[1 << 16];
  for (;;) {
    const ssize_t n = read_some(fd.get(), chunk, sizeof chunk);
    if (n < 0) return failed(FileProblem::kReadFailed, errno);
    if (n == 0) return {};
    text.append(chunk, static_cast<std::size_t>(n));
    if (text.size() > max_bytes) {
      text.clear();
      return grew_past_limit();
    }
  }
}

std::string problem_text(const FileCheck& check, std::size_t max_bytes) {
  switch (check.problem) {
    case FileProblem::kNone: return {};
    case FileProblem::kMissing: return "file not found";
    case FileProblem::kFolder: return "is a folder, expected a regular file";
    case FileProblem::kPipe: return "is a pipe (FIFO), expected a regular file";
    case FileProblem::kDevice: return "is a device, expected a regular file";
    case FileProblem::kNotRegular: return "is not a regular file";
    case FileProblem::kTooLarge:
      if (check.grew) return "larger than the limit of " + size_text(max_bytes);
      return std::to_string(check.size_bytes) + " bytes, larger than the limit of " + size_text(max_bytes);
    case FileProblem::kStatFailed: return std::string("cannot read: ") + std::strerror(check.err);
    case FileProblem::kOpenFailed: return std::string("cannot open: ") + std::strerror(check.err);
    case FileProblem::kReadFailed: return std::string("read error: ") + std::strerror(check.err);
  }
  return "cannot read";
}

std::string non_regular_problem(const std::string& path) {
  const FileCheck c = check_regular_file(path.c_str(), SIZE_MAX);
  return is_non_regular(c.problem) ? problem_text(c, SIZE_MAX) : std::string();
}

}  // namespace mrd::posix
