#pragma once
/// Outputs of `mrd modal`: the building's modes as summary.json.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "host_sim/structure/modal.hpp"

namespace mrd::run {

/// The fields documented in `mrd modal --help`.
[[nodiscard]] nlohmann::json modal_summary_json(const structure::ModalResult& r);

/// Writes `dir/summary.json` (the folder must exist).
void write_modal_outputs(const std::filesystem::path& dir, const structure::ModalResult& r);

}  // namespace mrd::run
