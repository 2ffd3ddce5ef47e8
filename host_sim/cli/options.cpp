#include "host_sim/cli/options.hpp"

namespace mrd::cli {

void add_pga_g_option(CLI::App& app, double& pga_g, const std::string& help) {
  app.add_option("--pga-g", pga_g, help)->capture_default_str();
}

void check_pga_g(double pga_g) { require_positive("--pga-g", pga_g, "a PGA"); }

void add_idle_years_option(CLI::App& app, double& idle_years, const std::string& help) {
  app.add_option("--idle-years", idle_years, help)->capture_default_str();
}

void check_idle_years(double idle_years) { require_finite_at_least("--idle-years", idle_years, 0.0); }

void add_step_s_option(CLI::App& app, double& step_s, const std::string& help) {
  app.add_option("--step-s", step_s, help)->capture_default_str();
}

void add_threads_option(CLI::App& app, unsigned& threads, const std::string& help) {
  app.add_option("--threads", threads, help)->capture_default_str();
}

CLI::Option* add_out_option(CLI::App& app, std::string& out_dir, const std::string& help) {
  return app.add_option("--out", out_dir, help);
}

}  // namespace mrd::cli
