// `--damper FILE` (sine, sim, sweep, study, fragility, schedule, settle) and
// `--fluid FILE` (the same but sine), run as a user runs them: the shipped
// thesis files give the same bytes as no file; a damper calibrated from the
// laboratory records of ../shared/lab_data reads as a damper of the lab's size
// and runs in closed loop on a small building; a fluid of 20 years changes the
// settling quotient and the participant ratio as Eq. 5.4–5.8 say by hand, and
// the schedule's times with it; a bad file is one line naming file, line and
// field, exit status 2, nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "host_sim/damper/damper_file.hpp"
#include "mrd/physics/bingham.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

const fs::path kSource = MRD_SOURCE_DIR;
const fs::path kThesisDamper = kSource / "dampers" / "thesis-200kn.toml";
const fs::path kThesisFluid = kSource / "fluids" / "thesis-model-fluid.toml";
const fs::path kTwentyYears = kSource / "fluids" / "illustrative-20-year.toml";
const fs::path kLab = fs::path(MRD_SHARED_DIR) / "lab_data" / "quiroz_utfsm";

/// Text of `dir`'s files without the lines that measure the machine (wall
/// and CPU time, rates, the cost estimate) or name the folder.
std::string outputs_without_timing(const fs::path& dir) {
  std::string all;
  for (const auto& [name, text] : snapshot(dir)) {
    all += "== " + name + "\n";
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      bool timing = false;
      for (const char* key : {"wall", "cpu_s", "runs_per_", "real_time_factor"})
        timing = timing || line.find(key) != std::string::npos;
      if (!timing) all += line + "\n";
    }
  }
  return all;
}

std::string stdout_without_timing(const std::string& out) {
  std::string kept;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.find("computing") == std::string::npos && line.find("wrote ") == std::string::npos &&
        line.find(" s wall") == std::string::npos && line.find("estimate") == std::string::npos &&
        line.find("runs computed") == std::string::npos)
      kept += line + "\n";
  }
  return kept;
}

class DamperFluidCli : public ::testing::Test {
 protected:
  /// A 4 s ground motion (CSV, 100 Hz): a 1.5 Hz sine under a 4 s ramp.
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

  /// `text` written to scratch/`name`.
  fs::path file(const std::string& name, const std::string& text) {
    const fs::path p = scratch_.path() / name;
    std::ofstream(p) << text;
    return p;
  }

  TempDir scratch_;
  TempDir out_;
};

/// Each command with options that make it cheap, `DIR` standing for its
/// output folder and what takes --fluid.
struct Command {
  std::string name;
  std::string args;
  bool fluid = true;
};

std::vector<Command> commands(const std::string& rec) {
  return {
      {"sine", "sine --duration-s 4 --idle-years 0.3", false},
      {"sim", "sim --record " + rec + " --control semi-active --idle-years 0.3"},
      {"sim hardware", "sim --record " + rec + " --control semi-active --plant hardware --idle-years 0.1"},
      {"sweep", "sweep --record " + rec + " --idle-step 0.5 --threads 1"},
      {"study", "study --no-sweep --idle-years 0.5"},
      {"fragility", "fragility --record " + rec + " --pga-g 0.2,0.6 --idle-years 0,0.5 --bootstrap 0 --threads 1"},
      {"schedule", "schedule --years 2"},
      {"settle", "settle --idle-years 0.3"},
  };
}

TEST_F(DamperFluidCli, TheThesisFilesGiveTheSameBytesAsNoFile) {
  const std::string rec = short_record().string();
  for (const Command& c : commands(rec)) {
    const fs::path plain = out_.path() / (c.name + " plain"), files = out_.path() / (c.name + " files");
    const auto a = run_mrd(c.args + " --out '" + plain.string() + "'", scratch_.path());
    const std::string given =
        " --damper " + kThesisDamper.string() + (c.fluid ? " --fluid " + kThesisFluid.string() : "");
    const auto b = run_mrd(c.args + given + " --out '" + files.string() + "'", scratch_.path());
    ASSERT_EQ(a.exit_code, 0) << c.name << ": " << a.err;
    ASSERT_EQ(b.exit_code, 0) << c.name << ": " << b.err;
    EXPECT_EQ(stdout_without_timing(a.out), stdout_without_timing(b.out)) << c.name;
    EXPECT_EQ(outputs_without_timing(plain), outputs_without_timing(files)) << c.name;
    EXPECT_EQ(entries(plain), entries(files)) << c.name;
  }
}

TEST_F(DamperFluidCli, EveryCommandsHelpNamesTheOptions) {
  for (const Command& c : commands("r.csv")) {
    const auto r = run_mrd(c.args.substr(0, c.args.find(' ')) + " --help", scratch_.path());
    ASSERT_EQ(r.exit_code, 0) << c.name << ": " << r.err;
    EXPECT_NE(r.out.find("--damper"), std::string::npos) << c.name;
    EXPECT_NE(r.out.find("Your damper and fluid"), std::string::npos) << c.name;
    EXPECT_EQ(r.out.find("--fluid") != std::string::npos, c.fluid) << c.name;
  }
}

// `mrd calibrate` on three laboratory records (2 mm at 5 Hz, 0, 0.5 and 1 A:
// a small commercial damper, 1.5–1.9 kN at 1 A by ../shared/lab_data/README.md)
// writes a damper.toml that --damper reads: a yield force at 1 A of order
// 1 kN, a rating derived from what the records cover, and a closed loop that
// runs semi-active on a small building (a 500 kg, 2 Hz frame).
TEST_F(DamperFluidCli, ALabCalibratedDamperRunsInClosedLoop) {
  ASSERT_TRUE(fs::exists(kLab)) << kLab << " not found: the shared data folder belongs beside the clone";
  const fs::path cal = out_.path() / "cal";
  std::string records;
  for (const char* current : {"0p00A", "0p50A", "1p00A"}) {
    const fs::path p = kLab / ("2mm_5Hz_" + std::string(current) + ".csv");
    records += ' ';
    records += p.string();
  }
  const auto r = run_mrd("calibrate --measured" + records +
                             " --law bingham --no-lost-motion --no-transition-time --no-plots --out " + cal.string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const damper::DamperFile d = damper::read_damper_file(cal / "damper.toml");
  const double fc_1a = physics::coulomb_force_n(d.params.bingham, 1.0);
  EXPECT_GT(fc_1a, 300.0);
  EXPECT_LT(fc_1a, 3000.0);
  EXPECT_LT(physics::coulomb_force_n(d.params.bingham, 0.0), 500.0);
  EXPECT_FALSE(d.rating_given);
  EXPECT_EQ(d.params.rating.current_a, 1.0);  // the records' largest current
  EXPECT_GT(d.params.rating.force_n, 1000.0);
  EXPECT_LT(d.params.rating.force_n, 3000.0);
  EXPECT_NEAR(d.params.rating.stroke_m, 0.0016, 0.0004);  // "2 mm" records: 1.6 mm half range measured
  EXPECT_FALSE(d.geometry_given);

  // 500 kg on 78 957 N/m: 2π·2 Hz squared times 500 kg; 2 % damping:
  // 2 · 0.02 · √(78 957 · 500) = 251 N s/m.
  const fs::path bldg = file("lab-1dof.toml",
                             "[building]\nname = \"lab-1dof\"\nbase = \"fixed\"\nmass_kg = [500.0]\n"
                             "stiffness_n_m = [78957.0]\ndamping_n_s_m = [251.0]\n");
  const fs::path sim = out_.path() / "sim";
  const auto s = run_mrd("sim --building " + bldg.string() + " --damper " + (cal / "damper.toml").string() +
                             " --record " + short_record().string() + " --pga-g 0.05 --control semi-active --out " +
                             sim.string(),
                         scratch_.path());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_NE(s.err.find("damper.toml: no [rating]"), std::string::npos) << s.err;
  EXPECT_NE(s.err.find("damper.toml: no [geometry]"), std::string::npos) << s.err;
  EXPECT_NE(s.out.find("time above rated 1 A"), std::string::npos) << s.out;
  const auto j = nlohmann::json::parse(slurp(sim / "summary.json"));
  // The lab damper's force, far below the thesis damper's 4.1 kN at 0 A.
  EXPECT_GT(j.at("peak_damper_force_kn").get<double>(), 0.0);
  EXPECT_LT(j.at("peak_damper_force_kn").get<double>(), 3.0);
  EXPECT_EQ(j.at("building"), "lab-1dof");
}

// A calibration's shape of the law reaches every command's closed loop: the
// thesis damper with a current exponent of 2 on its yield force and a lost
// motion (f_c at 1 A stays 170 − 165.9 e^(−0.7) = 87.6 kN, at 0.5 A it falls
// from 170 − 165.9 e^(−0.35) = 53.1 kN to 170 − 165.9 e^(−0.175) = 30.7 kN),
// so a semi-active run differs from the plain damper's; `mrd fragility`
// steps it in the scalar loop and says why.
TEST_F(DamperFluidCli, ACalibratedShapeActsInTheClosedLoopAndFragilityStepsItInTheLanes) {
  std::string text = slurp(kThesisDamper);
  const std::string rate = "rate_per_a = 0.7      # f_c,c, 1/A\n";
  ASSERT_NE(text.find(rate), std::string::npos);
  text.replace(text.find(rate), rate.size(), rate + "current_exponent = 2.0\n");
  text += "\n[lost_motion]\nm_per_n = 2e-09\nshare = 0.5\n";
  const fs::path shaped = file("shaped.toml", text);
  const std::string rec = short_record().string();
  const std::string run = " --record " + rec + " --pga-g 0.3 --control semi-active";
  double peaks[2] = {0.0, 0.0};
  int i = 0;
  for (const fs::path& damper : {kThesisDamper, shaped}) {
    const fs::path dir = out_.path() / ("sim" + std::to_string(i));
    const auto r = run_mrd("sim --damper " + damper.string() + run + " --out " + dir.string(), scratch_.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("lost_motion"), std::string::npos) << r.err;  // simulated, not warned about
    peaks[i++] = nlohmann::json::parse(slurp(dir / "summary.json")).at("peak_damper_force_kn").get<double>();
  }
  EXPECT_NE(peaks[0], peaks[1]);
  // The fragility run of the same motion in the SIMD lanes: mrd sim's peak (runs.csv's 9 digits).
  const fs::path frag = out_.path() / "frag";
  const auto f = run_mrd("fragility --damper " + shaped.string() + run +
                             " --idle-years 0 --bootstrap 0 --threads 1 --out " + frag.string(),
                         scratch_.path());
  ASSERT_EQ(f.exit_code, 0) << f.err;
  EXPECT_EQ(f.out.find("scalar loop"), std::string::npos) << f.out;
  std::istringstream csv(slurp(frag / "runs.csv"));
  std::string header, row;
  ASSERT_TRUE(std::getline(csv, header) && std::getline(csv, row));
  const auto split = [](const std::string& line) {
    std::vector<std::string> out;
    std::istringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
    return out;
  };
  const std::vector<std::string> names = split(header), cells = split(row);
  const auto at = std::find(names.begin(), names.end(), "peak_damper_force_kn");
  ASSERT_NE(at, names.end()) << header;
  EXPECT_NEAR(std::stod(cells.at(static_cast<std::size_t>(at - names.begin()))), peaks[1], 1e-8 * peaks[1]);
}

// `mrd sim --damper` heats the file's coil. Passive-on holds 2.5 A at rest
// for 60 s; the rise is i² R R_th (1 − e^(−t/τ)) after the coil's lag of
// Eq. 4.5 (τ_slow 0.7 s). Against the thesis coil (2 K/W, 1200 s), the same
// coil with 6 K/W and 600 s rises by 3 · (1 − e^−0.1)/(1 − e^−0.05) =
// 3 · 0.0951626/0.0487706 = 5.8537 times as much; the lag withholds the same
// first second's heat from both, weighted by e^(−60/τ) as the rest is, to
// within (60 s/τ)·(0.7 s/60 s) ≈ 0.1 % of the ratio: 0.5 % holds it.
TEST_F(DamperFluidCli, SimHeatsTheDamperFilesCoil) {
  std::string text = slurp(kThesisDamper);
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"thermal_resistance_k_w = 2.0", "thermal_resistance_k_w = 6.0"},
                                 {"thermal_time_constant_s = 1200.0", "thermal_time_constant_s = 600.0"}}) {
    ASSERT_NE(text.find(from), std::string::npos) << from;
    text.replace(text.find(from), from.size(), to);
  }
  const fs::path hot = file("hot-coil.toml", text);
  double rise_k[2] = {0.0, 0.0};
  int i = 0;
  for (const fs::path& damper : {kThesisDamper, hot}) {
    const fs::path dir = out_.path() / ("heat" + std::to_string(i));
    const auto r = run_mrd("sim --damper " + damper.string() + " --record none --duration-s 60 --control passive-on --out " +
                               dir.string(),
                           scratch_.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("heating is assumed"), std::string::npos) << r.err;
    rise_k[i++] = nlohmann::json::parse(slurp(dir / "summary.json")).at("peak_coil_temperature_rise_k").get<double>();
  }
  // The thesis coil: 2.5² · 4.8 · 2 · (1 − e^−0.05) = 60 · 0.0487706 = 2.926 K, a little less for the lag.
  EXPECT_NEAR(rise_k[0], 2.926, 0.03);
  EXPECT_NEAR(rise_k[1] / rise_k[0], 5.8537, 0.005 * 5.8537);
}

// The 20-year fluid in `mrd settle` after 1 year, by hand (Eq. 5.5–5.8):
// SQ = 1/20 = 0.05; a_PR = 0.1 + 0.9·e^−0.35 = 0.7342192807; b_PR = 0.605 +
// 0.395·e^−0.225 = 0.9204139064; c_PR = 5.474·e^−0.1825 = 4.5608527409.
TEST_F(DamperFluidCli, ATwentyYearFluidSettlesAsEq55To58Say) {
  const fs::path dir = out_.path() / "settle";
  const auto r = run_mrd("settle --idle-years 1 --fluid " + kTwentyYears.string() + " --out " + dir.string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("measured (fluid file)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("fluid: illustrative-20-year"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  EXPECT_NEAR(j.at("max_settling_time_years").get<double>(), 20.0, 1e-12);
  EXPECT_NEAR(j.at("sq").get<double>(), 0.05, 1e-15);
  EXPECT_NEAR(j.at("a_pr").get<double>(), 0.7342192807, 1e-10);
  EXPECT_NEAR(j.at("b_pr").get<double>(), 0.9204139064, 1e-10);
  EXPECT_NEAR(j.at("c_pr").get<double>(), 4.5608527409, 1e-10);
}

// `mrd schedule`: T_max is the fluid's 20 years (7305 days), and the idle time
// that takes a fully mixed fluid to the capacity threshold scales with T_max
// (a_PR depends on idle time only through SQ = idle/T_max, Eq. 5.5–5.6), so
// it is the thesis fluid's times 20 years / the thesis fluid's T_max.
TEST_F(DamperFluidCli, ATwentyYearFluidStretchesTheSchedulesTimes) {
  const fs::path thesis = out_.path() / "thesis", slow = out_.path() / "slow";
  ASSERT_EQ(run_mrd("schedule --years 2 --out " + thesis.string(), scratch_.path()).exit_code, 0);
  const auto r = run_mrd("schedule --years 2 --fluid " + kTwentyYears.string() + " --out " + slow.string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto a = nlohmann::json::parse(slurp(thesis / "summary.json"));
  const auto b = nlohmann::json::parse(slurp(slow / "summary.json"));
  EXPECT_NEAR(b.at("max_settling_time_days").get<double>(), 20.0 * 365.25, 1e-9);
  const double scale = 20.0 * 365.25 / a.at("max_settling_time_days").get<double>();
  EXPECT_NEAR(b.at("threshold_idle_days").get<double>() / a.at("threshold_idle_days").get<double>(), scale,
              1e-6 * scale);
  EXPECT_GT(b.at("fixed_interval_days").get<double>(), a.at("fixed_interval_days").get<double>());
}

// A bad damper or fluid file through each command that takes it: one line
// on stderr naming file, line and field, exit status 2, no output folder.
TEST_F(DamperFluidCli, ABadFileIsOneLineNamingFileLineAndFieldAndWritesNothing) {
  const std::string rec = short_record().string();
  // Line 4 holds the negative rated force; line 8 the solid fraction of 1.
  std::string damper = slurp(kThesisDamper);
  damper.replace(damper.find("force_n = 200000.0"), 18, "force_n = -1.0");
  const fs::path bad_damper = file("bad-damper.toml", damper);
  int damper_line = 1;
  for (std::size_t i = 0; i < damper.find("force_n = -1.0"); ++i) damper_line += damper[i] == '\n';
  const fs::path bad_fluid = file("bad-fluid.toml",
                                  "[fluid]\nname = \"x\"\nsource = \"test\"\nparticle_diameter_m = 5e-6\n"
                                  "solid_density_kg_m3 = 7870.0\nliquid_density_kg_m3 = 820.0\n"
                                  "viscosity_pa_s = 2.0\nsolid_fraction = 1.0\nhindered_exponent = 4.65\n");
  for (const Command& c : commands(rec)) {
    const fs::path dir = out_.path() / "out";
    auto r = run_mrd(c.args + " --damper " + bad_damper.string() + " --out " + dir.string(), scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(bad_damper.string() + ":" + std::to_string(damper_line) +
                         ": rating.force_n: expected a force in [1, 1e+08] N"),
              std::string::npos)
        << c.name << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir)) << c.name;
    if (!c.fluid) continue;
    r = run_mrd(c.args + " --fluid " + bad_fluid.string() + " --out " + dir.string(), scratch_.path());
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(bad_fluid.string() + ":8: fluid.solid_fraction: expected a volume fraction in [0.001, 0.74]"),
              std::string::npos)
        << c.name << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir)) << c.name;
  }
}

TEST_F(DamperFluidCli, MissingFilesAndImpossibleCombinationsAreRefused) {
  const fs::path dir = out_.path() / "out";
  auto r = run_mrd("settle --idle-years 1 --fluid " + (scratch_.path() / "no-such-fluid.toml").string(),
                   scratch_.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("no-such-fluid.toml"), std::string::npos) << r.err;
  r = run_mrd("sim --record none --duration-s 1 --damper " + (scratch_.path() / "no-such-damper.toml").string(),
              scratch_.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("no-such-damper.toml"), std::string::npos) << r.err;
  // Table 5.2 was measured on the thesis damper: its cases refuse another.
  r = run_mrd("sine --thesis-cases --damper " + kThesisDamper.string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--damper: --thesis-cases is the thesis damper's"), std::string::npos) << r.err;
  // A small cylinder and a fluid of 74 % solids: 0.74 · 1e−4 m³ of solids
  // against π(0.02² − 0.005²)·0.1 = 1.178e−4 m³ fits; 0.74 · 2e−4 does not.
  std::string small = slurp(kThesisDamper);
  small = small.substr(0, small.find("[geometry]")) +
          "[geometry]\ninner_diameter_m = 0.04\nshaft_radius_m = 0.005\nfluid_length_m = 0.1\nfluid_volume_m3 = "
          "0.0002\n";
  const fs::path small_damper = file("small.toml", small);
  std::string dense = slurp(kThesisFluid);
  dense.replace(dense.find("solid_fraction = 0.4"), 20, "solid_fraction = 0.74");
  const fs::path dense_fluid = file("dense.toml", dense);
  r = run_mrd("settle --idle-years 1 --damper " + small_damper.string() + " --fluid " + dense_fluid.string(),
              scratch_.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("do not fit in the cylinder of"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
}

}  // namespace
}  // namespace mrd::test
