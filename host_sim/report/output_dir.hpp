#pragma once
/// Output folders and crash-safe file writing for the `mrd` subcommands.

#include <filesystem>
#include <string_view>

#include "host_sim/io/usage_error.hpp"

namespace mrd::report {

/// Creates `dir` (and parents) if needed and checks that a file can be
/// created in it. Throws io::UsageError naming the folder otherwise. Nothing is
/// left behind by the check.
void prepare_output_dir(const std::filesystem::path& dir);

/// Writes `content` to `path` through a temporary file in the same folder,
/// flushed and renamed into place, so a reader sees the old file or the new
/// one, never half of one. Throws io::UsageError on failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace mrd::report
