#include "host_sim/run/modal_outputs.hpp"

#include "host_sim/report/summary_json.hpp"

namespace mrd::run {

nlohmann::json modal_summary_json(const structure::ModalResult& r) {
  nlohmann::json shapes = nlohmann::json::array();
  for (int k = 0; k < structure::kDofs; ++k) {
    nlohmann::json col = nlohmann::json::array();
    for (int i = 0; i < structure::kDofs; ++i) col.push_back(r.mode_shapes(i, k));
    shapes.push_back(col);
  }
  return nlohmann::json{
      {"frequencies_hz", r.frequencies_hz},
      {"damping_ratios", r.damping_ratios},
      {"periods_s", r.periods_s},
      {"undamped_frequencies_hz", r.undamped_frequencies_hz},
      {"mode_shapes", shapes},
      {"dofs", nlohmann::json::array({"base", "floor_1", "floor_2", "floor_3", "floor_4", "floor_5"})},
  };
}

void write_modal_outputs(const std::filesystem::path& dir, const structure::ModalResult& r) {
  report::write_summary_json(dir, modal_summary_json(r));
}

}  // namespace mrd::run
