#include <cstdio>
#include <string>

#include "host_sim/cli/command.hpp"
#include "host_sim/report/output_transaction.hpp"

namespace mrd::cli {

std::filesystem::path open_out_dir(const std::string& out_dir) { return report::begin_output(out_dir); }

void commit_out_dir() { report::commit_outputs(); }

std::filesystem::path shown_path(const std::filesystem::path& path) { return report::shown_path(path); }

std::optional<std::filesystem::path> open_optional_out_dir(const std::string& out_dir) {
  if (out_dir.empty()) return std::nullopt;
  return open_out_dir(out_dir);
}

void print_warnings(const char* command, const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) std::fprintf(stderr, "mrd %s: warning: %s\n", command, w.c_str());
}

void warn_plots_not_written(const char* command, const std::vector<std::string>& problems) {
  for (const auto& p : problems) {
    std::fprintf(stderr, "mrd %s: warning: plot not written: %s\n", command, report::shown_text(p).c_str());
  }
}

}  // namespace mrd::cli
