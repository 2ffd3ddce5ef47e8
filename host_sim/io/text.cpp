#include "host_sim/io/text.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cstdint>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "host_sim/io/usage_error.hpp"

namespace mrd::io {

std::string excerpt(std::string_view text, std::size_t max_chars) {
  std::string out;
  for (const char c : text.substr(0, max_chars)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u >= 0x7f) ? '?' : c;
  }
  if (text.size() > max_chars) out += "...";
  return out;
}

std::string format_number(const char* printf_format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, value);
  return buf;
}

bool is_space(char c) noexcept { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

std::string_view trim(std::string_view s) noexcept {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_commas(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    if (comma == std::string_view::npos) {
      fields.push_back(trim(line.substr(start)));
      return fields;
    }
    fields.push_back(trim(line.substr(start, comma - start)));
    start = comma + 1;
  }
}

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

std::string to_upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string to_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string_view strip_bom(std::string_view text) noexcept {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (text.substr(0, kBom.size()) == kBom) text.remove_prefix(kBom.size());
  return text;
}

std::string file_label(const std::filesystem::path& path) { return path.string(); }

namespace {

std::string size_text(std::size_t bytes) {
  if (bytes >= (std::size_t{1} << 20)) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

/// Refuses what is not a regular file of at most `max_bytes`.
void check_status(const std::string& file, const struct stat& st, std::size_t max_bytes) {
  if (S_ISDIR(st.st_mode)) throw UsageError(file + ": is a folder, expected a regular file");
  if (S_ISFIFO(st.st_mode)) throw UsageError(file + ": is a pipe (FIFO), expected a regular file");
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) throw UsageError(file + ": is a device, expected a regular file");
  if (!S_ISREG(st.st_mode)) throw UsageError(file + ": is not a regular file");
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) {
    throw UsageError(file + ": " + std::to_string(st.st_size) + " bytes, larger than the limit of " +
                     size_text(max_bytes));
  }
}

}  // namespace

std::string errno_text(int err) { return std::strerror(err); }

void check_regular_file(const std::filesystem::path& path, std::size_t max_bytes) {
  const std::string file = file_label(path);
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT) throw UsageError(file + ": file not found");
    throw UsageError(file + ": cannot read: " + std::strerror(err));
  }
  check_status(file, st, max_bytes);
}

std::string read_regular_file(const std::filesystem::path& path, std::size_t max_bytes) {
  const std::string file = file_label(path);
  check_regular_file(path, max_bytes);
  // O_NONBLOCK: a file swapped for a FIFO after the check still cannot block the open.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) throw UsageError(file + ": cannot open: " + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw UsageError(file + ": cannot read: " + std::strerror(errno));
  check_status(file, st, max_bytes);
  std::string data;
  data.reserve(static_cast<std::size_t>(st.st_size));
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw UsageError(file + ": read error: " + std::strerror(errno));
    }
    if (n == 0) break;
    data.append(buf, static_cast<std::size_t>(n));
    if (data.size() > max_bytes) {
      throw UsageError(file + ": larger than the limit of " + size_text(max_bytes));
    }
  }
  return data;
}

std::string line_prefix(const std::string& file, std::size_t line_no) {
  return file + ":" + std::to_string(line_no) + ": ";
}

}  // namespace mrd::io
