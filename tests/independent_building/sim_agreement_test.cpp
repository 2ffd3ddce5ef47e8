// `mrd sim` against the independent continuous-time integration of the same
// building (nonlinear_building.hpp) under El Centro N-S at 0.3 g for 20 s,
// passive-on (2.5 A) and passive-off (0 A), fully mixed damper:
//   peak_base_displacement_m, peak_isolator_force_kn, peak_damper_force_kn  within 2 %,
//   peak_superstructure_accel_m_s2, peak_story_drift_m                      within 5 %.
// The thesis building runs without --building (mrd's default building) and
// is read here from buildings/thesis_6dof.toml; the building files run with
// --building FILE. $MRD_BINARY in the environment replaces the mrd the tests
// were built with.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "building_toml.hpp"
#include "constant_current_damper.hpp"
#include "ground_record.hpp"
#include "nonlinear_building.hpp"

namespace ibuild {
namespace {

const std::filesystem::path kBuildings = MRD_INDEPENDENT_BUILDINGS_DIR;
const std::filesystem::path kRecord = std::filesystem::path(MRD_SHARED_DIR) / "ground_motions" / "elcentro_ns.csv";
constexpr double kPga_g = 0.3;
constexpr double kDuration_s = 20.0;
constexpr double kForceTolerance = 0.02;   // base displacement, isolator force, damper force
constexpr double kResponseTolerance = 0.05;  // floor acceleration, story drift

std::string mrd_binary() {
  const char* env = std::getenv("MRD_BINARY");
  return env && *env ? std::string(env) : std::string(MRD_BINARY);
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A folder of its own under the temporary directory, removed afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "mrd-agreement-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// The number after "key": in a flat JSON object, if the key is there with a number.
std::optional<double> json_number(const std::string& json, const std::string& key) {
  const std::string quoted = "\"" + key + "\"";
  const auto at = json.find(quoted);
  if (at == std::string::npos) return std::nullopt;
  const auto colon = json.find(':', at + quoted.size());
  if (colon == std::string::npos) return std::nullopt;
  const char* start = json.c_str() + colon + 1;
  char* end = nullptr;
  const double v = std::strtod(start, &end);
  if (end == start) return std::nullopt;
  return v;
}

/// Runs `mrd sim` and returns summary.json's text ("" and a test failure if it failed).
std::string run_mrd_sim(const std::string& building_args, const std::string& control, const ScratchDir& dir) {
  const std::filesystem::path out = dir.path() / "run";
  const std::string cmd = "'" + mrd_binary() + "' sim " + building_args + " --record '" + kRecord.string() +
                          "' --pga-g " + std::to_string(kPga_g) + " --duration-s " + std::to_string(kDuration_s) +
                          " --control " + control + " --out '" + out.string() + "' >'" +
                          (dir.path() / "stdout.txt").string() + "' 2>'" + (dir.path() / "stderr.txt").string() + "'";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(status, 0) << cmd << "\n" << read_text(dir.path() / "stderr.txt");
  return status == 0 ? read_text(out / "summary.json") : std::string();
}

/// |mrd − independent| ≤ tolerance · |independent| for one summary field.
void expect_agreement(const std::string& summary, const char* field, double independent, double tolerance,
                      bool required) {
  const std::optional<double> mrd = json_number(summary, field);
  if (!mrd) {
    if (required) ADD_FAILURE() << "summary.json has no number " << field;
    return;
  }
  const double allowed = tolerance * std::fabs(independent) + 1e-9;
  const double relative = independent != 0.0 ? (*mrd - independent) / independent : 0.0;
  EXPECT_NEAR(*mrd, independent, allowed) << field << ": mrd " << *mrd << ", independent " << independent << " ("
                                          << 100.0 * relative << " %)";
  std::printf("  %-32s mrd %12.6g  independent %12.6g  %+7.3f %%\n", field, *mrd, independent, 100.0 * relative);
}

struct Case {
  const char* building_file;   ///< under buildings/
  bool pass_building;          ///< false: mrd runs its default building (the thesis's)
  bool passive_on;
};

void check_agreement(const Case& c) {
  const std::filesystem::path file = kBuildings / c.building_file;
  const Building b = read_building_file(file);
  const std::string control = c.passive_on ? "passive-on" : "passive-off";
  ScratchDir dir;
  const std::string summary =
      run_mrd_sim(c.pass_building ? "--building '" + file.string() + "'" : std::string(), control, dir);
  if (summary.empty()) return;

  RunSpec spec;
  spec.duration_s = kDuration_s;
  spec.command_a = c.passive_on ? kPassiveOnCommand_a : kPassiveOffCommand_a;
  spec.options = default_options(b);
  Dp45Stats stats;
  const Peaks p = simulate_earthquake(b, scaled_to_pga(read_ground_record(kRecord), kPga_g), spec, &stats);
  std::printf("%s, %s: %zu steps (%zu rejected)\n", c.building_file, control.c_str(), stats.accepted, stats.rejected);

  expect_agreement(summary, "peak_base_displacement_m", p.base_displacement_m, kForceTolerance, true);
  expect_agreement(summary, "peak_isolator_force_kn", p.isolator_force_n / 1e3, kForceTolerance, true);
  expect_agreement(summary, "peak_damper_force_kn", p.damper_force_n / 1e3, kForceTolerance, true);
  expect_agreement(summary, "peak_superstructure_accel_m_s2", p.superstructure_accel_m_s2, kResponseTolerance, true);
  expect_agreement(summary, "peak_story_drift_m", p.story_drift_m, kResponseTolerance, true);
}

TEST(IndependentBuildingAgreement, ThesisBuildingPassiveOn) { check_agreement({"thesis_6dof.toml", false, true}); }
TEST(IndependentBuildingAgreement, ThesisBuildingPassiveOff) { check_agreement({"thesis_6dof.toml", false, false}); }

TEST(IndependentBuildingAgreement, ThesisFilePassiveOn) {
  check_agreement({"thesis_6dof.toml", true, true});
}
TEST(IndependentBuildingAgreement, LeadRubberPassiveOn) {
  check_agreement({"lead_rubber.toml", true, true});
}
TEST(IndependentBuildingAgreement, LeadRubberPassiveOff) {
  check_agreement({"lead_rubber.toml", true, false});
}
TEST(IndependentBuildingAgreement, FrictionPendulumTwoDampersPassiveOn) {
  check_agreement({"friction_pendulum.toml", true, true});
}
TEST(IndependentBuildingAgreement, FrictionPendulumTwoDampersPassiveOff) {
  check_agreement({"friction_pendulum.toml", true, false});
}
TEST(IndependentBuildingAgreement, FixedBaseRayleighFramePassiveOn) {
  check_agreement({"fixed_frame.toml", true, true});
}
TEST(IndependentBuildingAgreement, FixedBaseRayleighFramePassiveOff) {
  check_agreement({"fixed_frame.toml", true, false});
}

}  // namespace
}  // namespace ibuild
