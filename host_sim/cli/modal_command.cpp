#include <cstdio>
#include <string>

#include "host_sim/cli/building_option.hpp"
#include "host_sim/cli/command.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/run/modal_outputs.hpp"
#include "host_sim/structure/building.hpp"
#include "host_sim/structure/modal.hpp"

namespace mrd::cli {
namespace modal_command {
namespace {

constexpr CommandHelp kModalHelp{
    "modal", "Natural frequencies, damping ratios and mode shapes of the building (Table 6.1, Fig. 6.2)",
    R"(Fields (printed and written to DIR/summary.json); modes in ascending frequency:
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
  isolator_stiffness        with isolators only: which of their stiffnesses K holds
Building without the MR damper: Table 6.1 and Fig. 6.2 of the thesis (masses 244,800 kg base and
212,292 kg per floor; isolation layer 3,287.3 kN/m and 209.8 kN·s/m), or --building FILE (N DOFs,
2N states; nonlinear isolators at their post-yield or pendulum stiffness, which the output names).)"};

struct ModalOptions {
  std::string building;
  std::string out_dir;
};

void print_table(const structure::ModalResult& r) {
  std::printf("Modes of the building without the MR damper (%zu DOFs; the thesis building: §6.1, Fig. 6.2)\n\n",
              r.frequencies_hz.size());
  std::printf("  %4s  %10s  %10s  %8s  %14s\n", "mode", "f (Hz)", "T (s)", "zeta (%)", "undamped f (Hz)");
  for (std::size_t k = 0; k < r.frequencies_hz.size(); ++k) {
    std::printf("  %4zu  %10.4f  %10.4f  %8.3f  %14.4f\n", k + 1, r.frequencies_hz[k], r.periods_s[k],
                100.0 * r.damping_ratios[k], r.undamped_frequencies_hz[k]);
  }
  if (!r.isolator_stiffness.empty()) std::printf("\n  %s\n", r.isolator_stiffness.c_str());
}

void add_options(CLI::App& app, ModalOptions& o) {
  add_out_option(app, o.out_dir, "Folder for summary.json (created if missing)");
  add_building_option(app, o.building);
}

void execute(const ModalOptions& o) {
  compute_print_write(
      "modal", o.out_dir, [&] { return structure::modal_analysis(load_building(o.building)); }, print_table,
      run::write_modal_outputs, "\nwrote %s\n");
}

}  // namespace
}  // namespace modal_command

Command add_modal_command(CLI::App& parent) {
  using namespace modal_command;
  return make_command(parent, kModalHelp, add_options, execute);
}

}  // namespace mrd::cli
