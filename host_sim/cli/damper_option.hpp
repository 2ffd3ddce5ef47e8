#pragma once
/// `--damper FILE`: the MR damper a command simulates (a damper file,
/// host_sim/damper/damper_file.hpp; README "Your damper and fluid"). Without
/// it, the thesis damper (dampers/thesis-200kn.toml).

#include <CLI/CLI.hpp>

#include <string>

#include "host_sim/damper/damper_file.hpp"

namespace mrd::cli {

/// Registers --damper FILE on `app`.
void add_damper_option(CLI::App& app, std::string& damper_file);

/// The damper `damper_file` describes (io::UsageError with file:line:field
/// for a bad file), its warnings printed on stderr as "mrd COMMAND: warning:
/// FILE: ..."; the thesis damper for an empty name.
damper::DamperFile load_damper(const char* command, const std::string& damper_file);

}  // namespace mrd::cli
