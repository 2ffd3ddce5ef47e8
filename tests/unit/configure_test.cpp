// mrd configure's derivations against hand calculations from the thesis's
// numbers and the building files' own values: RILD's k and ω_f, the forces
// and currents scaled from the rating, the direction thresholds from the
// stroke sensor's noise, and the board file that carries them reading back.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "firmware/app/board_config.hpp"
#include "host_sim/configure/configure.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/structure/building_file.hpp"

namespace mrd::configure {
namespace {

constexpr double kPi = 3.14159265358979323846;

Inputs thesis_inputs() {
  Inputs in;
  in.board = app::parse_board_config("[board]\nname = \"t\"\n[control]\n[can]\ninterface = \"vcan0\"\n[gpio]\n"
                                     "fitted = false\n",
                                     "t.toml");
  return in;
}

TEST(Configure, TheThesisBuildingAndDamperGiveTheThesisController) {
  const Result r = configure(thesis_inputs());
  const fw::ControllerConfig& c = r.board.controller;
  // Table 6.1: the isolation layer's 3287.3 kN/m (§6.3 rounds it to 3287 kN/m).
  EXPECT_EQ(c.stiffness_n_m, 3287.3e3);
  // `mrd modal` and §6.1: f_1 = 0.2508 Hz.
  EXPECT_NEAR(c.filter_freq_rad_s / (2.0 * kPi), 0.2508, 5e-5);
  EXPECT_EQ(c.loss_factor, 0.8);
  EXPECT_EQ(c.desired_force_limit_n, 400.0e3);
  EXPECT_EQ(c.force_limit_n, 500.0e3);
  EXPECT_EQ(c.force_deadband_n, 2.0e3);
  EXPECT_EQ(c.rated_current_a, 2.5);
  EXPECT_EQ(c.overdrive_current_a, 10.0);
  EXPECT_EQ(c.backdrive_current_a, -10.0);
  EXPECT_DOUBLE_EQ(c.current_band_a, 0.1);
  // σ_x = √((2 µm)² + (8.9142 µm)²/12) = √(10.622e−12) = 3.2591 µm (16 bit
  // over 0.5842 m); β = 1 − e^{−2π·30·0.001} = 0.171811; σ_v = σ_x·β/T·√(2/(2 − β))
  // = 3.2591e−6 · 171.811 · 1.045953 = 5.8569e−4 m/s: v_on 5.857 mm/s, v_off
  // 2.928 mm/s (the thesis's hand-set 6 and 3 mm/s).
  EXPECT_NEAR(c.velocity_on_m_s, 5.8569e-3, 1e-6);
  EXPECT_NEAR(c.velocity_off_m_s, 2.9285e-3, 1e-6);
  EXPECT_NEAR(c.disp_limit_m, 0.300863, 1e-6);  // 1.03 × 0.2921 m
  EXPECT_NEAR(r.board.mixing.max_amplitude_m, 0.075946, 1e-6);   // 0.26 × 0.2921 m
  EXPECT_NEAR(r.board.mixing.max_velocity_m_s, 0.09964, 1e-6);   // 0.4 × 0.2491 m/s
  EXPECT_NEAR(r.board.dead_band_m, 9.7774e-5, 1e-8);             // 30 σ_x
  EXPECT_EQ(fw::validate_config<num::Float32Policy>(c), fw::ConfigError::kNone);
  EXPECT_EQ(fw::validate_config<num::Fixed32Policy>(c), fw::ConfigError::kNone);
}

TEST(Configure, LeadRubberBearingsEnterAtTheirSecantStiffness) {
  Inputs in = thesis_inputs();
  in.building = structure::read_building_file(std::filesystem::path(MRD_BUILDINGS_DIR) / "lead-rubber-7dof.toml");
  in.design_displacement_m = 0.25;
  const Result r = configure(in);
  // The file: element 0 has no springs; 24 bearings of k_p = 0.74 MN/m and
  // Q = 72 kN: k = 24 · (0.74e6 + 72e3/0.25) = 24 · 1.028e6 = 24.672e6 N/m.
  EXPECT_NEAR(r.board.controller.stiffness_n_m, 24.672e6, 1.0);
  // Its fundamental mode with that layer linear: near the rigid-body estimate
  // √(k/Σm)/2π = √(24.672e6/3.53e6)/2π = 0.4208 Hz, a little below it for the
  // superstructure's flexibility.
  const double f1 = r.board.controller.filter_freq_rad_s / (2.0 * kPi);
  EXPECT_LT(f1, 0.4208);
  EXPECT_GT(f1, 0.40);
}

TEST(Configure, ASmallDamperGetsCurrentsAndForcesOfItsOwnSize) {
  Inputs in = thesis_inputs();
  in.damper.rating.current_a = 1.0;
  in.damper.rating.force_n = 1.5e3;
  in.damper.rating.stroke_m = 0.025;
  in.damper.rating.velocity_m_s = 0.2;
  const Result r = configure(in);
  const fw::ControllerConfig& c = r.board.controller;
  EXPECT_EQ(c.overdrive_current_a, 4.0);  // 4 × 1 A, inside the drive's 10 A
  EXPECT_DOUBLE_EQ(c.current_band_a, 0.04);
  EXPECT_EQ(c.desired_force_limit_n, 3.0e3);
  EXPECT_EQ(c.force_deadband_n, 15.0);
  EXPECT_NEAR(r.board.mixing.max_amplitude_m, 0.0065, 1e-12);
}

// The I²t's time constant is the damper's coil's (the thesis coil's assumed
// 20 min when its file gives none), and the board file carries the coil to
// the plant that simulates the board.
TEST(Configure, TheCoilsThermalTimeConstantIsTheDampersCoils) {
  EXPECT_EQ(configure(thesis_inputs()).board.controller.coil_thermal_time_constant_s, 1200.0);
  Inputs in = thesis_inputs();
  in.damper.coil_heat = {12.0, 5.0, 300.0};
  const Result r = configure(in);
  EXPECT_EQ(r.board.controller.coil_thermal_time_constant_s, 300.0);
  EXPECT_EQ(r.board.damper.coil_heat, (physics::CoilHeatParams{12.0, 5.0, 300.0}));
  const app::BoardConfig b = app::parse_board_config(app::board_toml(r.board), "board.toml");
  EXPECT_EQ(b.controller.coil_thermal_time_constant_s, 300.0);
  EXPECT_EQ(b.damper.coil_heat, (physics::CoilHeatParams{12.0, 5.0, 300.0}));
}

TEST(Configure, TheBoardFileCarriesEveryDerivedNumberAndReadsBack) {
  Inputs in = thesis_inputs();
  in.settling.measured_max_settling_time_s = 20.0 * 31557600.0;
  in.fluid_name = "slow";
  const Result r = configure(in);
  const app::BoardConfig b = app::parse_board_config(app::board_toml(r.board), "board.toml");
  EXPECT_EQ(b.controller.stiffness_n_m, r.board.controller.stiffness_n_m);
  EXPECT_EQ(b.controller.filter_freq_rad_s, r.board.controller.filter_freq_rad_s);
  EXPECT_EQ(b.controller.velocity_on_m_s, r.board.controller.velocity_on_m_s);
  EXPECT_EQ(b.settling.measured_max_settling_time_s, 20.0 * 31557600.0);
  EXPECT_EQ(b.fluid_name, "slow");
  const std::string md = configure_markdown(in, r);
  EXPECT_NE(md.find("controller.stiffness_n_m"), std::string::npos);
  EXPECT_NE(md.find("measured maximum settling time"), std::string::npos);
}

TEST(Configure, AFixedPointBoardSaysItsScales) {
  // The thesis's building and damper on a fixed-point board at 1 ms: s_D = 1
  // (0.30 m stroke limit), s_F = 1 (500 kN load cell ≤ 524 288 N), s_I = 1
  // (2.5 A), s_V = 2^−8 m per tick (8 m/s × 1 ms = 8e−3 m ≤ 4 × 3.9e−3 m,
  // not 4 × 1.95e−3 m): one velocity count 2^−36 m per 1 ms = 1.46e−8 m/s.
  Inputs in = thesis_inputs();
  in.board.fixed_point = true;
  const Result r = configure(in);
  const std::string md = configure_markdown(in, r);
  EXPECT_NE(md.find("## Fixed-point scales"), std::string::npos) << md;
  EXPECT_NE(md.find("| s_D, strokes | 2^0 m"), std::string::npos) << md;
  EXPECT_NE(md.find("| s_F, forces | 2^0 N"), std::string::npos) << md;
  EXPECT_NE(md.find("| s_I, currents | 2^0 A"), std::string::npos) << md;
  EXPECT_NE(md.find("| s_V, velocities | 2^-8 m per tick"), std::string::npos) << md;
  EXPECT_NE(md.find("1.46e-08 m/s"), std::string::npos) << md;
  // A float board has none.
  EXPECT_EQ(configure_markdown(thesis_inputs(), configure(thesis_inputs())).find("Fixed-point"), std::string::npos);
}

TEST(Configure, ABuildingWithoutADamperIsRefused) {
  Inputs in = thesis_inputs();
  in.building.dampers.clear();
  EXPECT_THROW((void)configure(in), io::UsageError);
}

}  // namespace
}  // namespace mrd::configure
