#pragma once
/// What the emulated-board tests share: running a script of
/// scripts/emulated-board/ (a failure, never a skip, when it cannot run),
/// reading the serial console it kept, parsing key=value lines, and the
/// closed-loop comparison with the in-process simulation.

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "host_sim/run/wire_controller.hpp"
#include "host_sim/run/closed_loop.hpp"
#include "host_sim/run/motions.hpp"
#include "mrd/units.hpp"

namespace mrd::testing {

namespace fs = std::filesystem;

/// The Hachinohe record of the shared folder.
inline fs::path hachinohe_record() { return fs::path(MRD_SHARED_DIR) / "ground_motions" / "hachinohe_ns.csv"; }

/// The output folder of one scenario under the build tree (serial logs kept).
inline fs::path emulated_out_dir(const std::string& scenario) {
  return fs::path(MRD_BINARY_DIR) / "emulated-board" / scenario;
}

/// Runs `ENV scripts/emulated-board/SCRIPT ARGS...`, its output to `log`
/// when given; true when it exited 0. The script prints why it failed
/// (missing QEMU, compiler, kernel, package).
inline bool run_emulated_script(const std::string& env, const std::string& script,
                                const std::vector<std::string>& args, const fs::path& log = {}) {
  std::string cmd = env + " '" + MRD_SOURCE_DIR + "/scripts/emulated-board/" + script + "'";
  for (const auto& a : args) cmd += " '" + a + "'";
  if (!log.empty()) cmd += " > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  return status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

/// The whole text of a file ("" when missing).
inline std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Numeric key=value pairs of a line.
inline std::map<std::string, double> key_values(const std::string& line) {
  std::map<std::string, double> kv;
  const std::regex re(R"(([a-z0-9_]+)=(-?[0-9.eE+-]+))");
  for (std::sregex_iterator it(line.begin(), line.end(), re), end; it != end; ++it) kv[(*it)[1]] = std::stod((*it)[2]);
  return kv;
}

/// Word key=value pairs of a line (state=ok, rtc=valid …).
inline std::map<std::string, std::string> key_words(const std::string& line) {
  std::map<std::string, std::string> kv;
  const std::regex re(R"(([a-z0-9_]+)=([^ ,]+))");
  for (std::sregex_iterator it(line.begin(), line.end(), re), end; it != end; ++it) kv[(*it)[1]] = (*it)[2];
  return kv;
}

/// The lines of `text` that start with `prefix`.
inline std::vector<std::string> find_lines(const std::string& text, const std::string& prefix) {
  std::vector<std::string> found;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) found.push_back(line);
  }
  return found;
}

/// The first line of `text` that starts with `prefix` and contains `part`
/// ("" when none).
inline std::string find_line_with(const std::string& text, const std::string& prefix, const std::string& part) {
  for (const auto& line : find_lines(text, prefix)) {
    if (line.find(part) != std::string::npos) return line;
  }
  return "";
}

/// The first line of `text` that starts with `prefix` ("" when none).
inline std::string find_line(const std::string& text, const std::string& prefix) {
  const auto lines = find_lines(text, prefix);
  return lines.empty() ? "" : lines.front();
}

/// One lockstep run in the guest and how close it must come to the
/// in-process run.
struct GuestRun {
  control::ControlMode mode;
  double idle_years;
  double rel_tol;
};

/// The closed-loop runs both emulated boards (vcan and Kvaser) make: the
/// first 10 s of the record, passive-on after a quarter year idle and
/// semi-active after half a year, both all but bit-exact (the cross build
/// contracts no multiply-add, cmake/toolchain-aarch64.cmake).
inline constexpr double kGuestDurationS = 10.0;
inline constexpr GuestRun kGuestRuns[] = {{control::ControlMode::kPassiveOn, 0.25, 1e-9},
                                          {control::ControlMode::kSemiActive, 0.5, 1e-9}};

/// "mode:idle_years …" for MRD_EMU_RUNS.
template <std::size_t N>
std::string runs_argument(const GuestRun (&runs)[N]) {
  std::string s;
  for (const auto& r : runs) s += std::string(s.empty() ? "" : " ") + control::mode_name(r.mode) + ":" + std::to_string(r.idle_years);
  return s;
}

/// Checks the plant and firmware summaries of run `index` (1-based, lines
/// tagged [run-N-plant] and [run-N-firmware]) against run::run_closed_loop
/// with the frames' quantization (run::WireQuantizedController) over the first
/// `duration_s` of `record`: same ticks, peaks within r.rel_tol, no rejected
/// frame and no transmit error.
inline void expect_guest_run_equals_in_process(const std::string& serial, int index, const GuestRun& r,
                                               const fs::path& record, double duration_s, const char* where) {
  const std::string tag = "[run-" + std::to_string(index) + "-";
  SCOPED_TRACE(control::mode_name(r.mode));
  const std::string plant_line = find_line(serial, tag + "plant] mrd-plant-sim: summary");
  ASSERT_FALSE(plant_line.empty()) << "no plant summary in the serial log";
  const auto guest = key_values(plant_line);
  const auto motion = run::load_study_motion(record, run::kThesisPga_g, 1e-3, duration_s);
  plant::PlantSpec spec;
  spec.idle_time_s = units::years_to_s(r.idle_years);
  run::WireQuantizedController controller(run::make_controller(r.mode, 1e-3));
  const plant::PlantSummary ref = run::run_closed_loop(spec, motion.accel_m_s2, controller);
  EXPECT_EQ(guest.at("ticks"), static_cast<double>(motion.accel_m_s2.size()));
  const std::pair<const char*, double> peaks[] = {
      {"peak_base_displacement_m", ref.peak_base_displacement_m},
      {"peak_damper_force_n", ref.peak_damper_force_n},
      {"peak_superstructure_accel_m_s2", ref.peak_superstructure_accel_m_s2},
      {"peak_base_accel_m_s2", ref.peak_base_accel_m_s2},
      {"peak_current_a", ref.peak_current_a},
      {"final_participant_ratio", ref.final_participant_ratio},
  };
  for (const auto& [key, want] : peaks) {
    const double got = guest.at(key);
    std::printf("%s vs in-process, %s: %-32s %.17g vs %.17g (relative %+.2e)\n", where, control::mode_name(r.mode),
                key, got, want, got / want - 1.0);
    EXPECT_NEAR(got, want, r.rel_tol * std::fabs(want)) << key;
  }
  EXPECT_GT(ref.peak_current_a, 2.0) << "the coil was driven";
  const auto fw = key_values(find_line(serial, tag + "firmware] mrd-firmware: summary"));
  ASSERT_FALSE(fw.empty()) << "no firmware summary in the serial log";
  EXPECT_EQ(fw.at("ticks"), static_cast<double>(motion.accel_m_s2.size()));
  EXPECT_EQ(fw.at("rejected"), 0.0);
  EXPECT_EQ(fw.at("tx_errors"), 0.0);
}

}  // namespace mrd::testing
