#include "host_sim/report/output_dir.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <system_error>

#include "host_sim/io/text.hpp"

namespace mrd::report {
namespace fs = std::filesystem;
using io::UsageError;

namespace {

void write_all(int fd, std::string_view content, const fs::path& tmp) {
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      throw UsageError("cannot write '" + tmp.string() + "': " + io::errno_text(err));
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}
}  // namespace

void prepare_output_dir(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw UsageError("--out '" + dir.string() + "' exists and is not a folder");
  }
  fs::create_directories(dir, ec);
  if (ec) {
    throw UsageError("--out '" + dir.string() + "' cannot be created: " + ec.message());
  }
  const fs::path probe = dir / ".mrd-write-probe";
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw UsageError("--out '" + dir.string() + "' is not writable: " + io::errno_text(errno));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

void write_file_atomically(const fs::path& path, std::string_view content) {
  const fs::path tmp = path.string() + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw UsageError("cannot create '" + tmp.string() + "': " + io::errno_text(errno));
  }
  write_all(fd, content, tmp);
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw UsageError("cannot flush '" + tmp.string() + "': " + io::errno_text(err));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw UsageError("cannot rename '" + tmp.string() + "' to '" + path.string() + "': " + io::errno_text(err));
  }
}

}  // namespace mrd::report
