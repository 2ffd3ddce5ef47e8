#pragma once
/// Output folders and crash-safe file writing for the `mrd` subcommands.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace mrd::report {

/// Bad input or an unusable output: the CLI prints the message on one line
/// and exits with status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Creates `dir` (and parents) if needed and checks that a file can be
/// created in it. Throws UsageError naming the folder otherwise. Nothing is
/// left behind by the check.
void prepare_output_dir(const std::filesystem::path& dir);

/// Writes `content` to `path` through a temporary file in the same folder,
/// flushed and renamed into place, so a reader sees the old file or the new
/// one, never half of one. Throws UsageError on failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace mrd::report
