#include "host_sim/cli/damper_option.hpp"

#include <cstdio>

#include "host_sim/io/text.hpp"

namespace mrd::cli {

void add_damper_option(CLI::App& app, std::string& damper_file) {
  app.add_option("--damper", damper_file,
                 "Damper file (TOML: the damper.toml `mrd calibrate` writes, with [rating] and [geometry]; README "
                 "\"Your damper and fluid\"); default: the thesis's 200 kN damper (dampers/thesis-200kn.toml)");
}

damper::DamperFile load_damper(const char* command, const std::string& damper_file) {
  if (damper_file.empty()) return damper::thesis_damper();
  damper::DamperFile d = damper::read_damper_file(damper_file);
  damper::require_law_for(d, command);
  const std::string label = io::file_label(damper_file);
  for (const std::string& w : d.warnings)
    std::fprintf(stderr, "mrd %s: warning: %s: %s\n", command, label.c_str(), w.c_str());
  return d;
}

}  // namespace mrd::cli
