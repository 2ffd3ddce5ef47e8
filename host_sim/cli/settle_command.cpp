#include <cstdio>
#include <string>

#include "host_sim/cli/command.hpp"
#include "host_sim/cli/damper_option.hpp"
#include "host_sim/cli/fluid_option.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/run/settle_outputs.hpp"
#include "host_sim/run/settle_study.hpp"
#include "mrd/units.hpp"

namespace mrd::cli {
namespace settle_command {
namespace {

constexpr CommandHelp kSettleHelp{
    "settle", "Settling state of the MR fluid after an idle time (Eq. 5.1-5.8)",
    R"(Fields (printed and written to DIR/summary.json):
  idle_years                       idle time you gave, years (1 year = 365.25 days)
  settling_velocity_m_s            Stokes settling velocity V_t of one particle, m/s (Eq. 5.1)
  hindered_settling_velocity_m_s   hindered settling velocity V_ts = V_t (1 - chi)^n, m/s (Eq. 5.2)
  settled_layer_height_m           height of the fully settled particle layer, m (Eq. 5.3 with the
                                   shaft removed; Table 5.5: 0.0831 m)
  max_settling_time_years          time for all particles to settle, years (Eq. 5.4; thesis 0.8531)
  sq                               settling quotient: settled fraction, 0..1, saturating at 1 (Eq. 5.5)
  a_pr                             participant ratio before mixing, fraction (Eq. 5.6, Table 5.6)
  b_pr                             participant ratio after unlimited mixing, fraction (Eq. 5.7)
  c_pr                             recovery rate per unit of displaced volume, 1/L (Eq. 5.8, 5.9)
Fluid and damper: Tables 3.1, 5.3 and 5.4 of the thesis, or --fluid FILE (Table 5.3's quantities,
or a measured max_settling_time_s that replaces Eq. 5.4, and Table 5.6's coefficients) and
--damper FILE (its [geometry], the cylinder of Eq. 5.3, and its participant ratio); README "Your
damper and fluid". The defaults, fluids/thesis-model-fluid.toml and dampers/thesis-200kn.toml,
give the same bytes as no file.)"};

struct SettleOptions {
  double idle_years = 0.0;
  std::string damper;
  std::string fluid;
  std::string out_dir;
};

void print_table(double idle_years, const run::SettleSummary& s, const DamperAndFluid& d, const SettleOptions& o) {
  std::printf("Idle-time settling after %.4g years idle (thesis §5.3)\n\n", idle_years);
  // Files whose values are the thesis's print the thesis's table.
  const bool own = !is_thesis_settling(d) || !is_thesis_damper(d);
  if (own) std::printf("  fluid: %s%s%s%s\n  damper: %s%s%s%s\n\n", d.fluid.name.c_str(), o.fluid.empty() ? "" : " (",
                       o.fluid.c_str(), o.fluid.empty() ? "" : ")", d.damper.name.c_str(), o.damper.empty() ? "" : " (",
                       o.damper.c_str(), o.damper.empty() ? "" : ")");
  const bool measured = d.settling.measured_max_settling_time_s > 0.0;
  std::printf("  %-34s %14s  %-6s %s\n", "quantity", "value", "unit", "source");
  const auto row = [](const char* name, double v, const char* unit, const char* src) {
    std::printf("  %-34s %14.6g  %-6s %s\n", name, v, unit, src);
  };
  row("Stokes settling velocity V_t", s.settling_velocity_m_s, "m/s", "Eq. 5.1");
  row("hindered settling velocity V_ts", s.hindered_settling_velocity_m_s, "m/s", "Eq. 5.2");
  row("settled-layer height h_max", s.settled_layer_height_m, "m", "Eq. 5.3, Table 5.5");
  row("maximum settling time", units::s_to_years(s.max_settling_time_s), "years",
      measured ? "measured (fluid file)" : "Eq. 5.4");
  row("settling quotient SQ", s.sq, "-", "Eq. 5.5");
  row("initial participant ratio a_PR", s.pr.a_pr, "-", "Eq. 5.6");
  row("final participant ratio b_PR", s.pr.b_pr, "-", "Eq. 5.7");
  row("participant-ratio rate c_PR", s.pr.c_pr, "1/L", "Eq. 5.8");
}

void add_options(CLI::App& app, SettleOptions& o) {
  app.add_option("--idle-years", o.idle_years, "Idle time in years (>= 0)")->required();
  add_damper_option(app, o.damper);
  add_fluid_option(app, o.fluid);
  add_out_option(app, o.out_dir, "Folder for summary.json (created if missing)");
}

void execute(const SettleOptions& o) {
  check_idle_years(o.idle_years);
  const DamperAndFluid d = load_damper_and_fluid("settle", o.damper, o.fluid);
  compute_print_write(
      "settle", o.out_dir, [&] { return run::settle_study(units::years_to_s(o.idle_years), d.settling, d.params.pr); },
      [&](const run::SettleSummary& s) { print_table(o.idle_years, s, d, o); },
      [&](const std::filesystem::path& dir, const run::SettleSummary& s) {
        run::write_settle_outputs(dir, o.idle_years, s);
      },
      "\nwrote %s\n");
}

}  // namespace
}  // namespace settle_command

Command add_settle_command(CLI::App& parent) {
  using namespace settle_command;
  return make_command(parent, kSettleHelp, add_options, execute);
}

}  // namespace mrd::cli
