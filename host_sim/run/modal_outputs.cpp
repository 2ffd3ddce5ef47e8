#include "host_sim/run/modal_outputs.hpp"

#include "host_sim/report/summary_json.hpp"

namespace mrd::run {

nlohmann::json modal_summary_json(const structure::ModalResult& r) {
  nlohmann::json shapes = nlohmann::json::array();
  const Eigen::Index n = r.mode_shapes.cols();
  for (Eigen::Index k = 0; k < n; ++k) {
    nlohmann::json col = nlohmann::json::array();
    for (Eigen::Index i = 0; i < n; ++i) col.push_back(r.mode_shapes(i, k));
    shapes.push_back(col);
  }
  nlohmann::json j{
      {"frequencies_hz", r.frequencies_hz},
      {"damping_ratios", r.damping_ratios},
      {"periods_s", r.periods_s},
      {"undamped_frequencies_hz", r.undamped_frequencies_hz},
      {"mode_shapes", shapes},
      {"dofs", r.dof_names},
  };
  if (!r.isolator_stiffness.empty()) j["isolator_stiffness"] = r.isolator_stiffness;
  return j;
}

void write_modal_outputs(const std::filesystem::path& dir, const structure::ModalResult& r) {
  report::write_summary_json(dir, modal_summary_json(r));
}

}  // namespace mrd::run
