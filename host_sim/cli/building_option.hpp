#pragma once
/// `--building FILE`: the building every closed-loop command simulates (a
/// building file, host_sim/structure/building_file.hpp; README "Your
/// building"). Without it, the thesis building of Table 6.1.

#include <CLI/CLI.hpp>

#include <string>

#include "host_sim/structure/building_params.hpp"

namespace mrd::cli {

/// Registers --building FILE on `app`.
void add_building_option(CLI::App& app, std::string& building_file);

/// The building `building_file` describes (io::UsageError with
/// file:line:field for a bad file); the thesis building for an empty name.
structure::BuildingParams load_building(const std::string& building_file);

}  // namespace mrd::cli
