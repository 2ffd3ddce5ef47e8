#include "host_sim/cli/options.hpp"

#include <charconv>

#include "host_sim/cli/command.hpp"

namespace mrd::cli {

void refuse_empty_values(CLI::App& app) {
  const CLI::Validator non_empty(
      [](std::string& value) -> std::string {
        for (const char c : value) {
          if (c != ' ' && c != '\t' && c != '\n' && c != '\r') return {};
        }
        return "expected a value, got an empty one";
      },
      "", "non-empty");
  for (CLI::Option* opt : app.get_options()) {
    if (opt->get_type_size() != 0 && opt->get_expected_min() > 0) opt->check(non_empty);
  }
}

void add_pga_g_option(CLI::App& app, double& pga_g, const std::string& help) {
  app.add_option("--pga-g", pga_g, help)->capture_default_str();
}

void check_pga_g(double pga_g) {
  require_positive("--pga-g", pga_g, "a PGA");
  require_at_most("--pga-g", pga_g, kMaxPga_g, "100 g (no earthquake comes near it)");
}

void add_idle_years_option(CLI::App& app, double& idle_years, const std::string& help) {
  app.add_option("--idle-years", idle_years, help)->capture_default_str();
}

void check_idle_years(double idle_years) {
  require_finite_at_least("--idle-years", idle_years, 0.0);
  require_at_most("--idle-years", idle_years, kMaxIdleYears, "1000 years");
}

void add_step_s_option(CLI::App& app, double& step_s, const std::string& help) {
  app.add_option("--step-s", step_s, help)->capture_default_str();
}

void add_threads_option(CLI::App& app, unsigned& threads, const std::string& help) {
  app.add_option("--threads", threads, help)->capture_default_str()->check(CLI::Range(0u, kMaxThreads));
}

std::optional<std::uint64_t> parse_seed(std::string_view text) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string_view::npos) return std::nullopt;
  std::uint64_t seed = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), seed, 10);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;  // above kMaxSeed
  return seed;
}

CLI::Option* add_seed_option(CLI::App& app, std::uint64_t& seed, const std::string& help, const std::string& name) {
  const CLI::Validator decimal_seed(
      [](std::string& text) -> std::string {
        if (parse_seed(text)) return {};
        return "expected a decimal whole number from 0 to " + std::to_string(kMaxSeed) + ", got '" + text + "'";
      },
      "", "seed");
  const auto assign = [&seed](const std::string& text) { seed = parse_seed(text).value(); };
  return app.add_option_function<std::string>(name, assign, help)
      ->type_name("UINT64")
      ->default_str(std::to_string(seed))
      ->check(decimal_seed);
}

CLI::Option* add_out_option(CLI::App& app, std::string& out_dir, const std::string& help) {
  return app.add_option("--out", out_dir, help);
}

}  // namespace mrd::cli
