#pragma once
/// DIR/summary.json, the machine-readable result every `mrd` subcommand writes.

#include <filesystem>
#include <nlohmann/json.hpp>

namespace mrd::report {

/// Writes `summary` to `dir/summary.json` (two-space indent, final newline)
/// with write_file_atomically and returns that path. Throws io::UsageError
/// when the file cannot be written.
std::filesystem::path write_summary_json(const std::filesystem::path& dir, const nlohmann::json& summary);

}  // namespace mrd::report
