// `mrd rths`: the files and fields it writes, the benchmark's published
// acceptance on the nominal plant over 10 s of El Centro, and bad input
// (exit status 2, one line naming the option, or the file, line and field),
// and a folder that is not mrd's is never replaced.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"

namespace mrd::test {
namespace {
namespace fs = std::filesystem;

const std::string kElCentroRthsCli = std::string(MRD_SHARED_DIR) + "/ground_motions/elcentro_ns.csv";

class RthsCli : public ::testing::Test {
 protected:
  TempDir scratch_;
  TempDir out_;
};

TEST_F(RthsCli, WritesSummaryCsvAndCriteria) {
  const fs::path out = out_.path() / "run";
  const auto r = run_mrd("rths --record " + kElCentroRthsCli + " --duration-s 10 --out " + out.string(),
                         scratch_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["compensator"], "adaptive");
  EXPECT_EQ(j["rate_hz"], 4096.0);
  // The published acceptance: J2 <= 3 %, J4 <= 5 %.
  EXPECT_LE(j["criteria"]["j2_tracking_rms_pct"].get<double>(), 3.0);
  EXPECT_LE(j["criteria"]["j4_floor1_rms_pct"].get<double>(), 5.0);
  // σ of the displacement noise: √(6.25e-14 m²/Hz · 4096 Hz) = 16.0 µm.
  EXPECT_NEAR(j["laboratory"]["displacement_noise_sigma_m"].get<double>(), 16.0e-6, 1e-9);
  EXPECT_EQ(j["coefficient_names"].size(), 3u);
  const std::string csv = slurp(out / "tracking.csv");
  EXPECT_EQ(csv.rfind("time_s,target_m,measured_m,command_m,force_n,floor_1_m,floor_2_m,floor_3_m,"
                      "reference_floor_1_m,",
                      0),
            0u);
  EXPECT_EQ(slurp(out / "coefficients.csv").rfind("time_s,a0,a1_s,a2_s2\n", 0), 0u);
}

TEST_F(RthsCli, RefusesAnUnknownCompensator) {
  const auto r = run_mrd("rths --record " + kElCentroRthsCli + " --compensator smith --out " +
                             (out_.path() / "x").string(),
                         scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--compensator: expected none, sample, polynomial, adaptive or model, got 'smith'"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out_.path() / "x"));
}

TEST_F(RthsCli, NamesTheRecordsLineAndField) {
  const fs::path rec = scratch_.path() / "bad.csv";
  std::ofstream(rec) << "time_s,accel_m_s2\n0.00,0\n0.02,abc\n";
  const auto r = run_mrd("rths --record " + rec.string() + " --out " + (out_.path() / "x").string(), scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.csv:3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("accel_m_s2"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out_.path() / "x"));
}

TEST_F(RthsCli, RefusesCaseWithABuildingAndABadSpecimenDof) {
  auto r = run_mrd("rths --record " + kElCentroRthsCli + " --case 2 --building " + std::string(MRD_BUILDINGS_DIR) +
                       "/silva-2020-3dof.toml --out " + (out_.path() / "x").string(),
                   scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--case: not allowed with --building"), std::string::npos) << r.err;
  r = run_mrd("rths --record " + kElCentroRthsCli + " --specimen-dof 4 --out " + (out_.path() / "x").string(),
              scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--specimen-dof: expected 1..3"), std::string::npos) << r.err;
}

TEST_F(RthsCli, NeverReplacesAFolderThatIsNotMrds) {
  const fs::path mine = out_.path() / "mine";
  fs::create_directories(mine);
  std::ofstream(mine / "notes.txt") << "keep me\n";
  const auto r = run_mrd("rths --record " + kElCentroRthsCli + " --duration-s 1 --out " + mine.string(),
                         scratch_.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(slurp(mine / "notes.txt"), "keep me\n");
  EXPECT_FALSE(fs::exists(mine / "summary.json"));
}

}  // namespace
}  // namespace mrd::test
