// The board file's [controller], [damper] and [fluid] tables: absent, the
// board runs the thesis's controller, damper and fluid (what every board ran
// before they existed); present, each key lands in its field; what the
// control core or physics would refuse is refused at parse time with the
// file, the line and the field.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "firmware/app/board_config.hpp"
#include "firmware/core/controller_config.hpp"
#include "firmware/core/idle_estimator.hpp"
#include "mrd/units.hpp"

namespace mrd::app {
namespace {

constexpr const char* kTablesBase = R"([board]
name = "x"
[control]
numeric = "float"
[can]
interface = "can0"
[gpio]
fitted = false
)";

std::string tables_error_of(const std::string& tables) {
  try {
    parse_board_config(std::string(kTablesBase) + tables, "b.toml");
  } catch (const BoardConfigError& e) {
    return e.what();
  }
  return "";
}

BoardConfig parse_tables(const std::string& tables) { return parse_board_config(std::string(kTablesBase) + tables, "b.toml"); }

TEST(BoardTables, AbsentTheyAreTheThesisControllerDamperAndFluid) {
  const BoardConfig c = parse_tables("");
  const fw::ControllerConfig d = fw::default_controller_config(c.mode, c.period_s());
  const fw::ControllerConfig k = c.controller_config();
  EXPECT_EQ(k.stiffness_n_m, d.stiffness_n_m);
  EXPECT_EQ(k.filter_freq_rad_s, d.filter_freq_rad_s);
  EXPECT_EQ(k.rated_current_a, d.rated_current_a);
  EXPECT_EQ(k.velocity_cutoff_hz, d.velocity_cutoff_hz);
  EXPECT_EQ(k.period_s, 1e-3);
  EXPECT_EQ(c.damper.bingham.fc_b_n, 170.0e3);  // Table 4.1
  EXPECT_EQ(c.damper.rating.current_a, 2.5);
  EXPECT_EQ(c.settling.particle_diameter_m, 5.0e-6);  // Table 5.3
  EXPECT_EQ(c.settling.measured_max_settling_time_s, 0.0);
  const MixingTaskConfig m = c.mixing_task_config();
  EXPECT_EQ(m.estimator.model.nominal_current_a, fw::IdleModelConfig{}.nominal_current_a);
  EXPECT_EQ(m.estimator.model.pr.flow_area_m2, fw::IdleModelConfig{}.pr.flow_area_m2);
}

TEST(BoardTables, ControllerKeysReplaceTheDefaultsOneByOne) {
  const BoardConfig c = parse_tables("[controller]\nstiffness_n_m = 1.5e6\nfilter_freq_rad_s = 3.0\nrated_current_a = 1.0\n"
                              "nominal_current_a = 1.0\nfallback_current_a = 1.0\ncurrent_band_a = 0.04\n"
                              "overdrive_current_a = 4.0\nbackdrive_current_a = -4.0\nstuck_ticks = 300\n");
  const fw::ControllerConfig k = c.controller_config();
  EXPECT_EQ(k.stiffness_n_m, 1.5e6);
  EXPECT_EQ(k.filter_freq_rad_s, 3.0);
  EXPECT_EQ(k.rated_current_a, 1.0);
  EXPECT_EQ(k.overdrive_current_a, 4.0);
  EXPECT_EQ(k.backdrive_current_a, -4.0);
  EXPECT_EQ(k.stuck_ticks, 300u);
  EXPECT_EQ(k.loss_factor, 0.8);  // not given: the thesis's η
  EXPECT_EQ(fw::validate_config<num::Float32Policy>(k), fw::ConfigError::kNone);
}

TEST(BoardTables, CurrentsTheCoreWouldRefuseAreRefusedWithTheirLine) {
  // I_r = 3 A above I_od = 2 A breaks 0 < I_r ≤ I_od (validate_config's current rule).
  const std::string e = tables_error_of("[controller]\noverdrive_current_a = 2.0\nrated_current_a = 3.0\n");
  EXPECT_EQ(e.rfind("b.toml:11: controller.rated_current_a: the control core (float build) refuses these values:", 0),
            0u)
      << e;
  EXPECT_NE(e.find("I_r ≤ I_od"), std::string::npos) << e;
}

TEST(BoardTables, AFilterAboveNyquistIsRefused) {
  // π/T = 3141.6 rad/s at 1 kHz.
  const std::string e = tables_error_of("[controller]\nfilter_freq_rad_s = 4000.0\n");
  EXPECT_EQ(e.rfind("b.toml:10: controller.filter_freq_rad_s: the control core", 0), 0u) << e;
}

TEST(BoardTables, VelocityThresholdsOutOfOrderAreRefused) {
  const std::string e = tables_error_of("[controller]\nvelocity_on_m_s = 0.002\nvelocity_off_m_s = 0.004\n");
  EXPECT_EQ(e.rfind("b.toml:10: controller.velocity_on_m_s:", 0), 0u) << e;
  EXPECT_NE(e.find("v_off ≤ v_on"), std::string::npos) << e;
}

TEST(BoardTables, AStiffnessTheFixedBuildCannotHoldIsRefusedForAFixedBoard) {
  // kη = 9e9 · 0.8 = 7.2e9 N/m needs a force unit of 2^10 N for Gain Q23.8
  // (8.39e6 units), in which the 400 kN desired-force limit spans only
  // 400e3/1024·4096 = 1.6e6 counts of Force Q19.12: too coarse for the fixed
  // build's resolution rule (numeric_formats.hpp), while the float build holds it.
  const std::string fixed = std::string(kTablesBase).replace(std::string(kTablesBase).find("\"float\""), 7, "\"fixed\"");
  try {
    parse_board_config(fixed + "[controller]\nstiffness_n_m = 9.0e9\n", "b.toml");
    ADD_FAILURE() << "accepted";
  } catch (const BoardConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("controller.stiffness_n_m: the control core (fixed build) refuses"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("desired_force_limit_n"), std::string::npos) << e.what();
  }
  EXPECT_EQ(tables_error_of("[controller]\nstiffness_n_m = 9.0e9\n"), "");
}

TEST(BoardTables, UnknownAndMistypedKeysAreRefused) {
  EXPECT_EQ(tables_error_of("[controller]\nstifness_n_m = 1.0\n"), "b.toml:10: controller.stifness_n_m: unknown key");
  EXPECT_EQ(tables_error_of("[damper]\nfc_b_n = \"big\"\n"), "b.toml:10: damper.fc_b_n: expected a number, N");
  EXPECT_EQ(tables_error_of("[fluid]\nsolid_fraction = 0.9\n"),
            "b.toml:10: fluid.solid_fraction: expected 0.0001 … 0.74 (volume fraction; 0.74 is the densest "
            "packing), got 0.9");
  EXPECT_EQ(tables_error_of("[damper]\nlaw = \"magic\"\n"),
            "b.toml:10: damper.law: expected bingham, bingham_tanh or bouc_wen, got 'magic'");
}

TEST(BoardTables, DamperAndFluidInconsistenciesAreRefused) {
  EXPECT_EQ(tables_error_of("[damper]\nweight_slow = 0.7\n"), "b.toml:10: damper.weight_slow: the coil's two weights must sum to 1");
  EXPECT_EQ(tables_error_of("[damper]\ninner_diameter_m = 0.05\nshaft_radius_m = 0.03\n"),
            "b.toml:11: damper.shaft_radius_m: the shaft must be narrower than the bore");
  EXPECT_EQ(tables_error_of("[fluid]\nsolid_density_kg_m3 = 800.0\n"),
            "b.toml:10: fluid.solid_density_kg_m3: the particles must be denser than the carrier liquid (else "
            "nothing settles, Eq. 5.1)");
  EXPECT_EQ(tables_error_of("[damper]\nlaw = \"bouc_wen\"\n").rfind("b.toml:", 0), 0u);
}

// A fluid that takes 20 years to settle fully (a measured T_max): the
// estimator's SQ after τ = 1 year is τ/T_max = 0.05 (Eq. 5.5), and a_PR
// (Eq. 5.6 with Table 5.6's a = 1, b = 0.10, c = 7) is
// 0.10 + 0.90·exp(−7·0.05) = 0.10 + 0.90·0.704688 = 0.734219.
TEST(BoardTables, AMeasuredSettlingTimeDrivesTheEstimator) {
  const BoardConfig c = parse_tables("[fluid]\nname = \"slow\"\nmax_settling_time_s = 631152000.0\n");  // 20 × 365.25 d
  EXPECT_EQ(c.fluid_name, "slow");
  fw::SettlingModel m;
  ASSERT_TRUE(m.init(c.mixing_task_config().estimator.model));
  EXPECT_DOUBLE_EQ(m.max_settling_time_s(), 631152000.0);
  const double year_s = 31557600.0;
  EXPECT_NEAR(m.sq_of_idle(year_s), 0.05, 1e-12);
  EXPECT_NEAR(m.pr_of_idle(year_s), 0.734219, 1e-6);
}

TEST(BoardTables, DamperKeysReachTheEstimator) {
  const BoardConfig c = parse_tables("[damper]\nname = \"lab\"\nfc_a_n = 40.0\nfc_b_n = 1200.0\nrated_current_a = 1.0\n"
                              "flow_area_m2 = 0.0005\n");
  const MixingTaskConfig m = c.mixing_task_config();
  EXPECT_EQ(c.damper_name, "lab");
  EXPECT_EQ(m.estimator.model.bingham.fc_b_n, 1200.0);
  EXPECT_EQ(m.estimator.model.nominal_current_a, 1.0);
  EXPECT_EQ(m.estimator.model.pr.flow_area_m2, 0.0005);
}

// A calibrated damper's bends of its Bingham law (physics::LawShape)
// ride in [damper] as `mrd configure` writes them, read back exactly; the
// keys of the Bingham laws are refused on a bouc_wen damper, and a viscous
// exponent needs its reference velocity.
TEST(BoardTables, ACalibratedShapeReadsBackAndIsRefusedWhereItCannotAct) {
  BoardConfig c = parse_tables("[damper]\nlaw = \"bingham_tanh\"\n");
  c.damper.shape.yield_current_exponent = 1.0 / 3.0 + 1.0;
  c.damper.shape.viscous_current_exponent = 0.7;
  c.damper.shape.viscous_exponent = 0.55;
  c.damper.shape.viscous_ref_m_s = 0.03;
  c.damper.shape.stiffness_n_m = 12000.0;
  c.damper.shape.transition_time_s = 0.004;
  c.damper.shape.lost_motion_m_per_n = 2.241e-07;
  c.damper.shape.lost_motion_share = 1.0;
  c.damper.shape.lost_motion_band_m_s = 0.015;
  const BoardConfig r = parse_board_config(board_toml(c), "w.toml");
  EXPECT_TRUE(r.damper.shape == c.damper.shape);
  EXPECT_EQ(board_toml(r), board_toml(c));
  // Absent, the shape bends nothing and the writer writes none of its keys.
  EXPECT_FALSE(parse_tables("").damper.shape.bends());
  const std::string plain = board_toml(parse_tables(""));
  for (const char* key : {"current_exponent", "viscous_exponent", "viscous_ref_m_s", "bingham_stiffness_n_m", "transition_time_s",
                          "lost_motion"})
    EXPECT_EQ(plain.find(key), std::string::npos) << key;
  EXPECT_EQ(tables_error_of("[damper]\nlaw = \"bouc_wen\"\nbouc_wen_yield_disp_m = 0.001\nbingham_stiffness_n_m = 10.0\n"),
            "b.toml:12: damper.bingham_stiffness_n_m: acts on the bingham and bingham_tanh laws only (the bouc_wen law's "
            "spring is bouc_wen_stiffness_n_m)");
  EXPECT_EQ(tables_error_of("[damper]\nviscous_exponent = 0.5\n"),
            "b.toml:10: damper.viscous_exponent: a viscous exponent needs viscous_ref_m_s > 0 m/s (the velocity at "
            "which c0 is the slope)");
  EXPECT_EQ(tables_error_of("[damper]\nyield_current_exponent = 20.0\n").rfind("b.toml:10: damper.yield_current_exponent: expected", 0), 0u);
}

// The damper's coil heating (physics::CoilHeatParams): read back as written,
// absent the thesis coil's (and not written), refused out of range.
TEST(BoardTables, TheCoilsHeatingReadsBack) {
  BoardConfig c = parse_tables("");
  EXPECT_EQ(c.damper.coil_heat, physics::CoilHeatParams{});
  EXPECT_EQ(board_toml(c).find("coil_thermal_resistance_k_w"), std::string::npos);
  c.damper.coil_heat = {12.0, 5.0, 900.0};
  const BoardConfig r = parse_board_config(board_toml(c), "w.toml");
  EXPECT_EQ(r.damper.coil_heat, (physics::CoilHeatParams{12.0, 5.0, 900.0}));
  EXPECT_EQ(board_toml(r), board_toml(c));
  EXPECT_EQ(tables_error_of("[damper]\ncoil_thermal_time_constant_s = 0.5\n")
                .rfind("b.toml:10: damper.coil_thermal_time_constant_s: expected", 0),
            0u);
  EXPECT_EQ(tables_error_of("[damper]\ncoil_resistance_ohm = -1.0\n").rfind("b.toml:10: damper.coil_resistance_ohm: expected", 0),
            0u);
}

// A coil of 1 H at 1 A and 0.3 H at 2 A: its floor is its own L(2 A), below
// the 0.5 H assumed for a coil that states none (physics::coil_inductance).
TEST(BoardTables, TheCoilsInductanceReadsBack) {
  BoardConfig c = parse_tables("");
  EXPECT_EQ(c.damper.coil_inductance, physics::CoilInductance{});
  EXPECT_EQ(board_toml(c).find("coil_inductance"), std::string::npos);
  c.damper.coil_inductance = physics::coil_inductance(1.0, 0.3);
  const BoardConfig r = parse_board_config(board_toml(c), "w.toml");
  EXPECT_EQ(r.damper.coil_inductance, (physics::CoilInductance{1.0, 0.3, 0.3}));
  EXPECT_EQ(board_toml(r), board_toml(c));
  EXPECT_EQ(tables_error_of("[damper]\ncoil_inductance_1a_h = 2.0\n")
                .rfind("b.toml:10: damper.coil_inductance_2a_h: missing key", 0),
            0u);
  EXPECT_EQ(tables_error_of("[damper]\ncoil_inductance_1a_h = 2.0\ncoil_inductance_2a_h = 3.0\n")
                .rfind("b.toml:11: damper.coil_inductance_2a_h: expected at most coil_inductance_1a_h", 0),
            0u);
  EXPECT_EQ(tables_error_of("[damper]\ncoil_inductance_1a_h = 0.0\ncoil_inductance_2a_h = 0.0\n")
                .rfind("b.toml:10: damper.coil_inductance_1a_h: expected", 0),
            0u);
}

// [drive]: the drive the board commands, read back exactly; every key
// required; and the controller held within it (the default ±10 A command
// range over a ±5 A drive is refused at the drive's key, a given
// [controller] key at its own line).
TEST(BoardTables, TheDriveReadsBackAndHoldsTheController) {
  BoardConfig c = parse_tables("");
  EXPECT_FALSE(c.drive.has_value());
  EXPECT_EQ(board_toml(c).find("[drive]"), std::string::npos);
  BoardDrive d;
  d.name = "bench";
  d.bus_v = 24.0;
  d.command_range_v = 10.0;
  d.volts_per_amp = 0.5;  // ±20 A
  d.continuous_current_a = 20.0;
  d.peak_current_a = 40.0;
  d.peak_time_s = 1.5;
  d.loop_bandwidth_rad_s = 300.0;
  d.loop_period_s = 5e-5;
  c.drive = d;
  const BoardConfig r = parse_board_config(board_toml(c), "w.toml");
  ASSERT_TRUE(r.drive.has_value());
  EXPECT_EQ(r.drive->name, "bench");
  EXPECT_EQ(r.drive->volts_per_amp, 0.5);
  EXPECT_EQ(r.drive->loop_period_s, 5e-5);
  EXPECT_EQ(r.drive->command_limit_a(), 20.0);
  EXPECT_EQ(board_toml(r), board_toml(c));
  const std::string full =
      "[drive]\nname = \"small\"\nbus_v = 24.0\ncommand_range_v = 5.0\nvolts_per_amp = 1.0\n"
      "continuous_current_a = 15.0\npeak_current_a = 30.0\npeak_time_s = 2.0\nloop_bandwidth_rad_s = 200.0\n"
      "loop_period_s = 0.0001\n";
  // The default controller commands ±10 A: more than the ±5 A drive (command_range_v on line 12).
  EXPECT_EQ(tables_error_of(full).rfind("b.toml:12: controller.command_limit_a: 10 A exceeds the [drive]'s command "
                                        "range (command_range_v / volts_per_amp) of 5 A",
                                        0),
            0u)
      << tables_error_of(full);
  const std::string held = "[controller]\ncommand_limit_a = 5.0\noverdrive_current_a = 5.0\n"
                           "backdrive_current_a = -5.0\n\n" + full;
  EXPECT_EQ(tables_error_of(held), "");
  std::string missing = full;
  missing.erase(missing.find("peak_time_s = 2.0\n"), 18);
  EXPECT_EQ(tables_error_of(missing).rfind("b.toml:9: drive.peak_time_s: missing key", 0), 0u) << tables_error_of(missing);
  std::string weak = held;
  weak.replace(weak.find("peak_current_a = 30.0"), 21, "peak_current_a = 10.0");
  EXPECT_NE(tables_error_of(weak).find("drive.peak_current_a: expected at least continuous_current_a"),
            std::string::npos)
      << tables_error_of(weak);
}

}  // namespace
}  // namespace mrd::app

namespace mrd::app {
namespace {

void expect_same_board(const BoardConfig& a, const BoardConfig& b) {
  // Every table through its own text: the writer's output of both must match,
  // and the fields a program uses must be equal.
  EXPECT_EQ(board_toml(a), board_toml(b));
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.can_interface, b.can_interface);
  EXPECT_EQ(a.gpio_chip, b.gpio_chip);
  EXPECT_EQ(a.drive_enable.offset, b.drive_enable.offset);
  EXPECT_EQ(a.drive_enable.name, b.drive_enable.name);
  EXPECT_EQ(a.state_path, b.state_path);
  EXPECT_EQ(a.mixing.max_amplitude_m, b.mixing.max_amplitude_m);
  EXPECT_EQ(a.controller.stiffness_n_m, b.controller.stiffness_n_m);
  EXPECT_EQ(a.controller.filter_freq_rad_s, b.controller.filter_freq_rad_s);
  EXPECT_EQ(a.controller.velocity_cutoff_hz, b.controller.velocity_cutoff_hz);
  EXPECT_EQ(a.damper.bingham.c0_b_ns_m, b.damper.bingham.c0_b_ns_m);
  EXPECT_EQ(a.damper.coil.tau_fast_s, b.damper.coil.tau_fast_s);
  EXPECT_EQ(a.settling.viscosity_pa_s, b.settling.viscosity_pa_s);
  EXPECT_EQ(a.settling.measured_max_settling_time_s, b.settling.measured_max_settling_time_s);
  EXPECT_EQ(a.damper.pr.c_rise, b.damper.pr.c_rise);
}

TEST(BoardWriter, EveryRepositoryBoardReadsBackFromItsWrittenText) {
  for (const char* name : {"sim", "emulated-arm64", "rpi-cm4-mcp2515"}) {
    SCOPED_TRACE(name);
    const std::string path = std::string(MRD_BOARDS_DIR) + "/" + name + "/board.toml";
    std::string text;
    {
      std::FILE* f = std::fopen(path.c_str(), "rb");
      ASSERT_NE(f, nullptr);
      char buf[4096];
      std::size_t n = 0;
      while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
      std::fclose(f);
    }
    const BoardConfig c = parse_board_config(text, path);
    expect_same_board(parse_board_config(board_toml(c, "written by a test\nsecond line"), "w.toml"), c);
  }
}

TEST(BoardWriter, ValuesThatNeedAllDigitsReadBackExactly) {
  BoardConfig c = parse_tables("");
  c.controller.stiffness_n_m = 3287.3e3 + 1.0 / 3.0;
  c.controller.filter_freq_rad_s = 2.0 * 3.141592653589793 * 0.25083;
  c.damper.bingham.c0_b_ns_m = 0.1 + 0.2;
  c.damper.coil.tau_fast_s = 1e-9;
  c.damper.law = physics::ForceLaw::kBoucWen;
  c.damper.bouc_wen.yield_disp_m = 0.0012345678901234;
  c.settling.viscosity_pa_s = 1.0 / 7.0;
  c.settling.measured_max_settling_time_s = 631152000.0;
  c.damper.pr.c_rise = 3.65;
  c.damper_name = "lab \"damper\" µ";
  const BoardConfig r = parse_board_config(board_toml(c), "w.toml");
  expect_same_board(r, c);
  EXPECT_EQ(r.damper.bouc_wen.yield_disp_m, c.damper.bouc_wen.yield_disp_m);
  EXPECT_EQ(r.damper_name, "lab \"damper\" ??");  // board files are ASCII outside comments: µ is two bytes
}

}  // namespace
}  // namespace mrd::app
