#include "host_sim/excitation/record_folder.hpp"

#include <algorithm>
#include <system_error>

#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::excitation {
namespace {

namespace fs = std::filesystem;

/// What a non-regular entry is, for the message.
std::string kind_of(const fs::directory_entry& entry) {
  std::error_code ec;
  const fs::file_status s = entry.status(ec);
  switch (s.type()) {
    case fs::file_type::directory:
      return "a folder";
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::block:
    case fs::file_type::character:
      return "a device";
    case fs::file_type::socket:
      return "a socket";
    case fs::file_type::not_found:
      return "a broken link";
    default:
      return "not a regular file";
  }
}

}  // namespace

bool has_record_extension(const fs::path& name) {
  const std::string ext = io::to_lower(name.extension().string());
  return std::any_of(std::begin(kRecordExtensions), std::end(kRecordExtensions),
                     [&](const char* e) { return ext == e; });
}

std::vector<fs::path> record_files_in_folder(const std::string& option, const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw io::UsageError(option + ": '" + dir.string() + "' is not a folder");
  std::vector<fs::path> files;
  fs::directory_iterator it(dir, ec);
  for (const fs::directory_iterator end; !ec && it != end; it.increment(ec)) {
    const fs::path& path = it->path();
    const std::string name = path.filename().string();
    if (name.empty() || name.front() == '.' || !has_record_extension(path)) continue;
    std::error_code status_ec;
    if (!it->is_regular_file(status_ec)) {
      throw io::UsageError(option + ": '" + path.string() + "' is " + kind_of(*it) +
                           ", not a record file (names starting with '.' are skipped)");
    }
    files.push_back(path);
  }
  if (ec) throw io::UsageError(option + ": cannot list '" + dir.string() + "': " + ec.message());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw io::UsageError(option + ": no .csv or .at2 record in '" + dir.string() + "'");
  return files;
}

}  // namespace mrd::excitation
