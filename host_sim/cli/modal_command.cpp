#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "host_sim/cli/command.hpp"
#include "host_sim/report/output_dir.hpp"
#include "host_sim/structure/building.hpp"
#include "host_sim/structure/modal.hpp"

namespace mrd::cli {
namespace {

constexpr const char* kModalHelp = R"(Fields (printed and written to DIR/summary.json); modes in ascending frequency:
  frequencies_hz            natural frequencies |λ|/2π of the 6 damped modes, Hz, from the
                            eigenvalues λ of the 12x12 state matrix (thesis §6.1: f1 = 0.25 Hz)
  damping_ratios            modal damping ratios -Re(λ)/|λ|, fraction (0.0497 = 4.97 %;
                            thesis §6.1: 4.97 %, 3.17 %, 5.07 % in modes 1-3)
  periods_s                 1 / frequencies_hz, s
  undamped_frequencies_hz   frequencies of K φ = ω² M φ (damping ignored), Hz, a cross-check
  mode_shapes               undamped mode shapes, one array of 6 per mode in the same order as
                            undamped_frequencies_hz; entry i is DOF i (0 = base, 1-5 = floors),
                            scaled so the largest-magnitude entry is +1
  dofs                      names of the 6 degrees of freedom in mode_shapes order
Building without the MR damper: Table 6.1 and Fig. 6.2 of the thesis (masses 244,800 kg base and
212,292 kg per floor; isolation layer 3,287.3 kN/m and 209.8 kN·s/m).)";

struct ModalOptions {
  std::string out_dir;
};

void print_table(const structure::ModalResult& r) {
  std::printf("Modes of the base-isolated building without the MR damper (thesis §6.1, Fig. 6.2)\n\n");
  std::printf("  %4s  %10s  %10s  %8s  %14s\n", "mode", "f (Hz)", "T (s)", "zeta (%)", "undamped f (Hz)");
  for (int k = 0; k < structure::kDofs; ++k) {
    std::printf("  %4d  %10.4f  %10.4f  %8.3f  %14.4f\n", k + 1, r.frequencies_hz[k], r.periods_s[k],
                100.0 * r.damping_ratios[k], r.undamped_frequencies_hz[k]);
  }
}

nlohmann::json to_json(const structure::ModalResult& r) {
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

}  // namespace

Command add_modal_command(CLI::App& parent) {
  auto opts = std::make_shared<ModalOptions>();
  CLI::App* app = parent.add_subcommand(
      "modal", "Natural frequencies, damping ratios and mode shapes of the building (Table 6.1, Fig. 6.2)");
  app->add_option("--out", opts->out_dir, "Folder for summary.json (created if missing)");
  app->footer(kModalHelp);
  return {app, [opts] {
            if (!opts->out_dir.empty()) report::prepare_output_dir(opts->out_dir);
            const structure::ModalResult r = structure::modal_analysis(structure::BuildingParams{});
            print_table(r);
            if (!opts->out_dir.empty()) {
              const auto path = std::filesystem::path(opts->out_dir) / "summary.json";
              report::write_file_atomically(path, to_json(r).dump(2) + "\n");
              std::printf("\nwrote %s\n", path.c_str());
            }
          }};
}

}  // namespace mrd::cli
