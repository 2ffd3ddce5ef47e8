#include "host_sim/report/path_ownership.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <string_view>
#include <system_error>
#include <utility>

#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::report {
namespace fs = std::filesystem;
using io::UsageError;

namespace {

std::vector<InputPath>& inputs_store() {
  static std::vector<InputPath> inputs;
  return inputs;
}

/// Whether the components of `prefix` start those of `path`.
bool starts_with(const fs::path& path, const fs::path& prefix) {
  auto p = path.begin();
  for (auto q = prefix.begin(); q != prefix.end(); ++q, ++p) {
    if (p == path.end() || *p != *q) return false;
  }
  return true;
}

const char* overlap_words(Overlap o) {
  switch (o) {
    case Overlap::kSame:
      return "is";
    case Overlap::kContains:
      return "contains";
    case Overlap::kInside:
      return "lies inside";
    case Overlap::kNone:
      break;
  }
  return "";
}

constexpr std::string_view kMarkerText =
    "This folder was made by mrd; mrd replaces or removes it only while this file is in it.\n";

}  // namespace

fs::path resolve_path(const std::string& option, const fs::path& given) {
  std::error_code ec;
  fs::path p = fs::absolute(given, ec);
  if (ec) throw UsageError(option + " '" + io::excerpt(given.string(), 200) + "': " + ec.message());
  fs::path canonical = fs::weakly_canonical(p, ec);
  p = (ec ? p : canonical).lexically_normal();
  while (p.has_relative_path() && p.filename().empty()) p = p.parent_path();
  return p;
}

Overlap overlap(const fs::path& a, const fs::path& b) {
  const bool a_in_b = starts_with(a, b);
  const bool b_in_a = starts_with(b, a);
  if (a_in_b && b_in_a) return Overlap::kSame;
  if (b_in_a) return Overlap::kContains;
  if (a_in_b) return Overlap::kInside;
  return Overlap::kNone;
}

void declare_inputs(std::vector<InputPath> inputs) { inputs_store() = std::move(inputs); }

const std::vector<InputPath>& declared_inputs() { return inputs_store(); }

void check_clear_of_inputs(const std::string& option, const std::string& shown, const fs::path& resolved) {
  for (const InputPath& in : inputs_store()) {
    const Overlap o = overlap(resolved, in.resolved);
    if (o == Overlap::kNone) continue;
    throw UsageError(option + " '" + io::excerpt(shown, 200) + "' " + overlap_words(o) + " the input '" +
                     io::excerpt(in.shown.string(), 200) + "' (" + in.option +
                     "): an output never replaces what a command reads; name another folder");
  }
}

void check_clear_of_output(const std::string& option_a, const std::string& shown_a, const fs::path& a,
                           const std::string& option_b, const std::string& shown_b, const fs::path& b) {
  const Overlap o = overlap(a, b);
  if (o == Overlap::kNone) return;
  throw UsageError(option_a + " '" + io::excerpt(shown_a, 200) + "' " + overlap_words(o) + " " + option_b + " '" +
                   io::excerpt(shown_b, 200) + "': the two must be separate folders");
}

bool holds_marker(const fs::path& dir, const char* marker) {
  std::error_code ec;
  return fs::is_regular_file(fs::symlink_status(dir / marker, ec));
}

void check_owned_or_new(const std::string& option, const std::string& shown, const fs::path& dir,
                        const char* marker) {
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (!fs::exists(st)) return;
  const std::string named = option + " '" + io::excerpt(shown, 200) + "'";
  if (!fs::is_directory(st)) throw UsageError(named + " exists and is not a folder");
  const bool empty = fs::is_empty(dir, ec);
  if (ec) throw UsageError(named + " cannot be read: " + ec.message());
  if (!empty && !holds_marker(dir, marker)) {
    throw UsageError(named + " is a folder with other files and no " + marker +
                     " (not made by mrd): refusing to replace or remove it; name a new or empty folder");
  }
}

void write_marker(const std::string& option, const fs::path& dir, const char* marker) {
  const fs::path file = dir / marker;
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0) {
    throw UsageError(option + " '" + dir.string() + "': cannot write " + marker + ": " + io::errno_text(errno));
  }
  const ssize_t n = ::write(fd, kMarkerText.data(), kMarkerText.size());
  const int err = errno;
  ::close(fd);
  if (n != static_cast<ssize_t>(kMarkerText.size())) {
    throw UsageError(option + " '" + dir.string() + "': cannot write " + marker + ": " +
                     (n < 0 ? io::errno_text(err) : std::string("short write")));
  }
}

void claim_folder(const std::string& option, const fs::path& dir, const char* marker) {
  check_owned_or_new(option, dir.string(), dir, marker);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw UsageError(option + " '" + dir.string() + "' cannot be created: " + ec.message());
  if (!holds_marker(dir, marker)) write_marker(option, dir, marker);
}

}  // namespace mrd::report
