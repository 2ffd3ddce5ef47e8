// `--building FILE` in every program that simulates the building: `mrd sim`,
// `modal`, `sweep`, `study`, `fragility`, the DAQ/plant peer (mrd-plant-sim)
// and the in-process board (mrd-sim-board). The thesis building's file gives
// the same outputs as no file; the shipped lead-rubber and fixed-base
// buildings run and are named in the outputs; a bad building file is one
// line naming file, line and field, exit status 2, nothing written.
// (`mrd risk` reads fragility.csv only and simulates nothing: no --building.)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "host_sim/risk/fragility_plan.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

const fs::path kBuildings = fs::path(MRD_SOURCE_DIR) / "buildings";
const fs::path kThesis = kBuildings / "thesis-6dof.toml";
const fs::path kLeadRubber = kBuildings / "lead-rubber-7dof.toml";
const fs::path kFixedBase = kBuildings / "fixed-base-8dof.toml";

/// Every program given as shell text (the binary and its subcommand).
struct Program {
  std::string name;
  std::string command;
};

/// summary.json without the fields that measure the machine (wall and CPU
/// time and the rates derived from them).
nlohmann::json summary_without_timing(const fs::path& dir) {
  auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  for (const char* key : {"wall_time_s", "real_time_factor", "wall_s", "cpu_s_rank0", "runs_per_core_hour",
                          "runs_per_cpu_hour"}) {
    j.erase(key);
  }
  return j;
}

/// CSV text as rows of cells (no quoting in the files compared here).
std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream cs(line);
    for (std::string c; std::getline(cs, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return i;
  }
  ADD_FAILURE() << "no column " << name;
  return 0;
}

/// `key=value` of a peer's summary line.
double summary_value(const std::string& out, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex(" " + key + "=([-0-9.eE+]+)"))) {
    ADD_FAILURE() << "no " << key << " in " << out;
    return std::nan("");
  }
  return std::stod(m[1]);
}

class BuildingCli : public ::testing::Test {
 protected:
  /// A 4 s ground motion (CSV, 100 Hz): a 1.5 Hz sine under a 4 s ramp, PGA
  /// scaled by the commands. Short, so that each run takes milliseconds.
  fs::path short_record() {
    const fs::path p = scratch_.path() / "short.csv";
    std::ofstream f(p);
    f << "time_s,accel_m_s2\n";
    for (int k = 0; k <= 400; ++k) {
      const double t = 0.01 * k;
      f << t << ',' << (t / 4.0) * std::sin(2.0 * std::numbers::pi * 1.5 * t) << '\n';
    }
    return p;
  }

  /// A building file with a negative mass on line 3.
  fs::path bad_building() {
    const fs::path p = scratch_.path() / "negative-mass.toml";
    std::ofstream(p) << "[building]\n"
                        "name = \"negative-mass\"\n"
                        "mass_kg = [-1000.0, 1000.0]\n"
                        "stiffness_n_m = [1.0e6, 1.0e6]\n"
                        "damping_n_s_m = [0.0, 0.0]\n";
    return p;
  }

  /// Every program that takes --building, with options that make it cheap;
  /// `out` is its output folder (none for the peers).
  std::vector<Program> programs(const fs::path& out) {
    const std::string rec = short_record().string();
    const std::string mrd = std::string(MRD_BINARY);
    return {
        {"sim", mrd + " sim --record " + rec + " --control passive-on --out " + out.string()},
        {"modal", mrd + " modal --out " + out.string()},
        {"sweep", mrd + " sweep --record " + rec + " --control passive-on --idle-to 0 --threads 1 --out " +
                      out.string()},
        {"study", mrd + " study --no-sweep --out " + out.string()},
        {"fragility", mrd + " fragility --record " + rec + " --pga-g 0.2,0.6 --idle-years 0 --control passive-on "
                            "--bootstrap 0 --threads 1 --out " + out.string()},
        {"mrd-plant-sim", std::string(MRD_PLANT_SIM) + " --record " + rec + " --can mrdnone0"},
        {"mrd-sim-board", std::string(MRD_SIM_BOARD) + " --board " + MRD_BOARDS_DIR + "/sim/board.toml --record " +
                              rec + " --mode passive-on"},
    };
  }

  TempDir scratch_;
  TempDir out_;
};

TEST_F(BuildingCli, EveryProgramsHelpNamesTheBuildingOption) {
  for (const auto& p : programs(out_.path() / "unused")) {
    const std::string help = p.command.substr(0, p.command.find(" --")) + " --help";
    const auto r = run_command(help, scratch_.path());
    EXPECT_EQ(r.exit_code, 0) << p.name << ": " << r.err;
    EXPECT_NE(r.out.find("--building"), std::string::npos) << p.name << " --help:\n" << r.out;
  }
  const auto r = run_mrd("fragility --help", scratch_.path());
  EXPECT_NE(r.out.find("--drift-m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("story_drift"), std::string::npos) << r.out;
}

TEST_F(BuildingCli, ABadBuildingFileIsOneLineNamingFileLineAndFieldAndWritesNothing) {
  const fs::path bad = bad_building();
  for (const auto& p : programs(out_.path() / "out")) {
    const auto r = run_command(p.command + " --building " + bad.string(), scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << p.name << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << p.name << ": " << r.err;
    // Line 3 of the file written above holds mass_kg.
    EXPECT_NE(r.err.find(bad.string() + ":3: building.mass_kg[0]"), std::string::npos) << p.name << ": " << r.err;
    EXPECT_FALSE(fs::exists(out_.path() / "out")) << p.name;
    EXPECT_FALSE(fs::exists(out_.path() / "out.journal")) << p.name;
  }
}

TEST_F(BuildingCli, AMissingBuildingFileIsNamed) {
  const fs::path missing = scratch_.path() / "no-such-building.toml";
  for (const auto& p : programs(out_.path() / "out")) {
    const auto r = run_command(p.command + " --building " + missing.string(), scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << p.name << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << p.name << ": " << r.err;
    EXPECT_NE(r.err.find("no-such-building.toml"), std::string::npos) << p.name << ": " << r.err;
    EXPECT_FALSE(fs::exists(out_.path() / "out")) << p.name;
  }
}

/// The thesis building's file against no file: the same files, byte for byte
/// (summary.json's timing aside).
void expect_same_outputs(const fs::path& a, const fs::path& b, const std::vector<std::string>& files) {
  for (const auto& f : files) {
    ASSERT_TRUE(fs::exists(a / f)) << a / f;
    EXPECT_EQ(slurp(a / f), slurp(b / f)) << f;
  }
  EXPECT_EQ(summary_without_timing(a), summary_without_timing(b));
}

TEST_F(BuildingCli, TheThesisBuildingsFileGivesTheSameOutputsAsNoFile) {
  const std::map<std::string, std::vector<std::string>> files{
      {"sim", {"timeseries.csv"}},
      {"modal", {}},
      {"sweep", {"sweep.csv"}},
      {"study", {"report.md"}},
      {"fragility", {"runs.csv", "fragility.csv", "fragility_curves.csv"}},
  };
  const auto without = programs(out_.path() / "without");
  const auto with = programs(out_.path() / "with");
  for (std::size_t i = 0; i < without.size(); ++i) {
    SCOPED_TRACE(without[i].name);
    const auto a = run_command(without[i].command, scratch_.path());
    const auto b = run_command(with[i].command + " --building " + kThesis.string(), scratch_.path());
    if (without[i].name == "mrd-plant-sim") {
      // No CAN interface here: the building is read, then the interface refused (exit 1, not 2).
      EXPECT_EQ(b.exit_code, 1) << b.err;
      EXPECT_NE(b.err.find("mrdnone0"), std::string::npos) << b.err;
      EXPECT_EQ(a.err, b.err);
      continue;
    }
    ASSERT_EQ(a.exit_code, 0) << a.err;
    ASSERT_EQ(b.exit_code, 0) << b.err;
    if (without[i].name == "mrd-sim-board") {
      EXPECT_EQ(a.out, b.out);
      EXPECT_NE(b.out.find("building thesis-6dof (6 DOFs)"), std::string::npos) << b.out;
      continue;
    }
    expect_same_outputs(out_.path() / "without", out_.path() / "with", files.at(without[i].name));
    // sim names the building it ran; sweep, study and fragility keep the
    // thesis's summary.json for the thesis building (modal's lists the DOFs' names).
    const nlohmann::json summary = summary_without_timing(out_.path() / "with");
    if (without[i].name == "sim") {
      EXPECT_EQ(summary.at("building"), "thesis-6dof");
    } else if (without[i].name != "modal") {
      EXPECT_FALSE(summary.contains("building")) << without[i].name;
      EXPECT_FALSE(summary.contains("dofs")) << without[i].name;
    }
    fs::remove_all(out_.path() / "without");
    fs::remove_all(out_.path() / "with");
  }
}

/// The lead-rubber and fixed-base buildings shipped in buildings/: every
/// command runs them and names them in summary.json (modal's summary.json
/// gives the DOFs' names instead: their count is checked).
TEST_F(BuildingCli, EveryCommandRunsTheShippedBuildingsAndNamesThem) {
  for (const auto& [file, name, dofs] :
       {std::tuple{kLeadRubber, "lead-rubber-7dof", 7}, std::tuple{kFixedBase, "fixed-base-8dof", 8}}) {
    for (const auto& p : programs(out_.path() / "out")) {
      if (p.name == "mrd-plant-sim" || p.name == "mrd-sim-board") continue;  // below
      if (p.name == "study" && file == kLeadRubber) continue;  // StudyReportNamesTheBuildingAndItsPeaks
      SCOPED_TRACE(p.name + " " + name);
      const auto r = run_command(p.command + " --building " + file.string(), scratch_.path());
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const auto j = nlohmann::json::parse(slurp(out_.path() / "out" / "summary.json"));
      if (p.name == "modal") {
        EXPECT_EQ(j.at("dofs").size(), static_cast<std::size_t>(dofs));
      } else {
        EXPECT_EQ(j.at("building"), name);
        EXPECT_EQ(j.at("dofs"), dofs);
      }
      fs::remove_all(out_.path() / "out");
    }
  }
}

/// The in-process board and `mrd sim` step the same plant: on a building file
/// too, the board's summary equals sim's summary.json (17 digits both).
TEST_F(BuildingCli, SimBoardOnABuildingFileEqualsMrdSim) {
  const std::string rec = short_record().string();
  for (const auto& [file, name] :
       {std::pair{kLeadRubber, "lead-rubber-7dof"}, std::pair{kFixedBase, "fixed-base-8dof"}}) {
    SCOPED_TRACE(name);
    const auto board = run_command(std::string(MRD_SIM_BOARD) + " --board " + MRD_BOARDS_DIR +
                                    "/sim/board.toml --mode passive-on --record " + rec + " --building " +
                                    file.string(),
                                scratch_.path());
    ASSERT_EQ(board.exit_code, 0) << board.err;
    EXPECT_NE(board.out.find(std::string("building ") + name), std::string::npos) << board.out;
    const fs::path dir = out_.path() / name;
    const auto sim = run_mrd("sim --control passive-on --record " + rec + " --building " + file.string() + " --out " +
                                 dir.string(),
                             scratch_.path());
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
    EXPECT_EQ(summary_value(board.out, "peak_base_displacement_m"), j.at("peak_base_displacement_m").get<double>());
    EXPECT_EQ(summary_value(board.out, "peak_damper_force_n") / 1e3, j.at("peak_damper_force_kn").get<double>());
    EXPECT_EQ(summary_value(board.out, "peak_isolator_force_n") / 1e3, j.at("peak_isolator_force_kn").get<double>());
    EXPECT_EQ(summary_value(board.out, "peak_story_drift_m"), j.at("peak_story_drift_m").get<double>());
  }
}

TEST_F(BuildingCli, PlantSimulatorReadsTheBuildingBeforeTheInterface) {
  const std::string rec = short_record().string();
  for (const auto& file : {kLeadRubber, kFixedBase}) {
    const auto r = run_command(std::string(MRD_PLANT_SIM) + " --record " + rec + " --can mrdnone0 --building " +
                                file.string(),
                            scratch_.path());
    EXPECT_EQ(r.exit_code, 1) << r.err;  // the interface, not the building (2)
    EXPECT_NE(r.err.find("mrdnone0"), std::string::npos) << r.err;
  }
}

/// sweep.csv: the thesis's ten columns, then for another building the
/// isolators' summed force and the peak story drift. Checked against the
/// physics of the buildings' files, not the program:
/// - fixed base (fixed-base-8dof): no isolators, so 0; element 0 is a story
///   and its deformation is x_0, so the story drift is at least the "base"
///   (DOF 0) displacement;
/// - lead-rubber-7dof: 24 bearings, F = 24 (k_p u + Q z), |z| <= 1, so
///   |F| <= 24 (k_p u_max + Q) with k_p = 0.74e6 N/m, Q = 72e3 N; at the
///   largest displacement, several D_y = 0.011 m from the last reversal, z is
///   near 1 (z = tanh(Δu / D_y) on a loading branch from z = 0: 0.99 at
///   2.6 D_y), so |F| >= 24 (k_p u_max + 0.9 Q).
TEST_F(BuildingCli, SweepAppendsIsolatorForceAndStoryDriftForAnotherBuilding) {
  const fs::path rec = fs::path(MRD_SHARED_DIR) / "ground_motions" / "hachinohe_ns.csv";
  ASSERT_TRUE(fs::exists(rec)) << rec;
  const std::string sweep = "sweep --record " + rec.string() + " --control passive-off --idle-to 0 --threads 1";

  const fs::path fixed = out_.path() / "fixed";
  ASSERT_EQ(run_mrd(sweep + " --building " + kFixedBase.string() + " --out " + fixed.string(), scratch_.path())
                .exit_code, 0);
  auto rows = csv_rows(slurp(fixed / "sweep.csv"));
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[0].size(), 12u);
  EXPECT_EQ(rows[0][10], "peak_isolator_force_kn");
  EXPECT_EQ(rows[0][11], "peak_story_drift_m");
  EXPECT_EQ(std::stod(rows[1][10]), 0.0);
  const double base_m = std::stod(rows[1][column(rows[0], "peak_base_displacement_m")]);
  EXPECT_GT(base_m, 0.0);
  EXPECT_GE(std::stod(rows[1][11]), base_m);

  const fs::path lrb = out_.path() / "lrb";
  ASSERT_EQ(run_mrd(sweep + " --building " + kLeadRubber.string() + " --out " + lrb.string(), scratch_.path())
                .exit_code, 0);
  rows = csv_rows(slurp(lrb / "sweep.csv"));
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[0].size(), 12u);
  const double u_max = std::stod(rows[1][column(rows[0], "peak_base_displacement_m")]);
  ASSERT_GT(u_max, 2.6 * 0.011) << "the check needs a displacement of several D_y";
  const double force_kn = std::stod(rows[1][10]);
  EXPECT_LE(force_kn, 24.0 * (0.74e6 * u_max + 72.0e3) / 1e3 * (1.0 + 1e-9));
  EXPECT_GE(force_kn, 24.0 * (0.74e6 * u_max + 0.9 * 72.0e3) / 1e3);
  EXPECT_GT(std::stod(rows[1][11]), 0.0);

  // The plots name the building rather than a thesis figure; summary.json names it.
  EXPECT_EQ(nlohmann::json::parse(slurp(lrb / "summary.json")).at("building"), "lead-rubber-7dof");
}

TEST_F(BuildingCli, StudyReportNamesTheBuildingAndItsPeaks) {
  const fs::path dir = out_.path() / "study";
  const auto r = run_mrd("study --no-sweep --building " + kLeadRubber.string() + " --out " + dir.string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = slurp(dir / "report.md");
  EXPECT_NE(report.find("## Structure: lead-rubber-7dof"), std::string::npos) << report;
  EXPECT_EQ(report.find("Table 6.1, Fig. 6.2"), std::string::npos) << "not the thesis building";
  EXPECT_NE(report.find("peak isolator force [kN] | peak story drift [mm] |"), std::string::npos) << report;
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  EXPECT_EQ(j.at("building"), "lead-rubber-7dof");
  EXPECT_EQ(j.at("dofs"), 7);
  for (const auto& run : j.at("runs")) {
    for (const char* phase : {"fully_mixed", "idle"}) {
      const double u = run[phase].at("peak_base_displacement_m").get<double>();
      const double f = run[phase].at("peak_isolator_force_kn").get<double>();
      // |F| <= 24 (k_p u_max + Q) (see the sweep test); above k_p u_max alone once u > D_y.
      EXPECT_LE(f, 24.0 * (0.74e6 * u + 72.0e3) / 1e3 * (1.0 + 1e-9)) << run["record"] << " " << phase;
      EXPECT_GT(f, 24.0 * 0.74e6 * u / 1e3) << run["record"] << " " << phase;
      EXPECT_GT(run[phase].at("peak_story_drift_m").get<double>(), 0.0);
    }
  }
}

/// fragility.csv carries the story_drift limit state at --drift-m, and its
/// exceedances are the runs of runs.csv whose peak story drift reaches it.
TEST_F(BuildingCli, FragilityHasAStoryDriftLimitState) {
  const fs::path dir = out_.path() / "frag";
  const double drift_m = 0.01;
  const auto r = run_mrd("fragility --synthetic 3 --duration-s 6 --pga-g 0.1,0.4,1.0 --idle-years 0 "
                         "--control passive-on --bootstrap 0 --threads 1 --drift-m 0.01 --building " +
                             kFixedBase.string() + " --out " + dir.string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto runs = csv_rows(slurp(dir / "runs.csv"));
  ASSERT_EQ(runs.size(), 1u + 9u);
  const std::size_t drift_col = column(runs[0], "peak_story_drift_m");
  const std::size_t base_col = column(runs[0], "peak_base_displacement_m");
  int exceeded = 0;
  for (std::size_t i = 1; i < runs.size(); ++i) {
    const double drift = std::stod(runs[i][drift_col]);
    exceeded += drift >= drift_m;
    // Fixed base: element 0 is a story, its deformation the DOF-0 displacement.
    EXPECT_GE(drift, std::stod(runs[i][base_col])) << i;
  }
  const auto curves = csv_rows(slurp(dir / "fragility.csv"));
  int found = 0;
  for (std::size_t i = 1; i < curves.size(); ++i) {
    if (curves[i][column(curves[0], "limit_state")] != "story_drift") continue;
    ++found;
    EXPECT_EQ(std::stod(curves[i][column(curves[0], "threshold")]), drift_m);
    EXPECT_EQ(std::stoi(curves[i][column(curves[0], "runs")]), 9);
    EXPECT_EQ(std::stoi(curves[i][column(curves[0], "exceedances")]), exceeded);
  }
  EXPECT_EQ(found, 1);
  EXPECT_GT(exceeded, 0) << "the threshold should be reached by some run for the check to bite";
  EXPECT_LT(exceeded, 9);
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  bool listed = false;
  for (const auto& s : j.at("limit_states")) listed = listed || s.at("name") == "story_drift";
  EXPECT_TRUE(listed);
}

/// A building whose bearings state a displacement capacity has the
/// bearing_capacity limit state at the smallest (here the lead-rubber file's
/// bearings at 0.12 m instead of 0.45 m, so that some runs reach it): its
/// exceedances are the runs of runs.csv whose peak base displacement reaches
/// it, it comes before story_drift, and the curves of the other limit states,
/// bootstrap bands included, are those of the same building without a
/// capacity. The thesis building (no bearings) has none.
TEST_F(BuildingCli, FragilityHasABearingCapacityLimitStateWhereTheBearingsStateOne) {
  std::string text = slurp(kLeadRubber);
  const std::string from = "displacement_capacity_m = 0.45";
  ASSERT_NE(text.find(from), std::string::npos);
  const std::string with_capacity = std::string(text).replace(text.find(from), from.size(), "displacement_capacity_m = 0.12");
  const std::string without_capacity = std::string(text).replace(text.find(from), from.size(), "");
  const fs::path a = scratch_.path() / "lr-0.12.toml", b = scratch_.path() / "lr-none.toml";
  std::ofstream(a) << with_capacity;
  std::ofstream(b) << without_capacity;
  const std::string common = "fragility --synthetic 4 --duration-s 8 --pga-g 0.2,0.5,1.0 --idle-years 0 "
                             "--control passive-on --bootstrap 20 --threads 1 --drift-m 0.05 --building ";
  const fs::path da = out_.path() / "cap", db = out_.path() / "nocap";
  for (const auto& [building, dir] : {std::pair{a, da}, std::pair{b, db}}) {
    const auto r = run_mrd(common + building.string() + " --out " + dir.string(), scratch_.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto runs = csv_rows(slurp(da / "runs.csv"));
  ASSERT_EQ(runs.size(), 1u + 12u);
  const std::size_t base_col = column(runs[0], "peak_base_displacement_m");
  int exceeded = 0;
  for (std::size_t i = 1; i < runs.size(); ++i) exceeded += std::stod(runs[i][base_col]) >= 0.12;
  EXPECT_GT(exceeded, 0) << "some run should reach the capacity for the check to bite";
  EXPECT_LT(exceeded, 12);
  const auto curves = csv_rows(slurp(da / "fragility.csv")), plain = csv_rows(slurp(db / "fragility.csv"));
  const std::size_t state_col = column(curves[0], "limit_state");
  std::vector<std::string> order;
  for (std::size_t i = 1; i < curves.size(); ++i) {
    order.push_back(curves[i][state_col]);
    if (curves[i][state_col] != "bearing_capacity") continue;
    EXPECT_EQ(std::stod(curves[i][column(curves[0], "threshold")]), 0.12);
    EXPECT_EQ(std::stoi(curves[i][column(curves[0], "exceedances")]), exceeded);
  }
  ASSERT_EQ(order.size(), 5u);
  EXPECT_EQ(order[3], "bearing_capacity");
  EXPECT_EQ(order[4], "story_drift");
  // The other states' rows: the same bytes with and without the capacity.
  ASSERT_EQ(plain.size(), curves.size() - 1);
  for (std::size_t i = 1, j = 1; i < curves.size(); ++i) {
    if (curves[i][state_col] == "bearing_capacity") continue;
    EXPECT_EQ(curves[i], plain[j]) << curves[i][state_col];
    ++j;
  }
  // The thesis building: no bearings, no such state.
  const fs::path dt = out_.path() / "thesis";
  const auto t = run_mrd("fragility --synthetic 2 --duration-s 4 --pga-g 0.2,0.5 --idle-years 0 --control passive-on "
                         "--bootstrap 0 --threads 1 --out " + dt.string(),
                         scratch_.path());
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_EQ(slurp(dt / "fragility.csv").find("bearing_capacity"), std::string::npos);
}

/// sim, sweep and study warn when a run's peak base displacement passes the
/// bearings' displacement capacity (the lead-rubber file's bearings at 1 mm,
/// which every run with motion passes), on stderr and in summary.json.
TEST_F(BuildingCli, SimSweepAndStudyWarnPastTheBearingsCapacity) {
  std::string text = slurp(kLeadRubber);
  const std::string from = "displacement_capacity_m = 0.45";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "displacement_capacity_m = 0.001");
  const fs::path building = scratch_.path() / "lr-1mm.toml";
  std::ofstream(building) << text;
  const std::string rec = short_record().string();
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"sim", "sim --record " + rec + " --control passive-on"},
      {"sweep", "sweep --record " + rec + " --control passive-on --idle-to 0 --threads 1"},
      {"study", "study --no-sweep"}};
  for (const auto& [name, command] : commands) {
    const fs::path dir = out_.path() / name;
    const auto r = run_mrd(command + " --building " + building.string() + " --out " + dir.string(), scratch_.path());
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    EXPECT_NE(r.err.find("exceeds the bearings' displacement capacity 0.001 m (building file)"), std::string::npos)
        << name << ": " << r.err;
    const nlohmann::json summary = nlohmann::json::parse(slurp(dir / "summary.json"));
    bool in_summary = false;
    for (const auto& w : summary.at("warnings"))
      in_summary = in_summary || w.get<std::string>().find("displacement capacity 0.001 m") != std::string::npos;
    EXPECT_TRUE(in_summary) << name;
    // The study's many runs are counted (the sweep here has one run).
    if (name == "study") {
      EXPECT_NE(r.err.find(" runs: peak isolator displacement up to "), std::string::npos) << r.err;
    }
  }
}

TEST_F(BuildingCli, FragilityRefusesABadDriftThreshold) {
  for (const char* bad : {"0", "-0.01", "nan", "inf"}) {
    const fs::path dir = out_.path() / "frag";
    const auto r = run_mrd(std::string("fragility --synthetic 2 --drift-m ") + bad + " --out " + dir.string(),
                           scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("--drift-m: expected"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir));
  }
}

/// A resume journal kept for one building is not taken for another: the
/// fingerprint covers the building's values (not its name).
TEST(BuildingFingerprint, ChangesWithTheBuildingNotItsName) {
  risk::FragilityPlan a;
  a.records.push_back({"r", "r.csv", {0.0, 1.0, 0.0}});
  a.pga_g = {0.1};
  a.idle_years = {0.0};
  a.modes = {control::ControlMode::kPassiveOn};
  risk::FragilityPlan renamed = a;
  renamed.base.building.name = "another-name";
  EXPECT_EQ(a.fingerprint(), renamed.fingerprint());
  risk::FragilityPlan heavier = a;
  heavier.base.building.mass_kg[3] *= 1.01;
  EXPECT_NE(a.fingerprint(), heavier.fingerprint());
  risk::FragilityPlan isolated = a;
  isolated.base.building.isolators.push_back(structure::LeadRubberBearing{4, 1.0e4, 1.0e5, 0.01, 2.0, 0.0});
  EXPECT_NE(a.fingerprint(), isolated.fingerprint());
  risk::FragilityPlan two_dampers = a;
  two_dampers.base.building.dampers[0].count = 2;
  EXPECT_NE(a.fingerprint(), two_dampers.fingerprint());
}

}  // namespace
}  // namespace mrd::test
