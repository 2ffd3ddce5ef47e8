#pragma once
/// `--damper FILE`: the MR damper a command simulates (a damper file,
/// host_sim/damper/damper_file.hpp; README "Your damper and fluid"). Without
/// it, the thesis damper (dampers/thesis-200kn.toml).

#include <CLI/CLI.hpp>

#include <string>

#include "host_sim/damper/damper_file.hpp"
#include "host_sim/plant/coil.hpp"

namespace mrd::cli {

/// Registers --damper FILE on `app`.
void add_damper_option(CLI::App& app, std::string& damper_file);

/// The damper `damper_file` describes (io::UsageError with file:line:field
/// for a bad file), its warnings printed on stderr as "mrd COMMAND: warning:
/// FILE: ..."; the thesis damper for an empty name.
damper::DamperFile load_damper(const char* command, const std::string& damper_file);

/// The inductance L(i) of `d`'s coil as the hardware plant drives it: the
/// file's inductance_1a_h and inductance_2a_h when it has them (else Table
/// 3.1's), the saturated floor (an assumption, plant/coil.hpp) kept below
/// the coil's own L(2 A).
plant::CoilInductance coil_inductance(const damper::DamperFile& d);

}  // namespace mrd::cli
