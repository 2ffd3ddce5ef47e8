#include "host_sim/cli/building_option.hpp"

#include "host_sim/structure/building_file.hpp"

namespace mrd::cli {

void add_building_option(CLI::App& app, std::string& building_file) {
  app.add_option("--building", building_file,
                 "Building file (TOML: masses, elements, isolators, dampers; README \"Your building\"); default: the "
                 "thesis building of Table 6.1 (buildings/thesis-6dof.toml)");
}

structure::BuildingParams load_building(const std::string& building_file) {
  if (building_file.empty()) return structure::BuildingParams{};
  return structure::read_building_file(building_file);
}

}  // namespace mrd::cli
