#include "host_sim/report/summary_json.hpp"

#include "host_sim/report/output_dir.hpp"

namespace mrd::report {

std::filesystem::path write_summary_json(const std::filesystem::path& dir, const nlohmann::json& summary) {
  const std::filesystem::path path = dir / "summary.json";
  write_file_atomically(path, summary.dump(2) + "\n");
  return path;
}

}  // namespace mrd::report
